"""Path following past limit points: arc-length and displacement control.

Unknowns (u, λ) with R(u, λ) = R_int(u) + λ q(u) (q = ∂R/∂λ, e.g. a follower
pressure per unit load factor) and one constraint c(Δu, Δλ) = 0 on the
increment of the step. Each Newton iteration factorises the tangent
K = ∂R/∂u once and solves twice (bordering):

    K δu_R = −R,   K t = −q,   δu = δu_R + δλ t,

with δλ from the constraint:
- arc length (Crisfield, cylindrical): |Δu + δu|² = Δl², a quadratic in δλ
  whose root keeps the increment pointing forward (largest Δu_old·Δu_new);
  a converged step whose increment points against the last step's went
  back along the path and is refused;
- displacement control: e·(Δu + δu) = Δs for one controlled dof e.

PETSc 3.18 has no arc-length SNES; this is the project's own.
"""
import numpy as np
from petsc4py import PETSc

from .. import _dolfinx as dfx
from .newton import set_prefixed_options


class ContinuationFailure(RuntimeError):
    """A continuation step did not converge (or the constraint has no root)."""


class Bordered:
    """Newton–bordering solves for R(u, λ) = 0 plus one constraint."""

    def __init__(self, problem, q_form, bcs, comm, petsc_options, timers, prefix="hcc_"):
        self.problem, self.bcs, self.comm, self.timers = problem, bcs, comm, timers
        self.q_form = dfx.compile_form(q_form)
        self.ksp = PETSc.KSP().create(comm)
        self.ksp.setOptionsPrefix(prefix)
        defaults = {"ksp_type": "preonly", "pc_type": "lu", "pc_factor_mat_solver_type": "mumps"}
        set_prefixed_options(prefix, {**defaults, **petsc_options})
        self.ksp.setOperators(problem.A)
        self.ksp.setFromOptions()
        b = problem.b
        self.R, self.q, self.t, self.du_R = b.duplicate(), b.duplicate(), b.duplicate(), b.duplicate()
        self.reference = 0.0  # R_ref of the last step (see step)
        self.tolerance = 0.0  # the |R| it converged to

    def assemble(self, x):
        """R(x), K(x) and q(x) at the current load factor; returns |R|."""
        p = self.problem
        p.residual(None, x, self.R)
        p.jacobian(None, x, p.A, p.A)
        with self.timers("volume assembly"):
            with self.q.localForm() as ql:
                ql.set(0.0)
            dfx.assemble_vector_into(self.q, self.q_form)
            dfx.zero_bc_rows(self.q, self.bcs)
        return self.R.norm()

    def residual_norm(self, x):
        """|R(x)| at the current load factor (residual only)."""
        self.problem.residual(None, x, self.R)
        return self.R.norm()

    def body_residual_norm(self, x):
        """|R(x)| of the body alone: volume and loads, without the contacts'
        terms (the same as assemble's |R| when there is no contact)."""
        self.problem.residual(None, x, self.R, with_contacts=False)
        return self.R.norm()

    def tangent_direction(self):
        """t = −K⁻¹ q (the change of u per unit λ along the equilibrium path)."""
        self.ksp.setOperators(self.problem.A)
        with self.timers("linear solve"):
            self.ksp.solve(self.q, self.t)
        self.t.scale(-1.0)
        self._check(self.t)
        return self.t

    def newton_correction(self):
        """δu_R = −K⁻¹ R (same factorisation as the tangent direction)."""
        with self.timers("linear solve"):
            self.ksp.solve(self.R, self.du_R)
        self.du_R.scale(-1.0)
        self._check(self.du_R)
        return self.du_R

    def _check(self, v):
        reason = self.ksp.getConvergedReason()
        if reason < 0 or not np.isfinite(v.norm()):
            raise ContinuationFailure(f"linear solve failed (KSP reason {reason})")


class ArcLengthConstraint:
    """|Δu|² = Δl² (cylindrical arc length)."""

    name = "arc length"

    def __init__(self, size):
        self.size = size

    def predictor(self, t, du_prev):
        norm = t.norm()
        if not norm > 0.0:
            raise ContinuationFailure("the load does no work on the free degrees of freedom "
                                      "(its tangent direction is zero)")
        direction = 1.0 if du_prev is None or t.dot(du_prev) >= 0 else -1.0
        return direction * self.size / norm

    def correction(self, Du, du_R, t, Du_old):
        """δλ solving |Du + du_R + δλ t|² = Δl², the root that keeps the
        increment closest in direction to the one before this iteration."""
        w = Du.duplicate()
        Du.copy(w)
        w.axpy(1.0, du_R)
        a, b, c = t.dot(t), 2.0 * t.dot(w), w.dot(w) - self.size**2
        disc = b * b - 4 * a * c
        if disc < 0:
            raise ContinuationFailure("arc-length constraint has no real root")
        roots = [(-b + s * np.sqrt(disc)) / (2 * a) for s in (1.0, -1.0)]
        scores = [w.dot(Du_old) + r * t.dot(Du_old) for r in roots]
        return roots[int(np.argmax(scores))]

    def check_forward(self, Du, du_prev):
        """A converged increment must not point against the last step's:
        the sphere |Δu| = Δl meets the path ahead of the start and behind
        it, and Newton iterates thrown about by contact changes can land on
        the point behind, which retraces the path with λ falling (a tube
        squeezed flat by pressure went back to round that way: the point
        behind looked like a limit point). At a true limit point Δλ changes
        sign, Δu does not turn back."""
        if du_prev is None:
            return
        cos = Du.dot(du_prev) / max(Du.norm() * du_prev.norm(), 1e-300)
        if cos < 0.0:
            raise ContinuationFailure(f"the step converged behind its start on the path (its increment "
                                      f"points against the last step's, cos = {cos:.3f})")

    def scale(self, factor):
        self.size *= factor


