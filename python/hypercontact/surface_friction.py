"""Coulomb friction against a deformable master surface: the history of each
slave point and the calls to the C++ assembly (``assemble_surface_friction``:
the normal penalty of :class:`~.surface_contact.SurfaceContact` plus the
return mapping of ``surface_friction`` per closed point).

History per slave point (SPEC §2: ξ and T_T of the last converged step) is a
*master material point*: the master facet the point was paired with at the
last converged step and ξ* there, and that step's tangential traction t. The
kernel places the old point at the old facet's *current* nodes, so a master
that moves or deforms under a sticking point creates no trial traction, and a
point now over another facet keeps its history. Paired points, open or
closed, store (facet, ξ*, t) (t = 0 when open, as the rigid contact stores the
position of an open node); points off the master or without a candidate store
none (old facet −1: the kernel then takes the current point, t_old = 0). The
history is set from the reference configuration when the contact is built and
changes only in :meth:`FrictionalSurfaceContact.commit`, after a converged
step: a step that fails and is cut back leaves it as it was.

The tangent has columns of the old facet's nodes: :meth:`couplings` adds them
to the matrix pattern. Only contacts with μ > 0 use this class (single pass,
nodal integration: scene.py refuses the others), so a frictionless scene never
enters it. What the results report mirrors :class:`~.friction.FrictionalRigidContact`.
"""
import numpy as np
from mpi4py import MPI

from . import _cpp
from .friction import OPEN, SLIP, FrictionAccounting
from .surface_contact import SurfaceContact


