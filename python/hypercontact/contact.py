"""Rigid-obstacle contact: the Python side of the C++ kernels.

Each :class:`RigidContact` pairs one named surface of the body (the slave
nodes) with one analytic rigid obstacle that moves with the load factor λ.
The C++ library evaluates the paper's normal penalty per slave node
(nodal integration: the node's area A_i = ∫_Γ N_i dA over its slave facets,
in the reference configuration) and adds residual and tangent into the
PETSc objects. Each slave node is evaluated once, on the rank that owns it.
"""
import numpy as np
import ufl
from mpi4py import MPI

from . import _cpp
from . import _dolfinx as dfx
from . import penalty


def nodal_areas(V, facet_tags, tag):
    """A_i = ∫_Γ N_i dA on the tagged surface, owned nodes (parallel-safe:
    assembled as a dolfinx form and summed over ranks)."""
    v = ufl.TestFunction(V)
    ds = dfx.facet_integration_measure(V.mesh, facet_tags, quadrature_degree=2)
    L = dfx.compile_form(ufl.dot(v, ufl.as_vector((1.0, 0.0, 0.0))) * ds(tag))
    b = dfx.assemble_vector_owned(L)
    with b.localForm() as bl:
        area = bl.array_r[0::3].copy()
    b.destroy()
    area[dfx.num_owned_nodes(V):] = 0.0  # ghosts are counted on their owner
    return area


def make_obstacle(spec, load_factor):
    """The C++ obstacle of a scene's contact entry at load factor λ."""
    shift = load_factor * np.asarray(spec["motion"])
    if spec["obstacle"] == "plane":
        return _cpp.RigidPlane(np.asarray(spec["point"]) + shift, np.asarray(spec["normal"]))
    if spec["obstacle"] == "box":
        return _cpp.RigidBox(np.asarray(spec["lo"]) + shift, np.asarray(spec["hi"]) + shift)
    if spec["obstacle"] == "cylinder":
        return _cpp.RigidCylinder(np.asarray(spec["point"]) + shift, np.asarray(spec["axis"]), float(spec["radius"]))
    raise ValueError(f"unknown obstacle {spec['obstacle']!r}")


class UzawaMultipliers:
    """The augmented Lagrangian's per-point pressures λ_N (``multipliers``,
    empty for pure penalty), shared by rigid and deformable contacts: the
    kernels' current pressures are ⟨λ_N − ε_N g⟩, so an update takes them."""

    def augment(self, u):
        """Uzawa update λ_N ← ⟨λ_N − ε_N g⟩ (the current pressures)."""
        self.multipliers = np.ascontiguousarray(self.evaluate(u).pressure, dtype=float)

    def restore_multipliers(self):
        self.multipliers = self.multipliers_committed.copy()


class RigidContact(UzawaMultipliers):
    """One slave surface against one rigid obstacle, normal penalty."""

    def __init__(self, spec, V, facet_tags, surface_tag, constrained):
        self.spec = spec
        self.name = spec["name"]
        self.eps_n = float(spec["eps_n"])
        self.smoothing = penalty.smoothing_band(spec, V, facet_tags, [surface_tag])
        self.comm = V.mesh.comm
        area = nodal_areas(V, facet_tags, surface_tag)
        self.nodes = np.flatnonzero(area > 0.0).astype(np.int32)
        self.area = area[self.nodes].copy()
        dofs = (3 * self.nodes[:, None] + np.arange(3, dtype=np.int32)).astype(np.int32)
        dofs[constrained[dofs]] = -1  # PETSc skips negative indices: Dirichlet rows stay exact
        self.dofs = np.ascontiguousarray(dofs)
        self.X = np.ascontiguousarray(dfx.node_coordinates(V)[self.nodes])
        self.global_nodes = dfx.global_node_indices(V).astype(np.int64)
        self.total_area = self.comm.allreduce(self.area.sum(), op=MPI.SUM)
        self.num_slave_nodes = self.comm.allreduce(len(self.nodes), op=MPI.SUM)
        self.set_load_factor(0.0)
        self.state = None
        # Augmented Lagrangian: one pressure per slave node, held fixed in a Newton solve and
        # updated between solves (Uzawa); committed with the step, restored on a cut-back.
        self.augmented = spec.get("enforcement", "penalty") == "augmented_lagrangian"
        self.multipliers = np.zeros(len(self.nodes)) if self.augmented else np.zeros(0)
        self.multipliers_committed = self.multipliers.copy()

    def set_load_factor(self, load_factor):
        self.load_factor = load_factor
        self.obstacle = make_obstacle(self.spec, load_factor)

    def current_coordinates(self, u):
        return np.ascontiguousarray(self.X + u.x.array.reshape(-1, 3)[self.nodes])

    def add_residual(self, u, b_local):
        self.state = _cpp.assemble_rigid_residual(
            self.obstacle, self.current_coordinates(u), self.area, self.eps_n, self.dofs, b_local,
            self.multipliers, self.smoothing)

    def add_tangent(self, u, A):
        _cpp.assemble_rigid_tangent(
            self.obstacle, self.current_coordinates(u), self.area, self.eps_n, self.dofs, A, self.multipliers,
            self.smoothing)

    def evaluate(self, u):
        """Gap, pressure and force of this rank's slave nodes, no assembly."""
        scratch = np.zeros(u.x.array.size)
        return _cpp.assemble_rigid_residual(
            self.obstacle, self.current_coordinates(u), self.area, self.eps_n, self.dofs, scratch,
            self.multipliers, self.smoothing)

    def max_penetration(self, u):
        """Largest penetration ⟨−g⟩ over all slave nodes (all ranks)."""
        gap = np.asarray(self.evaluate(u).gap)
        local = float(max(0.0, -gap.min())) if len(gap) else 0.0
        return self.comm.allreduce(local, op=MPI.MAX)

    def active_set_signature(self):
        """(number of active nodes — closed, or in the smoothing band with a
        pressure — and a checksum of their global indices) at the last residual
        evaluation, summed over ranks: a change of the active set changes the
        signature."""
        gap, pressure = np.asarray(self.state.gap), np.asarray(self.state.pressure)
        closed = self.nodes[(gap <= 0.0) | (pressure > 0.0)]
        local = (len(closed), int(self.global_nodes[closed].sum()))
        return tuple(self.comm.allreduce(np.array(local, dtype=np.int64), op=MPI.SUM).tolist())

    def point_status(self):
        """Per slave node of this rank at the last residual evaluation: 0 open,
        2 closed (a frictionless closed node slides: the SLIP of friction.py)."""
        return np.where(np.asarray(self.state.gap) <= 0.0, 2, 0).astype(np.int8)

    def point_coordinates(self, u):
        """(reference, current) coordinates of this rank's slave nodes."""
        return self.X, self.current_coordinates(u)

    def force(self, u):
        """Total force the obstacle exerts on the body (summed over ranks)."""
        return self.comm.allreduce(np.asarray(self.evaluate(u).force), op=MPI.SUM)

    def commit(self, u):
        """Frictionless penalty contact has no history; the augmented
        Lagrangian's multipliers are kept as the next step's start."""
        self.multipliers_committed = self.multipliers.copy()
        return None

    def num_closed(self, u):
        return self.comm.allreduce(int(self.evaluate(u).num_closed), op=MPI.SUM)
