"""Coulomb friction against a rigid obstacle: the history of each slave node
and the calls to the C++ return-mapping kernel.

Per slave node the history of the last converged step is its position ξ
(carried with the obstacle's rigid motion since then) and its tangential
traction t. The trial traction of a Newton iterate is t + ε_T P (x − ξ); the
kernel returns it to the Coulomb cone (SPEC §2). The history changes only in
:meth:`FrictionalRigidContact.commit`, after a converged step: a step that
fails and is cut back leaves it as it was. Only contact pairs with μ > 0 are
built with this class, so a frictionless scene never enters this code.

Besides the history the return mapping needs, each node accumulates what the
results report: its slip path Σ|Δs| (mm) and its dissipated energy Σ D
(N mm, D = A t·Δs = μ p_N |Δs| A ≥ 0 in slip, 0 in stick); the total
dissipation of the last converged step and of all of them (all ranks).
"""
import numpy as np
from mpi4py import MPI

from . import _cpp
from .contact import RigidContact

#: Values of the kernel's per-node state (hypercontact::StickSlip).
OPEN, STICK, SLIP = 0, 1, 2


class FrictionAccounting:
    """What every frictional contact keeps over converged steps: dissipation
    (per step, accumulated, per point) and accumulated slip, and the
    stick/slip counts of the last converged state (``self.committed``)."""

    def accumulate(self, state):
        """Add a converged step's dissipation and slip (state: the kernel's),
        and count the points whose status flipped between stick and slip
        since the last converged step (``flips_step``, all ranks)."""
        status = np.asarray(state.state).astype(np.int8)
        old = self.status_committed
        flipped = ((old == STICK) & (status == SLIP)) | ((old == SLIP) & (status == STICK))
        self.flips_step = int(self.comm.allreduce(int(np.count_nonzero(flipped)), op=MPI.SUM))
        self.status_committed = status
        dissipation = np.asarray(state.dissipation)
        self.dissipation_step = self.comm.allreduce(float(np.sum(dissipation)), op=MPI.SUM)
        self.dissipation += self.dissipation_step
        self.dissipation_nodes = self.dissipation_nodes + dissipation
        self.slip_accumulated = self.slip_accumulated + np.linalg.norm(np.asarray(state.slip_increment), axis=1)

    def stick_slip_signature(self):
        """(sticking, slipping, checksums of the sticking and of the slipping
        points) at the last residual evaluation, summed over ranks: a point
        that changes between open, stick and slip changes it."""
        status = self.iterate_status()
        ids = self.point_ids()
        stick, slip = ids[status == STICK], ids[status == SLIP]
        local = np.array([len(stick), len(slip), stick.sum(), slip.sum(), (slip * slip).sum()], dtype=np.int64)
        return tuple(self.comm.allreduce(local, op=MPI.SUM).tolist())

    def point_status(self):
        """Per slave point of this rank: 0 open, 1 stick, 2 slip at the last residual evaluation."""
        return self.iterate_status().astype(np.int8)

    def stick_slip_counts(self):
        """(sticking, slipping) slave points at the last converged step, all ranks."""
        if self.committed is None:
            return 0, 0
        s = np.asarray(self.committed.state)
        local = np.array([np.count_nonzero(s == STICK), np.count_nonzero(s == SLIP)], dtype=np.int64)
        return tuple(int(v) for v in self.comm.allreduce(local, op=MPI.SUM))