class FrictionalSurfaceContact(FrictionAccounting, SurfaceContact):
    """Node-to-surface normal penalty plus Coulomb friction (ε_T, μ)."""

    def __init__(self, spec, V, facet_tags, slave_tags, master_tags, constrained, name=None):
        super().__init__(spec, V, facet_tags, slave_tags, master_tags, constrained, name)
        if self.nodes is None:
            raise ValueError(f"contact {self.name!r}: friction against a surface needs nodal integration")
        self.mu = float(spec["mu"])
        self.eps_t = float(spec["eps_t"] or spec["eps_n"])
        n = len(self.point_area)
        self.old_facet = np.full(n, -1, np.int32)
        self.xi = np.zeros((n, 2))
        self.t_old = np.zeros((n, 3))
        self.lam_committed = 0.0  # kept for the checkpoint's common format (the master moves with u)
        self.dissipation = 0.0  # accumulated over converged steps, all ranks
        self.dissipation_step = 0.0  # of the last converged step, all ranks
        self.slip_accumulated = np.zeros(n)  # per point: Σ |Δs|
        self.dissipation_nodes = np.zeros(n)  # per point: Σ D
        self.committed = None  # friction state of the last converged step
        self.status_committed = np.zeros(n, np.int8)  # per point, the last converged step's
        self.flips_step = 0  # stick <-> slip flips of the last converged step, all ranks
        # History at the reference configuration: where each point is paired before any load.
        self.candidates = self.search(self.X)
        self._store_history(_cpp.evaluate_surface_friction(*self._args_at(self.X), smoothing=self.smoothing))
        self.candidates = None

    # --- kernel calls ------------------------------------------------------
    def _args_at(self, x):
        offsets, cand = self.candidates
        return (x, self.point_nodes, self.point_weights, self.point_area, self.facets, self.edge_neighbour,
                offsets, cand, self.eps_n, self.dofs, self.old_facet, np.ascontiguousarray(self.xi),
                np.ascontiguousarray(self.t_old), self.eps_t, self.mu)

    def _fargs(self, u):
        return self._args_at(self.current_coordinates(u))

    def add_residual_global(self, u, b):
        self.state = _cpp.assemble_surface_friction_residual(*self._fargs(u), b, multipliers=self.multipliers,
            smoothing=self.smoothing)

    def add_tangent(self, u, A):
        _cpp.assemble_surface_friction_tangent(*self._fargs(u), A, multipliers=self.multipliers,
            smoothing=self.smoothing)

    def evaluate(self, u):
        """Pairing, normal and friction state at u against the history
        (``force`` is the total, normal + tangential, force on the slave body)."""
        return _cpp.evaluate_surface_friction(*self._fargs(u), multipliers=self.multipliers,
            smoothing=self.smoothing)

    friction_state = evaluate

    def iterate_status(self):
        """Per point: 0 open, 1 stick, 2 slip at the last residual evaluation."""
        return np.asarray(self.state.state)

    def point_ids(self):
        return self.global_ids[self.point_nodes[:, 0]].astype(np.int64)  # the slave node of each point

    def active_set_signature(self):
        closed = self._active()
        facets = np.asarray(self.state.facet)[closed]
        slipping = int(np.count_nonzero(np.asarray(self.state.state) == SLIP))
        local = (len(closed), int(closed.sum() + facets.sum()), slipping)
        return tuple(self.comm.allreduce(np.array(local, dtype=np.int64), op=MPI.SUM).tolist())

    # --- pattern -----------------------------------------------------------
    def point_node_pairs(self):
        """As SurfaceContact's, plus each point's old facet's nodes (the
        friction tangent has their columns)."""
        points, nodes = super().point_node_pairs()
        has = np.flatnonzero(self.old_facet >= 0)
        old = np.repeat(has, 4), self.facets[self.old_facet[has]].ravel()
        return np.concatenate([points, old[0]]), np.concatenate([nodes, old[1]])

    # --- history -----------------------------------------------------------
    def _store_history(self, state):
        paired = np.asarray(state.status) == 2  # PairingStatus::Paired
        self.old_facet = np.where(paired, np.asarray(state.facet), -1).astype(np.int32)
        self.xi = np.where(paired[:, None], np.asarray(state.xi), 0.0)
        self.t_old = np.where(paired[:, None], np.asarray(state.traction), 0.0)

    def commit(self, u):
        """Make the converged state the history of the next step (and, augmented,
        the multipliers the next step's start)."""
        state = self.committed = self.evaluate(u)
        self.accumulate(state)
        self._store_history(state)
        self.multipliers_committed = self.multipliers.copy()
        self.lam_committed = getattr(self, "load_factor", 0.0)
        return state

    def surface_fields(self):
        """Per slave node of this rank at the last converged step, as
        FrictionalRigidContact.surface_fields: status, the tangential
        traction of the master on the slave body (−t), slip increment,
        accumulated slip, dissipation of the step and accumulated, per unit
        reference area."""
        n, area = len(self.point_area), self.point_area
        if self.committed is None:
            zeros3 = np.zeros((n, 3))
            return {"status": np.full(n, float(OPEN)), "traction": zeros3, "slip_increment": zeros3,
                    "accumulated_slip": self.slip_accumulated.copy(), "dissipation_step": np.zeros(n),
                    "dissipation": self.dissipation_nodes / area}
        state = self.committed
        return {"status": np.asarray(state.state, dtype=float),
                "traction": -np.asarray(state.traction),
                "slip_increment": np.asarray(state.slip_increment),
                "accumulated_slip": self.slip_accumulated.copy(),
                "dissipation_step": np.asarray(state.dissipation) / area,
                "dissipation": self.dissipation_nodes / area}

    def history_arrays(self):
        """This rank's per-point history beyond ξ and t, for the checkpoint."""
        return {"facet": self.old_facet, "slip": self.slip_accumulated, "work": self.dissipation_nodes,
                "status": self.status_committed}

    def restore_history_arrays(self, arrays):
        n = len(self.point_area)
        self.status_committed = np.array(arrays.get("status", np.zeros(n)), dtype=np.int8)
        self.old_facet = np.array(arrays.get("facet", np.full(n, -1)), dtype=np.int32)
        self.slip_accumulated = np.array(arrays.get("slip", np.zeros(n)), dtype=float)
        self.dissipation_nodes = np.array(arrays.get("work", np.zeros(n)), dtype=float)
