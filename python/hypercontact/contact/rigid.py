"""Rigid obstacles as contact geometry: the slave points of one surface of the
body against an analytic obstacle (plane, box, cylinder, sphere) that moves rigidly along
the load path (translation, and rotation about an axis).

Nodal integration (the paper): one slave point per slave node with the
node's area (surface_mesh.nodal_areas: ∫_Γ N_i dA, or for 6-node triangles
the split-facet weights), evaluated on the rank that owns the node, adding
into its own dofs. Gauss-point integration: the Gauss points of the slave
facets (surface_mesh.facet_gauss_points), each x_p = Σ_a M_a x_a adding into
its facet's nodes, on the rank that owns the facet's cell. Either stays
inside the volume pattern and adds into the process-local residual array."""
import numpy as np
from mpi4py import MPI

from .. import _cpp
from .. import _dolfinx as dfx
from ..scene.contact import rotation_pivot
from ..scene.path import rotation_matrix
from .surface_mesh import (facet_gauss_points, facet_rule, nodal_areas, six_node_triangles, surface_facet_nodes,
                           surface_facets)


def make_obstacle(kind, where, pose):
    """The C++ obstacle ``kind`` at its rest position ``where`` in ``pose``
    (its points mapped by the pose, its directions turned by its rotation)."""
    if kind == "plane":
        return _cpp.RigidPlane(pose.point(where["point"]), pose.direction(where["normal"]))
    if kind == "box":  # the scene allows no rotation of a box: it stays axis-aligned
        return _cpp.RigidBox(pose.point(where["lo"]), pose.point(where["hi"]), float(where.get("edge_radius", 0.0)),
                             where.get("edge_profile", "circular") == "blended")
    if kind == "cylinder":
        return _cpp.RigidCylinder(pose.point(where["point"]), pose.direction(where["axis"]),
                                  float(where["radius"]), bool(where.get("inside", False)))
    if kind == "sphere":
        return _cpp.RigidSphere(pose.point(where["center"]), float(where["radius"]))
    raise ValueError(f"unknown obstacle {kind!r}")


class Pose:
    """A rigid motion: x ↦ pivot + t + R (x − pivot), R the rotation by
    ``angle`` about ``axis`` (through the pivot at rest). Without rotation
    a point is just moved by t."""

    def __init__(self, translation, angle=0.0, axis=None, pivot=None):
        self.t = np.asarray(translation, dtype=float)
        self.angle = float(angle)
        self.R = None if self.angle == 0.0 else rotation_matrix(axis, self.angle)
        self.pivot = None if pivot is None else np.asarray(pivot, dtype=float)

    def point(self, x):
        x = np.asarray(x, dtype=float)
        if self.R is None:
            return x + self.t
        return self.pivot + self.t + (x - self.pivot) @ self.R.T

    def direction(self, d):
        d = np.asarray(d, dtype=float)
        return d if self.R is None else self.R @ d

    def relative_to(self, earlier, x):
        """Points x (rows) carried with the obstacle from ``earlier`` to this pose."""
        if self.R is None and earlier.R is None:
            return x + (self.t - earlier.t)
        R0 = np.eye(3) if earlier.R is None else earlier.R
        R1 = np.eye(3) if self.R is None else self.R
        body = (x - (self.pivot + earlier.t)) @ R0  # R0ᵀ (x − pivot − t0), row-wise
        return self.pivot + self.t + body @ R1.T

    def state(self):
        return {"translation": self.t.tolist(), "angle": self.angle}


def rigid_integration(integration, V):
    """"nodal" or "gauss": "auto" is nodal (the paper) except on the 6-node
    triangles of quadratic tetrahedra, whose nodal weights are positive but do
    not integrate a uniform pressure consistently (the patch test is off by
    1.7 % in force and 0.2–1.3 × in nodal pressure): Gauss points there."""
    if integration != "auto":
        return integration
    return "gauss" if six_node_triangles(V) else "nodal"