class FrictionalRigidContact(FrictionAccounting, RigidContact):
    """Normal penalty plus Coulomb friction (penalty ε_T, coefficient μ)."""

    def __init__(self, spec, V, facet_tags, surface_tag, constrained):
        super().__init__(spec, V, facet_tags, surface_tag, constrained)
        self.mu = float(spec["mu"])
        self.eps_t = float(spec["eps_t"] or spec["eps_n"])
        self.motion = np.asarray(spec["motion"], dtype=float)
        self.xi = self.X.copy()  # positions at the last converged step
        self.t_old = np.zeros_like(self.X)
        self.lam_committed = 0.0
        self.dissipation = 0.0  # accumulated over converged steps, all ranks (N mm)
        self.dissipation_step = 0.0  # of the last converged step, all ranks (N mm)
        self.slip_accumulated = np.zeros(len(self.nodes))  # per node: Σ |Δs| (mm)
        self.dissipation_nodes = np.zeros(len(self.nodes))  # per node: Σ D (N mm)
        self.last = None  # friction state at the last residual evaluation
        self.committed = None  # friction state of the last converged step
        self.status_committed = np.zeros(len(self.nodes), np.int8)  # per node, the last converged step's
        self.flips_step = 0  # stick <-> slip flips of the last converged step, all ranks

    def iterate_status(self):
        """Per node: 0 open, 1 stick, 2 slip at the last residual evaluation."""
        return np.asarray(self.last.state)

    def point_ids(self):
        return self.global_nodes[self.nodes]

    def _xi_now(self):
        """ξ carried with the obstacle's translation since the last commit."""
        return np.ascontiguousarray(self.xi + (self.load_factor - self.lam_committed) * self.motion)

    def _friction(self, u, b_local):
        return _cpp.assemble_rigid_friction_residual(
            self.obstacle, self.current_coordinates(u), self.area, self.eps_n, self.eps_t, self.mu,
            self._xi_now(), self.t_old, self.dofs, b_local, self.multipliers, self.smoothing)

    def add_residual(self, u, b_local):
        super().add_residual(u, b_local)
        self.last = self._friction(u, b_local)

    def add_tangent(self, u, A):
        super().add_tangent(u, A)
        _cpp.assemble_rigid_friction_tangent(
            self.obstacle, self.current_coordinates(u), self.area, self.eps_n, self.eps_t, self.mu,
            self._xi_now(), self.t_old, self.dofs, A, self.multipliers, self.smoothing)

    def friction_state(self, u):
        """Traction, slip increment, dissipation and stick/slip of this
        rank's slave nodes at u against the current history, without
        assembly (after a commit, use :attr:`committed` for the converged
        step's state)."""
        return self._friction(u, np.zeros(u.x.array.size))

    def force(self, u):
        """Total force (normal and tangential) the obstacle exerts on the body."""
        local = np.asarray(self.evaluate(u).force) + np.asarray(self.friction_state(u).force)
        return self.comm.allreduce(local, op=MPI.SUM)

    def commit(self, u):
        """Make the converged state the history of the next step."""
        state = self.committed = self.friction_state(u)
        self.accumulate(state)
        self.t_old = np.ascontiguousarray(state.traction)
        self.xi = self.current_coordinates(u).copy()
        self.lam_committed = self.load_factor
        self.multipliers_committed = self.multipliers.copy()  # augmented Lagrangian (else empty)
        return state

    def surface_fields(self):
        """Per slave node of this rank, at the last converged step: status
        (0 open, 1 stick, 2 slip), the tangential traction the obstacle
        exerts on the body (MPa, −t), the slip increment of the step and the
        accumulated slip (mm), and the dissipation of the step and the
        accumulated one per unit reference area (N/mm = mJ/mm²: nodal value
        D / A, so that Σ A × value is the surface total)."""
        n = len(self.nodes)
        if self.committed is None:
            zeros3 = np.zeros((n, 3))
            return {"status": np.zeros(n), "traction": zeros3, "slip_increment": zeros3,
                    "accumulated_slip": self.slip_accumulated.copy(), "dissipation_step": np.zeros(n),
                    "dissipation": self.dissipation_nodes / self.area}
        state = self.committed
        return {"status": np.asarray(state.state, dtype=float),
                "traction": -np.asarray(state.traction),
                "slip_increment": np.asarray(state.slip_increment),
                "accumulated_slip": self.slip_accumulated.copy(),
                "dissipation_step": np.asarray(state.dissipation) / self.area,
                "dissipation": self.dissipation_nodes / self.area}

    def history_arrays(self):
        """This rank's per-node history beyond ξ and t, for the checkpoint."""
        return {"slip": self.slip_accumulated, "work": self.dissipation_nodes, "status": self.status_committed}

    def restore_history_arrays(self, arrays):
        """Inverse of :meth:`history_arrays` (a checkpoint without them, from
        an older version, restarts the accumulated per-node values at 0)."""
        n = len(self.nodes)
        self.status_committed = np.array(arrays.get("status", np.zeros(n)), dtype=np.int8)
        self.slip_accumulated = np.array(arrays.get("slip", np.zeros(n)), dtype=float)
        self.dissipation_nodes = np.array(arrays.get("work", np.zeros(n)), dtype=float)
