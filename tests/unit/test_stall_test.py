"""The line-search fallback's stall stop (solve.newton.StallTest).

- On synthetic residual histories: two iterations in a row that each lower
  |R| by less than the fraction stop the solve; one slow iteration between
  fast ones does not; NaN, the absolute and the relative tolerance give
  PETSc's own reasons.
- On a real nonlinear solve whose iterations never stall, the test is PETSc's
  default: the same residual history and reason as SNESConvergedDefault,
  iterate for iterate (an independent nonlinear system, not a scene).
"""
import numpy as np
import pytest
from mpi4py import MPI
from petsc4py import PETSc

from hypercontact.solve.newton import StallTest

R = PETSc.SNES.ConvergedReason


def snes_with(rtol=1e-10, atol=1e-10):
    snes = PETSc.SNES().create(MPI.COMM_SELF)
    snes.setTolerances(rtol=rtol, atol=atol, stol=0.0, max_it=50)
    return snes


def run(test, norms):
    reasons = [test(test_snes, k, (1.0, 1.0, f)) for k, f in enumerate(norms)]
    return reasons


test_snes = snes_with()


@pytest.mark.parametrize("norms, stop_at", [
    ([4.58e3, 35.0, 34.9, 34.9], 3),            # the 32×32×8 punch in one step: a crawl after one good iteration
    ([360.0, 2.50, 2.50, 2.50, 2.49], 3),        # the 706k punch's crawl
    ([100.0, 99.0, 98.0], 2),                    # never a good iteration
    ([100.0, 96.0, 50.0, 49.0, 48.5], 4),        # slow, fast, slow, slow
    ([100.0, 101.0, 100.5], 2),                  # an increase counts as no decrease
])
def test_two_slow_iterations_in_a_row_stop_the_solve(norms, stop_at):
    test = StallTest(test_snes, 0.05)
    reasons = run(test, norms)
    assert all(r == R.CONVERGED_ITERATING for r in reasons[:stop_at])
    assert reasons[stop_at] == R.DIVERGED_MAX_IT and test.stalled


@pytest.mark.parametrize("norms", [
    [73.7, 1.0, 0.666, 0.325, 0.125, 0.0447],      # the 706k punch's fallbacks that were still converging
    [29.4, 0.89, 0.78, 0.572, 0.543, 0.107],
    [41.4, 1.17, 0.833, 0.719, 0.228, 0.122],
    [100.0, 96.0, 50.0, 48.0, 20.0, 19.5, 5.0],    # slow iterations, never two in a row
])
def test_one_slow_iteration_between_fast_ones_goes_on(norms):
    test = StallTest(test_snes, 0.05)
    assert all(r == R.CONVERGED_ITERATING for r in run(test, norms)) and not test.stalled


def test_the_fraction_sets_what_is_slow():
    norms = [100.0, 90.0, 81.0, 72.9]  # 10 % per iteration
    assert run(StallTest(test_snes, 0.05), norms)[-1] == R.CONVERGED_ITERATING
    assert run(StallTest(test_snes, 0.2), norms)[2] == R.DIVERGED_MAX_IT


def test_petsc_reasons_come_first():
    test = StallTest(snes_with(rtol=1e-3, atol=1e-8), 0.05)
    assert run(test, [1.0, float("nan")])[-1] == R.DIVERGED_FNORM_NAN
    assert run(test, [1.0, 0.9999, 5e-9])[-1] == R.CONVERGED_FNORM_ABS and not test.stalled
    assert run(test, [1.0, 0.9999, 9e-4])[-1] == R.CONVERGED_FNORM_RELATIVE and not test.stalled
    assert run(test, [1.0, 2e4])[-1] == R.DIVERGED_DTOL  # PETSc's divergence tolerance, 1e4 by default
    assert run(test, [1e-9])[0] == R.CONVERGED_FNORM_ABS  # converged at the start


def test_history_restarts_with_each_solve():
    test = StallTest(test_snes, 0.05)
    run(test, [100.0, 99.0, 98.0])
    assert test.stalled
    assert run(test, [100.0, 10.0])[-1] == R.CONVERGED_ITERATING and not test.stalled


