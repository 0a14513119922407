"""Contact laws: frictionless, or Coulomb friction by return mapping with a
history per slave point. A law knows what the kernels need of it (μ, ε_T, the
history) and what converged steps accumulate (dissipation, slip, stick/slip
counts); the geometry decides the history's layout."""
import numpy as np
from mpi4py import MPI

from .kernels import SLIP, STICK


class Frictionless:
    """⟨−g⟩ normal pressure only: a closed point slides freely."""

    frictional = False
    history = None

    def commit(self, state, x):
        pass

    def forget(self, x):
        pass

    def observables(self):
        return {}

    def state_dict(self):
        return {}, {}

    def load_state_dict(self, meta, arrays):
        pass


class Coulomb:
    """Coulomb friction, coefficient μ, tangential penalty ε_T; ``history`` is
    the geometry's (rigid: anchors and tractions; surface: master points).

    Per slave point the converged steps accumulate the slip path Σ|Δs| and
    the dissipated energy Σ D (D = A t·Δs = μ p_N |Δs| A ≥ 0 in slip, 0 in
    stick); totals are over all ranks."""

    frictional = True

    def __init__(self, mu, eps_t, history, comm):
        self.mu, self.eps_t, self.history, self.comm = float(mu), float(eps_t), history, comm
        n = len(history.traction)
        self.dissipation = 0.0  # accumulated over converged steps, all ranks (N mm)
        self.dissipation_step = 0.0  # of the last converged step, all ranks
        self.slip_accumulated = np.zeros(n)  # per point: Σ |Δs| (mm)
        self.dissipation_points = np.zeros(n)  # per point: Σ D (N mm)
        self.status_committed = np.zeros(n, np.int8)  # per point, of the last converged step
        self.committed = None  # the kernel state of the last converged step
        self.flips_step = 0  # stick ↔ slip flips of the last converged step, all ranks

    def commit(self, state, x):
        """Make a converged state the history of the next step and add its dissipation and slip."""
        status = state.state.astype(np.int8)
        old = self.status_committed
        flipped = ((old == STICK) & (status == SLIP)) | ((old == SLIP) & (status == STICK))
        self.flips_step = int(self.comm.allreduce(int(np.count_nonzero(flipped)), op=MPI.SUM))
        self.status_committed = status
        self.dissipation_step = self.comm.allreduce(float(np.sum(state.dissipation)), op=MPI.SUM)
        self.dissipation += self.dissipation_step
        self.dissipation_points = self.dissipation_points + state.dissipation
        self.slip_accumulated = self.slip_accumulated + np.linalg.norm(state.slip_increment, axis=1)
        self.committed = state
        self.history.store(state, x)

    def forget(self, x):
        """A converged step of a switched-off pair: no point carries a
        traction or an anchor into the next step (each starts open, from
        where it is: x), nothing slipped or was dissipated in this step; the
        totals accumulated so far stay."""
        old = self.status_committed
        self.flips_step = 0
        self.status_committed = np.zeros_like(old)
        self.dissipation_step = 0.0
        self.committed = None
        self.history.forget(x)

    def stick_slip_counts(self):
        """(sticking, slipping) slave points at the last converged step, all ranks."""
        if self.committed is None:
            return 0, 0
        s = self.committed.state
        local = np.array([np.count_nonzero(s == STICK), np.count_nonzero(s == SLIP)], dtype=np.int64)
        return tuple(int(v) for v in self.comm.allreduce(local, op=MPI.SUM))

    def observables(self):
        stick, slip = self.stick_slip_counts()
        return {"dissipation_step": self.dissipation_step, "dissipation": self.dissipation,
                "stick_nodes": stick, "slip_nodes": slip, "stick_slip_flips": self.flips_step}

    def point_fields(self, area):
        """Per slave point of this rank at the last converged step: status (0
        open, 1 stick, 2 slip), the tangential traction on the body (−t, MPa),
        the slip increment and the accumulated slip (mm), the dissipation of
        the step and the accumulated one per unit reference area (N/mm:
        D / A, so that Σ A × value is the surface total)."""
        n, state = len(area), self.committed
        if state is None:
            zeros3 = np.zeros((n, 3))
            return {"status": np.zeros(n), "traction": zeros3, "slip_increment": zeros3,
                    "accumulated_slip": self.slip_accumulated.copy(), "dissipation_step": np.zeros(n),
                    "dissipation": self.dissipation_points / area}
        return {"status": state.state.astype(float), "traction": -state.traction,
                "slip_increment": state.slip_increment, "accumulated_slip": self.slip_accumulated.copy(),
                "dissipation_step": state.dissipation / area, "dissipation": self.dissipation_points / area}

    def state_dict(self):
        meta, arrays = self.history.state_dict()
        meta = {**meta, "dissipation": self.dissipation}
        arrays = {**arrays, "slip": self.slip_accumulated, "work": self.dissipation_points,
                  "status": self.status_committed}
        return meta, arrays

    def load_state_dict(self, meta, arrays):
        self.history.load_state_dict(meta, arrays)
        self.dissipation = meta["dissipation"]
        self.slip_accumulated = np.array(arrays["slip"], dtype=float)
        self.dissipation_points = np.array(arrays["work"], dtype=float)
        self.status_committed = np.array(arrays["status"], dtype=np.int8)
