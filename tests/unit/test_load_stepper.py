"""The load-step controller on its own: no mesh, no solver. Each case states
the rule of solve/step_control.py it checks, with Δλ worked by hand."""
import pytest

from hypercontact.solve.step_control import LoadStepper


def stepper(**kw):
    settings = dict(initial=0.1, max=0.4, min=0.01, growth=2.0, grow_below=4, grow_after=3, max_cutbacks=3)
    return LoadStepper(**{**settings, **kw})


def test_fast_steps_grow_by_the_growth_factor_up_to_max():
    s = stepper()
    increments = []
    while not s.done():
        increments.append(s.increment())
        s.converged(iterations=3)
    # 0.1, 0.2, 0.4 (max), then 0.3 to land exactly on λ = 1
    assert increments == pytest.approx([0.1, 0.2, 0.4, 0.3])
    assert s.lam == pytest.approx(1.0)


def test_slow_steps_keep_their_increment():
    s = stepper(grow_after=0)
    for _ in range(3):
        s.increment()
        s.converged(iterations=9)
    assert s.dlam == 0.1 and s.lam == pytest.approx(0.3)


def test_a_failure_halves_the_increment_and_regrowth_stops_at_the_failed_one():
    s = stepper()
    s.increment()
    s.failed()  # 0.1 failed: 0.05, remember 0.1
    assert s.dlam == 0.05 and s.cuts == 1 and s.regrow_to == 0.1
    for _ in range(3):  # slow steps: no growth until grow_after = 3 of them in a row
        s.increment()
        s.converged(iterations=9)
    assert s.dlam == 0.1  # regrown to the Δλ that failed, not beyond
    for _ in range(3):
        s.increment()
        s.converged(iterations=9)
    assert s.dlam == 0.1


def test_cut_backs_are_limited_in_number_and_size():
    s = stepper(max_cutbacks=2)
    s.increment()
    assert s.can_cut()
    s.failed()
    s.failed()
    assert s.cuts == 2 and not s.can_cut()  # max_cutbacks reached
    t = stepper(min=0.04)
    t.increment()
    t.failed()  # 0.05
    assert not t.can_cut()  # halving again would go below min


def test_state_round_trip_resumes_the_same_sequence():
    a = stepper()
    a.increment()
    a.failed()
    a.increment()
    a.converged(iterations=9)
    b = stepper()
    b.load_state_dict(a.state_dict())
    for s in (a, b):
        s.increment()
        s.converged(iterations=9)
    assert (a.lam, a.dlam, a.streak, a.regrow_to) == (b.lam, b.dlam, b.streak, b.regrow_to)