def solve_cubic(convergence_test, line_search):
    """x_i³ + x_i − b_i = 0 with a weak coupling, n = 20, from x = 0: a nonlinear solve whose
    iterations fall fast (no stall), so the stall test must act exactly as PETSc's default."""
    n = 20
    b = np.linspace(1.0, 30.0, n)

    def residual(snes, x, f):
        xa = x.getArray(readonly=True)
        fa = xa ** 3 + xa - b
        fa[1:] += 0.1 * xa[:-1]
        f.setArray(fa)

    def jacobian(snes, x, J, P):
        xa = x.getArray(readonly=True)
        P.zeroEntries()
        for i in range(n):
            P.setValue(i, i, 3 * xa[i] ** 2 + 1)
            if i:
                P.setValue(i, i - 1, 0.1)
        P.assemble()

    snes = PETSc.SNES().create(MPI.COMM_SELF)
    snes.setOptionsPrefix("stalltest_")
    PETSc.Options()["stalltest_snes_linesearch_type"] = line_search
    J = PETSc.Mat().createAIJ([n, n], nnz=2, comm=MPI.COMM_SELF)
    f = PETSc.Vec().createSeq(n)
    snes.setFunction(residual, f)
    snes.setJacobian(jacobian, J)
    snes.getKSP().setType("preonly")
    snes.getKSP().getPC().setType("lu")
    snes.setTolerances(rtol=1e-12, atol=1e-14, stol=0.0, max_it=50)
    snes.setFromOptions()
    snes.setConvergenceHistory(length=51, reset=True)
    if convergence_test is not None:
        snes.setConvergenceTest(convergence_test(snes))
    x = f.duplicate()
    x.set(0.0)
    snes.solve(None, x)
    norms = np.asarray(snes.getConvergenceHistory()[0])
    return snes.getConvergedReason(), norms, x.getArray().copy()


@pytest.mark.parametrize("line_search", ["basic", "bt"])
def test_without_a_stall_it_is_petsc_default(line_search):
    reason, norms, x = solve_cubic(None, line_search)
    reason_s, norms_s, x_s = solve_cubic(lambda snes: StallTest(snes, 0.05), line_search)
    assert reason > 0 and len(norms) > 4  # a real nonlinear solve, converged in several iterations
    assert reason_s == reason
    assert np.array_equal(norms_s, norms)
    assert np.array_equal(x_s, x)


@pytest.mark.parametrize("norms, stop_at", [
    # the 706k frictional punch's full-step solve at λ = 0.8 + 0.1: down to 0.003, then 2-cycling
    ([162.657, 0.633, 0.248, 0.038, 0.003, 0.018, 0.004, 0.019, 0.004, 0.019, 0.004], 8),
    ([10.0, 1.0, 3.0, 2.0, 1.0, 3.0, 2.0, 1.0, 3.0], 5),  # a period-3 cycle: 4 without a new best at 5
])
def test_a_cycle_is_stopped_after_four_iterations_without_a_new_smallest_residual(norms, stop_at):
    test = StallTest(test_snes, 0.05, window=0, cycle_window=4)
    reasons = run(test, norms)
    assert all(r == R.CONVERGED_ITERATING for r in reasons[:stop_at])
    assert reasons[stop_at] == R.DIVERGED_MAX_IT and test.stalled
    # without the cycle stop (the crawl stop alone) it runs on: no two slow iterations in a row
    assert all(r == R.CONVERGED_ITERATING for r in run(StallTest(test_snes, 0.05), norms))


@pytest.mark.parametrize("norms", [
    [1.0, 1.5, 1.2, 0.1, 1e-3],                     # a rise while the active set settles, then Newton
    [1.0, 0.99, 1.3, 0.98, 0.5, 1e-2],              # three iterations without a new smallest |R|
    [360.0, 2.50, 0.4, 0.38, 0.37, 0.2, 1e-3],      # slow iterations with no crawl stop (window 0)
    [79.7, 3.76e4, 1.11e4, 3.28e3, 957.0, 267.0, 65.2, 10.5, 0.557],  # an overshoot, then a steady recovery
])
def test_full_steps_that_settle_within_four_iterations_go_on(norms):
    test = StallTest(test_snes, 0.05, window=0, cycle_window=4)
    assert all(r == R.CONVERGED_ITERATING for r in run(test, norms)) and not test.stalled


@pytest.mark.parametrize("line_search", ["basic", "bt"])
def test_without_a_stall_both_stops_are_petsc_default(line_search):
    reason, norms, x = solve_cubic(None, line_search)
    reason_s, norms_s, x_s = solve_cubic(lambda snes: StallTest(snes, 0.05, window=2, cycle_window=4), line_search)
    assert reason_s == reason and np.array_equal(norms_s, norms) and np.array_equal(x_s, x)