class RigidObstacle:
    """Slave nodes of one surface and the obstacle they press against."""

    #: adds into the process-local residual array
    assembly = "local"

    def __init__(self, spec, V, facet_tags, tag, constrained, u_dofs=None):
        """``constrained``: mask of the unknown's process-local dofs; ``u_dofs``:
        where V's dofs sit in the unknown (the mixed formulation), None if the
        unknown is the displacement. ``spec["integration"]``: "nodal" (a point
        per slave node, its area), "gauss" (the Gauss points of the slave
        facets, each spread over its facet's nodes) or "auto"
        (:func:`rigid_integration`)."""
        self.kind = spec["obstacle"]
        self.rest = {k: spec[k] for k in ("point", "normal", "lo", "hi", "axis", "radius", "center", "inside",
                                          "edge_radius", "edge_profile")
                     if k in spec}
        self.axis, self.pivot = rotation_pivot(spec)
        self.comm = V.mesh.comm
        gid = dfx.global_node_indices(V).astype(np.int64)
        X_nodes = dfx.node_coordinates(V)
        self.integration = rigid_integration(spec.get("integration", "auto"), V)
        if self.integration == "nodal":
            area = nodal_areas(V, facet_tags, tag)
            self.nodes = np.flatnonzero(area > 0.0).astype(np.int32)
            self.area = area[self.nodes].copy()
            self.point_nodes, self.point_weights = self.nodes[:, None], None
            self.X = np.ascontiguousarray(X_nodes[self.nodes])
            self.ids = gid[self.nodes]
        elif self.integration == "facet":
            # a constraint per facet on its mean gap: the kernel sees the Gauss points (kernel_*), the
            # results one point per facet at its centroid with its area
            facets = (surface_facet_nodes if dfx.degree_of(V) == 2 else surface_facets)(V, facet_tags, tag)
            gauss_nodes, self.kernel_weights, self.kernel_area = facet_gauss_points(facets, X_nodes)
            self.points_per_facet = len(facet_rule(facets.shape[1])[1])
            self.point_nodes, self.point_weights = facets.astype(np.int32), None
            self.area = self.kernel_area.reshape(len(facets), self.points_per_facet).sum(axis=1)
            self.nodes = None
            # the Gauss points' reference coordinates and their nodes' dofs in V and in the unknown
            self._gauss_X = np.einsum("pa,pak->pk", self.kernel_weights, X_nodes[gauss_nodes])
            self._gauss_v_dofs = 3 * gauss_nodes[:, :, None] + np.arange(3)
            self._gauss_dofs = self._gauss_v_dofs if u_dofs is None else u_dofs[self._gauss_v_dofs]
            self.X = self._centroids(self._gauss_X)
            self.ids = 7919 * gid[facets[:, 0]] + 31 * gid[facets[:, 1]]
        else:
            facets = (surface_facet_nodes if dfx.degree_of(V) == 2 else surface_facets)(V, facet_tags, tag)
            self.point_nodes, self.point_weights, self.area = facet_gauss_points(facets, X_nodes)
            self.nodes = None  # no value per node for the results
            self.X = np.ascontiguousarray(np.einsum("pa,pak->pk", self.point_weights, X_nodes[self.point_nodes]))
            q = np.tile(np.arange(len(facet_rule(facets.shape[1])[1])), len(facets))
            # an id per point for the active-set checksums: its facet's first two nodes and its index
            self.ids = 7919 * gid[self.point_nodes[:, 0]] + 31 * gid[self.point_nodes[:, 1]] + q
        if self.integration != "facet":  # each point its own constraint
            self.points_per_facet, self.kernel_weights, self.kernel_area = 0, self.point_weights, self.area
        self.point_area = self.area
        index = 3 * self.point_nodes[:, :, None].astype(np.int64) + np.arange(3)  # (n, k, 3): V's dofs
        if u_dofs is not None:
            index = u_dofs[index]
        self._index = index.astype(np.int32)  # the points' nodes' dofs in the unknown
        self._num_v_dofs = 3 * dfx.num_local_nodes(V)
        dofs = self._index.reshape(len(self.area), 3 * self.point_nodes.shape[1]).copy()
        dofs[constrained[dofs]] = -1  # PETSc skips negative indices: Dirichlet rows stay exact
        self.dofs = np.ascontiguousarray(dofs)
        self.num_points = self.comm.allreduce(len(self.area), op=MPI.SUM)
        self.load_factor = 0.0
        self.set_pose(np.zeros(3))

    def set_load_factor(self, load_factor):
        """The phase's parameter s (the obstacle's place is set by :meth:`set_pose`)."""
        self.load_factor = load_factor

    def set_pose(self, translation, angle=0.0):
        """Move the obstacle to ``translation`` from its place in the scene, turned by ``angle``."""
        self.pose = Pose(translation, angle, self.axis, self.pivot)
        self.obstacle = make_obstacle(self.kind, self.rest, self.pose)

    def displacement(self):
        """How far the obstacle has moved from its place in the scene: |t|."""
        return float(np.linalg.norm(self.pose.t))

    def _centroids(self, gauss):
        """Facet integration: each facet's area-weighted mean of its Gauss points."""
        Q = self.points_per_facet
        w = self.kernel_area.reshape(len(self.area), Q)
        return np.ascontiguousarray(np.einsum("fq,fqk->fk", w, gauss.reshape(len(self.area), Q, 3))
                                    / self.area[:, None])

    def coordinates(self, u):
        """Current coordinates of this rank's slave nodes (the Gauss points, facet integration);
        u the displacement or (mixed formulation) the unknown it is part of."""
        values = u.x.array
        if self.integration == "facet":
            dofs = self._gauss_v_dofs if values.size == self._num_v_dofs else self._gauss_dofs
            return np.ascontiguousarray(self._gauss_X + np.einsum("pa,pak->pk", self.kernel_weights, values[dofs]))
        if self.point_weights is None:
            if values.size == self._num_v_dofs:
                return np.ascontiguousarray(self.X + values.reshape(-1, 3)[self.nodes])
            return np.ascontiguousarray(self.X + values[self._index[:, 0]])
        index = self._index if values.size != self._num_v_dofs else \
            3 * self.point_nodes[:, :, None] + np.arange(3)
        return np.ascontiguousarray(self.X + np.einsum("pa,pak->pk", self.point_weights, values[index]))

    def point_coordinates(self, u):
        """(reference, current) coordinates of this rank's slave points (the facets' centroids,
        facet integration)."""
        if self.integration == "facet":
            return self.X, self._centroids(self.coordinates(u))
        return self.X, self.coordinates(u)

    def field_nodes(self):
        """Process-local node of each slave point (the results' vertex fields)."""
        return self.nodes

    def update_pairing(self, u, fresh):
        """An analytic obstacle needs no search: the pattern never changes."""
        return False

    def active(self, state, augmented):
        """Slave points that carry a pressure: closed, or in the smoothing band with a pressure."""
        return np.flatnonzero((state.gap <= 0.0) | (state.pressure > 0.0))

    def closed(self, state, augmented):
        """Slave points the frictionless status calls closed (g ≤ 0)."""
        return np.flatnonzero(state.gap <= 0.0)

    def max_penetration(self, state):
        """Largest penetration ⟨−g⟩ over all slave nodes (all ranks)."""
        local = float(max(0.0, -state.gap.min())) if len(state.gap) else 0.0
        return self.comm.allreduce(local, op=MPI.MAX)


