"""One Newton solve at the current load factor: PETSc SNES on the model's
Problem, a line-search fallback, the per-iterate monitor and the check that
no element is inverted."""
import time

import numpy as np
from mpi4py import MPI
from petsc4py import PETSc

from .. import _dolfinx as dfx
from ..model.inversion import INVERTED_ELEMENT, InversionDamping
from .monitor import IterationHistory
from .newton import (KRYLOV_RTOL_MIN, STALLED, StallTest, converged_reason_name, krylov_forcing, line_search_of,
                     make_snes, residual_norms_of, set_line_search)

class NewtonSolver:
    """SNES (newtonls) with the scene's solver settings. Line search "auto":
    full steps with rigid obstacles, backtracking with a deformable master;
    a solve that fails with one is tried again with the other before the step
    is cut back (which converges depends on the contact: full steps on the
    paper's punch, where backtracking crawls; backtracking where full steps
    cycle, on Hertz or the ironing die's rim). The full-step fallback starts
    from the same start. The backtracking one starts where the failed
    full-step solve's leading full steps end, so long as each lowered |R| by
    at least the fraction RESUME_DECREASE: backtracking accepts such a step
    whole (its sufficient-decrease test asks for at most 4e-4 |R|²),
    so from the same start it would take the same steps again, to the same
    iterates (resume_fallback; docs/performance.md §2)."""

    #: whether a backtracking fallback starts at the failed full-step solve's last iterate that it
    #: would reach itself (True), or at the step's start (False: the same iterates, each computed again)
    resume_fallback = True
    #: the least decrease of |R| that makes a full step one the backtracking line search takes whole
    #: (PETSc's bt, sufficient-decrease constant α = 1e-4, takes it when |R_new|² ≤ |R|² − 2α|R·J dx|,
    #: and |R·J dx| ≤ (1 + η)|R|² for a Krylov solve to the relative tolerance η ≤ 1, so any
    #: |R_new| ≤ 0.95 |R| passes), and by more than the crawl stop's fraction: no stop of the
    #: fallback would have looked at it
    RESUME_DECREASE = 0.05

    def __init__(self, model, solver, timers):
        self.model, self.timers = model, timers
        deformable = any(c.deformable for c in model.contacts)
        self.snes = make_snes(model.problem, model.comm, solver, deformable=deformable,
                              symmetric=model.symmetric_tangent)
        self.fallback = None
        if solver["linesearch"] == "auto" and model.contacts:
            self.fallback = "basic" if deformable else "bt"
        # the fallback's own iteration limit: a fallback that crawls (backtracking to tiny steps after a
        # full step overshot into inverted elements) costs up to max_it iterations before the cut-back
        self.max_it = self.snes.getTolerances()[3]  # solver.max_it, or a snes_max_it in solver.petsc
        self.fallback_max_it = solver["fallback_max_it"] or self.max_it
        # stall stops (docs/performance.md §2), then the step is cut back: a full-step solve that
        # cycles (stall_its iterations without a new smallest |R|, |R| back where it was two or three
        # iterations before), a backtracking fallback that crawls (two iterations in a row that each
        # lower |R| by less than the fraction stall_decrease). Not a backtracking first try: the
        # sharp contact law's hemisphere (tests/hard/test_chattering.py) sits at |R| 1.39–1.38 for
        # 12 iterations and then converges in 6
        on = solver["stall_decrease"] > 0
        self.cycle_stop = (StallTest(self.snes, solver["stall_decrease"], 0, solver["stall_its"])
                           if on and solver["stall_its"] > 0 else None)
        self.crawl_stop = StallTest(self.snes, solver["stall_decrease"], 2, 0) if on else None
        self.no_stop = StallTest(self.snes, 0.0, 0, 0)  # the default test, with a reference |R_0|
        # inexact Newton with the iterative solver (newton.krylov_forcing), unless the scene fixes the
        # Krylov tolerance itself (solver.petsc.ksp_rtol)
        self.forcing = (model.problem.linear_kind == "iterative" and "ksp_rtol" not in solver["petsc"])
        for test in (self.cycle_stop, self.crawl_stop, self.no_stop):
            if test is not None and self.forcing:
                test.forcing = self._force
        self.history = IterationHistory(model.contacts)
        self.snes.setConvergenceHistory(length=max(self.max_it, self.fallback_max_it) + 1, reset=True)
        self.snes.setMonitor(self.history.monitor)
        # the last iterate of the solve's leading full steps that each lowered |R| by RESUME_DECREASE or
        # more (and the fallback's stall_decrease): its number (0: none) and a copy of it
        self._resume_at, self._leading, self._last_fnorm, self._resume_vec = 0, False, 0.0, None
        self.resume_decrease = max(self.RESUME_DECREASE, solver["stall_decrease"])
        if self.fallback == "bt":
            self.snes.setMonitor(self._track_full_steps)
        self.linear_iterations = []  # Krylov iterations of each Newton solve
        # what each Newton solve did (line search, iterations, reason, residual norms): a failed
        # attempt's story lists its solves, the primary's as well as the fallback's
        self.solves = []
        # what the iterative solver's time goes to (read by Run.split): the preconditioner set-up is the
        # time from the end of the tangent's assembly to the Krylov solve's first monitor call (PETSc
        # sets the preconditioner up inside KSPSolve, before iterating), the Krylov time the rest of it.
        # Timed here, not by PETSc's event log: an error raised inside a KSP event (a failed solve in
        # the same process) leaves that event open and PETSc stops counting it.
        self.preconditioner_setups, self.preconditioner_setup_s, self.krylov_s = 0, 0.0, 0.0
        self._t_tangent = self._t_krylov = None
        self.snes.setJacobian(self._jacobian, model.problem.A)
        if model.problem.linear_kind == "iterative":
            self.snes.getKSP().setMonitor(self._krylov_monitor)
        # solver.damp_inversion: a full step that would invert an element is halved until it does not
        self.damping = None
        if solver["damp_inversion"]:
            self.damping = InversionDamping(model.w, model.u, model.volume.u_dofs,
                                            model.scene["discretisation"]["quadrature_degree"])
            self.snes.setLineSearchPreCheck(self.damping)
            for test in (self.cycle_stop, self.crawl_stop, self.no_stop):
                if test is not None:
                    test.damping = self.damping
        self.inverted = None  # InversionCheck's answer at the end of the last solve
        self.reference = 0.0  # the current solve's reference |R_0| (solve)
        self.last_snes_reason = None

    def use_matrix(self, A):
        """The problem's matrix was rebuilt (a new pattern)."""
        self.snes.setJacobian(self._jacobian, A)

    def _jacobian(self, snes, x, A, P):
        self.model.problem.jacobian(snes, x, A, P)
        self.preconditioner_setups += 1  # PETSc sets the preconditioner up (factorises) for every new tangent
        self._t_tangent = time.perf_counter()

    def _force(self, fnorm, target):
        self.snes.getKSP().setTolerances(rtol=krylov_forcing(fnorm, target))

    def _krylov_monitor(self, ksp, its, rnorm):
        now = time.perf_counter()
        if its == 0 and self._t_tangent is not None:
            self.preconditioner_setup_s += now - self._t_tangent
            self._t_tangent = None
        elif self._t_krylov is not None:
            self.krylov_s += now - self._t_krylov
        self._t_krylov = now

    def _track_full_steps(self, snes, its, fnorm):
        """Keep the last iterate of the leading full steps a backtracking
        fallback would take whole (solve). |R| is global: every rank decides
        alike."""
        if line_search_of(snes) != "basic":
            return
        if its == 0:
            self._resume_at, self._leading = 0, True
        elif (self._leading and its < self.fallback_max_it and np.isfinite(fnorm)
              and fnorm <= (1.0 - self.resume_decrease) * self._last_fnorm):
            x = snes.getSolution()
            if self._resume_vec is None or self._resume_vec.getSizes() != x.getSizes():
                self._resume_vec = x.duplicate()
            x.copy(self._resume_vec)
            self._resume_at = its
        else:
            self._leading = False
        self._last_fnorm = fnorm

    def residual_norm(self):
        """|R| at the current unknown and load factor (one residual evaluation)."""
        p = self.model.problem
        self.model.w.vector.copy(p.x)
        p.residual(None, p.x, p.b)
        return p.b.norm()

    def solve(self, reference=0.0):
        """(converged, iterations, norms, reason); the count includes a fallback
        solve, the norms and reason are the last solve's. ``reference``: the |R_0|
        the relative tolerance measures against if larger than the solve's own
        (a predicted start: the |R| of the unpredicted one)."""
        self.reference = reference
        w = self.model.w
        start = w.x.array.copy() if self.fallback else None
        self._resume_at = 0  # (set by _track_full_steps, with a backtracking fallback only)
        ok, its, norms, reason = self._newton(self._stall_stop(fallback=False))
        if ok or self.fallback is None or reason == INVERTED_ELEMENT:
            return ok, its, norms, reason
        # full steps of the failed solve the fallback does not take again
        done = self._resume_at if self.resume_fallback and self.damping is None else 0
        if not done:
            w.x.array[:] = start  # a failed solve leaves its last iterate in the unknown
        else:
            self._resume_vec.copy(w.vector)
            dfx.update_ghosts(w)
        self.model.sync_displacement()
        primary = set_line_search(self.snes, self.fallback)
        self.snes.setTolerances(max_it=self.fallback_max_it - done)
        try:
            test = self._stall_stop(fallback=True)
            # the tolerances measure against the step's |R_0|, as from the start
            test.reference = max(self.reference, norms[0]) if done else self.reference
            ok, more, norms, reason = self._newton(test)
            self.solves[-1]["from_iterate"] = done
        finally:
            set_line_search(self.snes, primary)
            self.snes.setTolerances(max_it=self.max_it)
        return ok, its + more, norms, reason

    def _stall_stop(self, fallback):
        """The stall stop for the solve about to run with the SNES's line search:
        the cycle stop for full steps, the crawl stop for a backtracking
        fallback, neither for a backtracking first try (or another line search);
        each with the solve's reference |R_0|."""
        line_search = line_search_of(self.snes)
        if line_search == "basic":
            test = self.cycle_stop
        else:
            test = self.crawl_stop if fallback and line_search == "bt" else None
        test = test if test is not None else self.no_stop
        test.reference = self.reference
        return test

    def _newton(self, stall_test):
        """One SNES solve (``stall_test``: its convergence test, a StallTest from
        _stall_stop). After it the unknown holds its end state (converged)
        or the last iterate SNES evaluated (failed); a state with det F ≤ 0
        somewhere fails with INVERTED_ELEMENT."""
        model, x = self.model, self.model.problem.x
        model.w.vector.copy(x)
        self.history.reset()
        damped_before = len(self.damping.halvings) if self.damping is not None else 0
        self.snes.setConvergenceTest(stall_test)
        try:
            self.snes.solve(None, x)
        finally:
            self.snes.setConvergenceTest("default")
            if self.forcing:  # whatever solves with this KSP next starts from the fixed tolerance
                self.snes.getKSP().setTolerances(rtol=KRYLOV_RTOL_MIN)
        self.linear_iterations.append(self.snes.getLinearSolveIterations())
        reason = self.snes.getConvergedReason()
        norms = residual_norms_of(self.snes)
        name = converged_reason_name(reason)
        if stall_test.stalled:
            name = STALLED  # (SNES was told DIVERGED_MAX_IT)
        self.last_snes_reason = name
        record = {"line_search": line_search_of(self.snes), "newton_iterations": self.snes.getIterationNumber(),
                  "linear_iterations": self.linear_iterations[-1], "snes_reason": name, "residual_norms": norms,
                  "damped_halvings": self.damping.halvings[damped_before:] if self.damping is not None else []}
        self.solves.append(record)
        # every rank must take the same branch: a NaN on one rank fails the step on all
        finite = model.comm.allreduce(int(np.all(np.isfinite(x.array))), op=MPI.MIN)
        converged = reason > 0 and bool(finite)
        if converged:
            x.copy(model.w.vector)
            dfx.update_ghosts(model.w)
        model.sync_displacement()
        with self.timers("inversion check"):
            self.inverted = model.inversion_check()
        if converged and self.inverted is not None:
            converged, name = False, INVERTED_ELEMENT
        record["reason"] = name
        return converged, self.snes.getIterationNumber(), norms, name

    def iterations_not_repeated(self):
        """The full steps the backtracking fallbacks of the solves since
        ``solves`` was last cleared started after instead of taking them again
        (resume_fallback): the same solves from the step's start would have
        taken that many more Newton iterations to the same iterates."""
        return sum(s.get("from_iterate", 0) for s in self.solves)

    def iterations(self):
        return self.snes.getIterationNumber()

    def negative_eigenvalues(self):
        """How many eigenvalues of the last tangent this solver factorised are
        negative, where that is known: with a symmetric tangent factorised by
        MUMPS as LDLᵀ it is the number of negative pivots (Sylvester's law of
        inertia), free once factorised. None with LU (a non-symmetric tangent),
        an iterative solver, or before the first factorisation. In a converged
        step that tangent is the one at its last Newton iterate but one. A
        stable equilibrium has none (the tangent of a minimum of the energy is
        positive definite); one or more mark a state past a bifurcation or a
        limit point of the path. In the mixed formulation the count leaves out
        the one negative eigenvalue each pressure unknown has at a stable
        state (Model.pressure_unknowns): what is left are the unstable modes."""
        pc = self.snes.getKSP().getPC()
        if pc.getType() != "cholesky" or pc.getFactorSolverType() != "mumps":
            return None
        try:
            factor = pc.getFactorMatrix()
        except PETSc.Error:
            return None
        # INFOG(29), the entries in the factors, is 0 until a numerical factorisation (< 0: millions);
        # INFOG(1) < 0: the last one failed
        if factor.getMumpsInfog(29) == 0 or factor.getMumpsInfog(1) < 0:
            return None
        return int(factor.getMumpsInfog(12)) - self.model.pressure_unknowns
