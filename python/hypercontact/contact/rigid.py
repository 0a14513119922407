"""Rigid obstacles as contact geometry: the slave nodes of one surface of the
body against an analytic obstacle (plane, box, cylinder, sphere) that moves rigidly along
the load path (translation, and rotation about an axis).

Nodal integration (the paper): one slave point per slave node with the
node's area A_i = ∫_Γ N_i dA (reference configuration). Each node is
evaluated on the rank that owns it and adds into the process-local residual
array (its own dofs only, inside the volume pattern)."""
import numpy as np
from mpi4py import MPI

from .. import _cpp
from .. import _dolfinx as dfx
from ..scene.contact import rotation_pivot
from ..scene.path import rotation_matrix
from .surface_mesh import nodal_areas


def make_obstacle(kind, where, pose):
    """The C++ obstacle ``kind`` at its rest position ``where`` in ``pose``
    (its points mapped by the pose, its directions turned by its rotation)."""
    if kind == "plane":
        return _cpp.RigidPlane(pose.point(where["point"]), pose.direction(where["normal"]))
    if kind == "box":  # the scene allows no rotation of a box: it stays axis-aligned
        return _cpp.RigidBox(pose.point(where["lo"]), pose.point(where["hi"]))
    if kind == "cylinder":
        return _cpp.RigidCylinder(pose.point(where["point"]), pose.direction(where["axis"]),
                                  float(where["radius"]))
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


class RigidObstacle:
    """Slave nodes of one surface and the obstacle they press against."""

    #: adds into the process-local residual array
    assembly = "local"

    def __init__(self, spec, V, facet_tags, tag, constrained):
        self.kind = spec["obstacle"]
        self.rest = {k: spec[k] for k in ("point", "normal", "lo", "hi", "axis", "radius", "center") if k in spec}
        self.axis, self.pivot = rotation_pivot(spec)
        self.comm = V.mesh.comm
        area = nodal_areas(V, facet_tags, tag)
        self.nodes = np.flatnonzero(area > 0.0).astype(np.int32)
        self.area = area[self.nodes].copy()
        self.point_area = self.area
        dofs = (3 * self.nodes[:, None] + np.arange(3, dtype=np.int32)).astype(np.int32)
        dofs[constrained[dofs]] = -1  # PETSc skips negative indices: Dirichlet rows stay exact
        self.dofs = np.ascontiguousarray(dofs)
        self.X = np.ascontiguousarray(dfx.node_coordinates(V)[self.nodes])
        self.ids = dfx.global_node_indices(V).astype(np.int64)[self.nodes]
        self.scratch_size = 3 * dfx.num_local_nodes(V)
        self.num_points = self.comm.allreduce(len(self.nodes), op=MPI.SUM)
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

    def coordinates(self, u):
        """Current coordinates of this rank's slave nodes."""
        return np.ascontiguousarray(self.X + u.x.array.reshape(-1, 3)[self.nodes])

    def point_coordinates(self, u):
        """(reference, current) coordinates of this rank's slave points."""
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