def test_a_reference_norm_sets_the_relative_and_divergence_tolerances():
    """A solve that starts from a prediction near the solution (|R_0| = 1e-6
    where the unpredicted start had 100) stops at rtol × 100, not rtol × 1e-6
    (below round-off); a smaller reference than the solve's own |R_0| changes
    nothing. The divergence tolerance measures against the same |R_0|."""
    test = StallTest(snes_with(rtol=1e-6, atol=1e-20), 0.0, 0, 0)
    assert run(test, [1e-6, 5e-5])[-1] == R.CONVERGED_ITERATING  # rtol × 1e-6: not yet
    test.reference = 100.0
    assert run(test, [1e-6, 5e-5])[-1] == R.CONVERGED_FNORM_RELATIVE  # below rtol × 100
    assert run(test, [1e-6, 2e-4])[-1] == R.CONVERGED_ITERATING
    assert run(test, [1e-6, 1e-3])[-1] == R.CONVERGED_ITERATING  # 1e3 × |R_0|, not 1e4 × the reference
    test.reference = 1e-9
    assert run(test, [1e-6, 5e-13])[-1] == R.CONVERGED_FNORM_RELATIVE
    assert run(test, [1e-6, 5e-12])[-1] == R.CONVERGED_ITERATING
    test.reference = 0.0
    assert run(test, [1e-6, 2e-2])[-1] == R.DIVERGED_DTOL


class Halvings:
    """A stand-in for InversionDamping: the list of halvings it made."""

    def __init__(self):
        self.halvings = []


def run_damped(test, damping, norms, damped):
    """``damped[k]``: the correction that led to iterate k was halved."""
    reasons = []
    for k, (f, d) in enumerate(zip(norms, damped)):
        if d:
            damping.halvings.append(1)
        reasons.append(test(test_snes, k, (1.0, 1.0, f)))
    return reasons


@pytest.mark.parametrize("window, cycle_window", [(0, 4), (2, 0), (0, 0)])
def test_two_slow_damped_corrections_in_a_row_stop_any_solve(window, cycle_window):
    """The one-cell block squeezed 70 % in one step: every correction halved,
    |R| 2.6e3, 2.1e3, 1.0e3, 1.0e3, 1.1e3: stopped at the fourth iterate
    whatever the test's other stops (the full-step test has no crawl stop)."""
    norms, damped = [2.6e3, 2.1e3, 1.0e3, 0.999e3, 1.1e3, 1.0e3], [False, True, True, True, True, True]
    test, damping = StallTest(test_snes, 0.05, window, cycle_window), Halvings()
    test.damping = damping
    reasons = run_damped(test, damping, norms, damped)
    assert all(r == R.CONVERGED_ITERATING for r in reasons[:4]) and reasons[4] == R.DIVERGED_MAX_IT and test.stalled


@pytest.mark.parametrize("damped", [
    [False, True, False, True, False, True],   # slow damped iterations, never two in a row
    [False, False, False, False, False, False],  # slow, but not damped: the full-step test goes on
])
def test_slow_iterations_not_both_damped_go_on(damped):
    norms = [2.6e3, 2.1e3, 1.0e3, 0.999e3, 0.998e3, 0.997e3]
    test, damping = StallTest(test_snes, 0.05, 0, 0), Halvings()
    test.damping = damping
    assert all(r == R.CONVERGED_ITERATING for r in run_damped(test, damping, norms, damped)) and not test.stalled


def test_damped_but_converging_goes_on():
    """The 32×32×8 punch pressed 2 mm in one step, damped: |R| rises and falls
    while the active set settles, then converges."""
    norms = [4578, 35.1, 115, 108, 208, 123, 54.3, 32.5, 0.969, 1.21, 0.0029, 1.7e-6, 2.4e-12]
    test, damping = StallTest(test_snes, 0.05, 0, 0), Halvings()
    test.damping = damping
    reasons = run_damped(test, damping, norms, [False] + [True] * 8 + [False] * 4)
    assert all(r == R.CONVERGED_ITERATING for r in reasons[:-1]) and reasons[-1] == R.CONVERGED_FNORM_ABS


def test_without_a_decrease_fraction_damping_stops_nothing():
    norms = [2.6e3, 2.1e3, 2.2e3, 2.3e3, 2.4e3]
    test, damping = StallTest(test_snes, 0.0, 0, 0), Halvings()
    test.damping = damping
    assert all(r == R.CONVERGED_ITERATING for r in run_damped(test, damping, norms, [False] + [True] * 4))