class DisplacementConstraint:
    """e·Δu = Δs for one controlled dof (owned by one rank)."""

    name = "displacement control"

    def __init__(self, dof, owner, comm, size):
        self.dof, self.owner, self.comm, self.size = dof, owner, comm, size

    def _component(self, v):
        local = v.array_r[self.dof] if self.comm.rank == self.owner else 0.0
        return self.comm.allreduce(local)

    def predictor(self, t, du_prev):
        et = self._component(t)
        if et == 0.0:
            raise ContinuationFailure("the controlled displacement does not respond to the load")
        return self.size / et

    def correction(self, Du, du_R, t, Du_old):
        return (self.size - self._component(Du) - self._component(du_R)) / self._component(t)

    def check_forward(self, Du, du_prev):
        """The controlled component moves forward by construction."""

    def scale(self, factor):
        self.size *= factor


def two_cycle(norms, repeats=2, rtol=1e-2, apart=2.0):
    """Whether the last residual norms alternate between two values (each
    repeated ``repeats`` times to ``rtol``, the two ``apart`` × apart):
    Newton flipping contact points between open and closed, a cycle more
    iterations do not leave (a step cut short the same way converges)."""
    n = 2 * repeats + 1
    if len(norms) < n:
        return False
    last = norms[-n:]
    same = all(abs(last[k] - last[k + 2]) <= rtol * max(last[k], last[k + 2]) for k in range(n - 2))
    return same and max(last[-1], last[-2]) >= apart * min(last[-1], last[-2])


def step(bordered, constraint, x, lam, du_prev, set_load_factor, rtol, atol, max_it, tangent=None,
         reference=0.0):
    """One continuation step from the converged (x, λ). On success returns
    (Δu, Δλ, iterations, residual norms) and leaves x, λ updated by the caller;
    raises ContinuationFailure otherwise (x is then unchanged). ``tangent``:
    t = −K⁻¹q at (x, λ) when the caller has it (else it is computed here).
    The step converges at |R| ≤ max(rtol · max(R_ref, |λq|), atol), R_ref the
    predictor's residual or ``reference`` if larger (a re-solve of a step with
    a smaller size keeps the tolerance of the step); R_ref is left in
    ``bordered.reference``."""
    x0 = x.copy()
    try:
        return _step(bordered, constraint, x, x0, lam, du_prev, set_load_factor, rtol, atol, max_it, tangent,
                     reference)
    except ContinuationFailure:
        x0.copy(x)
        set_load_factor(lam)
        raise


def _step(bordered, constraint, x, x0, lam, du_prev, set_load_factor, rtol, atol, max_it, tangent, floor):
    set_load_factor(lam)
    if tangent is None:
        bordered.assemble(x0)
        tangent = bordered.tangent_direction()
    t = tangent
    dlam = constraint.predictor(t, du_prev)
    Du = t.copy()
    Du.scale(dlam)
    norms = []
    for it in range(max_it + 1):
        x0.copy(x)
        x.axpy(1.0, Du)
        set_load_factor(lam + dlam)
        if it == 0 and bordered.problem.contacts:
            # The tolerance is relative to the predictor's residual of the body alone: with
            # contact, the predictor pushes nodes into an obstacle and its penalty forces,
            # ε_N × the overshoot (1e5 × the load on the sphere against a plane), would
            # accept an iterate far from equilibrium.
            reference = bordered.body_residual_norm(x)
        rnorm = bordered.assemble(x)
        if not np.isfinite(rnorm):
            raise ContinuationFailure(f"residual is not finite at iteration {it}")
        if it == 0 and not bordered.problem.contacts:
            reference = rnorm
        if it == 0:
            reference = bordered.reference = max(reference, floor)
        norms.append(rnorm)
        qnorm = bordered.q.norm() * max(abs(lam + dlam), 1e-300)
        bordered.tolerance = max(rtol * max(reference, qnorm), atol)
        if it > 0 and rnorm <= bordered.tolerance:
            constraint.check_forward(Du, du_prev)
            return Du, dlam, it, norms
        if it == max_it:
            break
        if two_cycle(norms):
            raise ContinuationFailure(f"Newton two-cycles at iteration {it} (|R| alternates {norms[-2]:.3e} / "
                                      f"{norms[-1]:.3e}: contact points flip between open and closed)")
        t = bordered.tangent_direction()
        du_R = bordered.newton_correction()
        Du_old = Du.copy()
        ddlam = constraint.correction(Du, du_R, t, Du_old)
        Du.axpy(1.0, du_R)
        Du.axpy(ddlam, t)
        dlam += ddlam
    raise ContinuationFailure(f"no convergence in {max_it} iterations (|R| = {norms[-1]:.3e})")