class RigidFrictionHistory:
    """Per slave node, the last converged step's position ξ (its *anchor*, a
    point of the obstacle: carried with the obstacle's rigid motion —
    translation and rotation — since then) and tangential traction t."""

    def __init__(self, geometry):
        self.geometry = geometry
        self.positions = geometry.X.copy()
        self.traction = np.zeros_like(geometry.X)
        self.lam_committed = 0.0
        self.pose_committed = geometry.pose

    def anchors(self):
        """ξ carried with the obstacle from its pose at the last commit to its pose now."""
        return np.ascontiguousarray(self.geometry.pose.relative_to(self.pose_committed, self.positions))

    def store(self, state, x):
        self.traction = np.ascontiguousarray(state.traction)
        self.positions = np.ascontiguousarray(x).copy()
        self.lam_committed = self.geometry.load_factor
        self.pose_committed = self.geometry.pose

    def forget(self, x):
        """No traction carried over; each node's anchor is where it is (x)."""
        self.traction = np.zeros_like(self.traction)
        self.positions = np.ascontiguousarray(x).copy()
        self.lam_committed = self.geometry.load_factor
        self.pose_committed = self.geometry.pose

    def pattern_nodes(self):
        return None

    def state_dict(self):
        return ({"lam_committed": self.lam_committed, "pose_committed": self.pose_committed.state()},
                {"anchor": self.positions, "traction": self.traction})

    def load_state_dict(self, meta, arrays):
        self.lam_committed = meta["lam_committed"]
        pose = meta["pose_committed"]
        self.pose_committed = Pose(pose["translation"], pose["angle"], self.geometry.axis, self.geometry.pivot)
        self.positions = np.ascontiguousarray(arrays["anchor"], dtype=float)
        self.traction = np.ascontiguousarray(arrays["traction"], dtype=float)
