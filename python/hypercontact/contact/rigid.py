"""Rigid obstacles as contact geometry: the slave nodes of one surface of the
body against an analytic obstacle (plane, box, cylinder, sphere) that translates with
the load factor λ.

Nodal integration (the paper): one slave point per slave node with the
node's area A_i = ∫_Γ N_i dA (reference configuration). Each node is
evaluated on the rank that owns it and adds into the process-local residual
array (its own dofs only, inside the volume pattern)."""
import numpy as np
from mpi4py import MPI

from .. import _cpp
from .. import _dolfinx as dfx
from .surface_mesh import nodal_areas


def make_obstacle(kind, where, shift):
    """The C++ obstacle ``kind`` at its rest position ``where`` moved by ``shift``."""
    if kind == "plane":
        return _cpp.RigidPlane(np.asarray(where["point"]) + shift, np.asarray(where["normal"]))
    if kind == "box":
        return _cpp.RigidBox(np.asarray(where["lo"]) + shift, np.asarray(where["hi"]) + shift)
    if kind == "cylinder":
        return _cpp.RigidCylinder(np.asarray(where["point"]) + shift, np.asarray(where["axis"]),
                                  float(where["radius"]))
    if kind == "sphere":
        return _cpp.RigidSphere(np.asarray(where["center"]) + shift, float(where["radius"]))
    raise ValueError(f"unknown obstacle {kind!r}")


class RigidObstacle:
    """Slave nodes of one surface and the obstacle they press against."""

    #: adds into the process-local residual array
    assembly = "local"

    def __init__(self, spec, V, facet_tags, tag, constrained):
        self.kind = spec["obstacle"]
        self.rest = {k: spec[k] for k in ("point", "normal", "lo", "hi", "axis", "radius", "center") if k in spec}
        self.motion = np.asarray(spec["motion"], dtype=float)
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
        self.set_load_factor(0.0)

    def set_load_factor(self, load_factor):
        self.load_factor = load_factor
        self.obstacle = make_obstacle(self.kind, self.rest, load_factor * self.motion)

    def move(self, motion):
        """Start a new phase: where the obstacle is now becomes its rest
        position (λ = 0) and it moves by ``motion`` as λ goes 0 → 1."""
        shift = self.load_factor * self.motion
        for key in ("point", "lo", "hi", "center"):
            if key in self.rest:
                self.rest[key] = [float(v) for v in np.asarray(self.rest[key], dtype=float) + shift]
        self.motion = np.asarray(motion, dtype=float)
        self.set_load_factor(0.0)

    def displacement(self):
        """How far the obstacle has moved: λ |motion|."""
        return self.load_factor * float(np.linalg.norm(self.motion))

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
    """Per slave node, the last converged step's position ξ (its *anchor*,
    carried with the obstacle's translation since then) and tangential
    traction t."""

    def __init__(self, geometry):
        self.geometry = geometry
        self.positions = geometry.X.copy()
        self.traction = np.zeros_like(geometry.X)
        self.lam_committed = 0.0

    def anchors(self, load_factor):
        """ξ moved with the obstacle from the last commit to λ."""
        return np.ascontiguousarray(self.positions + (load_factor - self.lam_committed) * self.geometry.motion)

    def store(self, state, x):
        self.traction = np.ascontiguousarray(state.traction)
        self.positions = np.ascontiguousarray(x).copy()
        self.lam_committed = self.geometry.load_factor

    def rebase(self):
        """The obstacle starts a new phase at λ = 0 (move): ξ was committed where it is."""
        self.lam_committed = 0.0

    def pattern_nodes(self):
        return None

    def state_dict(self):
        return {"lam_committed": self.lam_committed}, {"anchor": self.positions, "traction": self.traction}

    def load_state_dict(self, meta, arrays):
        self.lam_committed = meta["lam_committed"]
        self.positions = np.ascontiguousarray(arrays["anchor"], dtype=float)
        self.traction = np.ascontiguousarray(arrays["traction"], dtype=float)
