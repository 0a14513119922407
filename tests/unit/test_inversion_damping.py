"""InversionDamping, the line-search pre-check that halves a Newton
correction whose full step would invert an element, against closed forms
on the unit cube: a correction that compresses it uniformly by s in z
leaves J = 1 − α s at the step fraction α, so the halvings needed are the
smallest k ≥ 0 with 1 − s 2⁻ᵏ > 0."""
import math

import numpy as np
import pytest
from dolfinx import fem, mesh
from mpi4py import MPI

from hypercontact.model.inversion import InversionDamping


def cube_correction(s, cells=2):
    """(damping, x, y): the displacement x = 0 and a correction y with x − y = (0, 0, −s z)."""
    msh = mesh.create_unit_cube(MPI.COMM_WORLD, cells, cells, cells, mesh.CellType.hexahedron)
    V = fem.VectorFunctionSpace(msh, ("Lagrange", 1))
    w = fem.Function(V)
    damping = InversionDamping(w, w, None, quadrature_degree=2)
    direction = fem.Function(V)
    direction.interpolate(lambda X: np.vstack([0 * X[0], 0 * X[1], s * X[2]]))
    return damping, w.vector.copy(), direction.vector.copy()


def expected_halvings(s):
    return 0 if s < 1 else math.floor(math.log2(s)) + 1


@pytest.mark.mpi
@pytest.mark.parametrize("s", [0.5, 0.99, 1.01, 1.5, 2.4, 7.9, 100.0])  # none on a boundary J = 0
def test_correction_is_halved_exactly_as_often_as_the_closed_form_needs(s):
    damping, x, y = cube_correction(s)
    y0 = y.copy()
    k = expected_halvings(s)
    changed = damping(x, y)
    assert changed == (k > 0)
    assert damping.halvings == ([k] if k else [])
    assert np.allclose(y.array, 0.5 ** k * y0.array, rtol=0, atol=1e-15)
    assert np.all(x.array == 0.0)  # the iterate is not touched


def test_an_admissible_step_is_left_bit_for_bit():
    damping, x, y = cube_correction(0.3)
    before = y.array.copy()
    assert damping(x, y) is False
    assert np.array_equal(y.array, before) and damping.halvings == []


def test_a_correction_no_halving_makes_admissible_is_left_as_it_was():
    """s = 2¹² needs 13 halvings, more than the 10 allowed: the correction is
    returned unchanged (the solve then fails as without damping)."""
    damping, x, y = cube_correction(2.0 ** 12)
    before = y.array.copy()
    assert damping(x, y) is False
    assert np.array_equal(y.array, before) and damping.halvings == []


def test_mixed_unknowns_are_checked_through_their_displacement():
    """Taylor–Hood (u, p) on the cube: the displacement part of the trial is
    what is checked (the pressure does not enter J), with the same closed form."""
    import ufl

    msh = mesh.create_unit_cube(MPI.COMM_WORLD, 2, 2, 2, mesh.CellType.hexahedron)
    cell = msh.ufl_cell()
    W = fem.FunctionSpace(msh, ufl.MixedElement([ufl.VectorElement("Lagrange", cell, 2),
                                                  ufl.FiniteElement("Lagrange", cell, 1)]))
    V, u_dofs = W.sub(0).collapse()
    w, u, direction = fem.Function(W), fem.Function(V), fem.Function(W)
    s = 2.4
    direction.sub(0).interpolate(lambda X: np.vstack([0 * X[0], 0 * X[1], s * X[2]]))
    direction.sub(1).interpolate(lambda X: 1e3 * np.ones_like(X[0]))  # a pressure correction: no effect on J
    damping = InversionDamping(w, u, u_dofs, quadrature_degree=4)
    x, y = w.vector.copy(), direction.vector.copy()
    y0 = y.copy()
    assert damping(x, y) is True and damping.halvings == [expected_halvings(s)]
    assert np.allclose(y.array, 0.25 * y0.array, rtol=0, atol=1e-12)
