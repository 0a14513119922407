"""The two guards of a continuation step (docs/method.md, continuation): a
converged arc-length increment that points against the last step's went back
along the path and is refused; a Newton iteration whose residual alternates
between two values (contact points flipping between open and closed) stops
early so that the step is cut back instead of spending its iterations."""
import numpy as np
import pytest
from petsc4py import PETSc

from hypercontact.solve.continuation import (ArcLengthConstraint, ContinuationFailure, DisplacementConstraint,
                                             two_cycle)


def vec(values):
    return PETSc.Vec().createWithArray(np.asarray(values, dtype=float), comm=PETSc.COMM_SELF)


def test_an_increment_against_the_last_step_is_refused():
    arc = ArcLengthConstraint(1.0)
    last = vec([1.0, 0.0, 0.0])
    arc.check_forward(vec([0.6, 0.8, 0.0]), last)  # ahead (cos 0.6)
    arc.check_forward(vec([0.0, 1.0, 0.0]), last)  # square to it: a turn, not a step back
    arc.check_forward(vec([-1.0, 0.0, 0.0]), None)  # the first step has nothing to compare with
    with pytest.raises(ContinuationFailure, match=r"behind its start on the path .*cos = -0\.600"):
        arc.check_forward(vec([-0.6, 0.8, 0.0]), last)


def test_displacement_control_moves_forward_by_construction():
    DisplacementConstraint.check_forward(None, vec([-1.0, 0.0]), vec([1.0, 0.0]))


@pytest.mark.parametrize("norms, cycles", [
    ([1.0, 20.0, 1.0, 20.0, 1.0], True),                 # two values, each repeated
    ([50.0, 1.0, 20.0, 1.0, 20.0, 1.0], True),           # after a start elsewhere
    ([1.0, 20.0, 1.0, 20.0], False),                     # too short to tell
    ([1.0, 20.0, 1.0, 20.0, 0.5], False),                # the low value falls: converging
    ([1.0, 1.5, 1.0, 1.5, 1.0], False),                  # the two too close: stagnation, not flipping
    ([1e-1, 1e-2, 1e-4, 1e-8, 1e-16], False),            # quadratic convergence
    ([1.0, 20.0, 1.005, 20.1, 1.0], True),               # equal to 1 %
    ([1.0, 20.0, 1.05, 20.0, 1.0], False),               # not equal to 1 %
])
def test_a_two_cycle_is_two_values_alternating(norms, cycles):
    assert two_cycle(norms) is cycles
