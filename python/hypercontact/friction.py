"""Coulomb friction against a rigid obstacle: the history of each slave node
and the calls to the C++ return-mapping kernel.

Per slave node the history of the last converged step is its position ξ
(carried with the obstacle's rigid motion since then) and its tangential
traction t. The trial traction of a Newton iterate is t + ε_T P (x − ξ); the
kernel returns it to the Coulomb cone (SPEC §2). The history changes only in
:meth:`FrictionalRigidContact.commit`, after a converged step: a step that
fails and is cut back leaves it as it was. Only contact pairs with μ > 0 are
built with this class, so a frictionless scene never enters this code.
"""
import numpy as np
from mpi4py import MPI

from . import _cpp
from .contact import RigidContact


class FrictionalRigidContact(RigidContact):
    """Normal penalty plus Coulomb friction (penalty ε_T, coefficient μ)."""

    def __init__(self, spec, V, facet_tags, surface_tag, constrained):
        super().__init__(spec, V, facet_tags, surface_tag, constrained)
        self.mu = float(spec["mu"])
        self.eps_t = float(spec["eps_t"] or spec["eps_n"])
        self.motion = np.asarray(spec["motion"], dtype=float)
        self.xi = self.X.copy()  # positions at the last converged step
        self.t_old = np.zeros_like(self.X)
        self.lam_committed = 0.0
        self.dissipation = 0.0  # accumulated over converged steps, all ranks
        self.last = None  # friction state at the last residual evaluation
        self.committed = None  # friction state of the last converged step

    def _xi_now(self):
        """ξ carried with the obstacle's translation since the last commit."""
        return np.ascontiguousarray(self.xi + (self.load_factor - self.lam_committed) * self.motion)

    def _friction(self, u, b_local):
        return _cpp.assemble_rigid_friction_residual(
            self.obstacle, self.current_coordinates(u), self.area, self.eps_n, self.eps_t, self.mu,
            self._xi_now(), self.t_old, self.dofs, b_local)

    def add_residual(self, u, b_local):
        super().add_residual(u, b_local)
        self.last = self._friction(u, b_local)

    def add_tangent(self, u, A):
        super().add_tangent(u, A)
        _cpp.assemble_rigid_friction_tangent(
            self.obstacle, self.current_coordinates(u), self.area, self.eps_n, self.eps_t, self.mu,
            self._xi_now(), self.t_old, self.dofs, A)

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
        self.dissipation += self.comm.allreduce(float(np.sum(state.dissipation)), op=MPI.SUM)
        self.t_old = np.ascontiguousarray(state.traction)
        self.xi = self.current_coordinates(u).copy()
        self.lam_committed = self.load_factor
        return state
