"""Convergence rates on a smooth problem with a known solution (a
manufactured solution): the displacement formulation's L2 error falls at
order degree + 1 (2 for trilinear, 3 for triquadratic hexahedra).

u_ex = a (sin(πX) sin(πY) Z, …) on the unit cube, neo-Hookean, clamped
(u = u_ex) on the whole boundary, and the body force b = −Div P(F(u_ex))
computed by UFL from the same law — so the only error is the
discretisation's."""
import numpy as np
import pytest
import ufl
from dolfinx import fem, mesh
from dolfinx.fem.petsc import NonlinearProblem
from dolfinx.nls.petsc import NewtonSolver
from mpi4py import MPI
from petsc4py import PETSc

from hypercontact.forms import materials, volume

PARAMS = dict(mu=1.0, K=5.0)


def l2_error(n, degree):
    comm = MPI.COMM_SELF
    msh = mesh.create_unit_cube(comm, n, n, n, mesh.CellType.hexahedron)
    V = fem.VectorFunctionSpace(msh, ("Lagrange", degree))
    X = ufl.SpatialCoordinate(msh)
    a = 0.1
    u_ex = a * ufl.as_vector((ufl.sin(ufl.pi * X[0]) * ufl.sin(ufl.pi * X[1]) * X[2],
                              ufl.sin(ufl.pi * X[1]) * X[0] ** 2,
                              ufl.cos(ufl.pi * X[0]) * X[1] * X[2]))
    psi = materials.LAWS["neo_hookean"][0]
    F_ex = ufl.variable(ufl.Identity(3) + ufl.grad(u_ex))
    P_ex = ufl.diff(psi(F_ex, **PARAMS), F_ex)
    body = -ufl.div(P_ex)
    u = fem.Function(V)
    qdeg = 2 * degree + 2
    R, J = volume.displacement_forms(u, psi, PARAMS, qdeg)
    v = ufl.TestFunction(V)
    R = R - ufl.inner(body, v) * ufl.dx(metadata={"quadrature_degree": qdeg})
    boundary = mesh.locate_entities_boundary(msh, 2, lambda x: np.full(x.shape[1], True))
    u_bc = fem.Function(V)
    u_bc.interpolate(fem.Expression(u_ex, V.element.interpolation_points()))
    bc = fem.dirichletbc(u_bc, fem.locate_dofs_topological(V, 2, boundary))
    problem = NonlinearProblem(R, u, bcs=[bc], J=J)
    solver = NewtonSolver(comm, problem)
    solver.rtol, solver.atol = 1e-12, 1e-12
    ksp = solver.krylov_solver
    ksp.setType("preonly")
    ksp.getPC().setType("lu")
    ksp.getPC().setFactorSolverType("mumps")
    its, converged = solver.solve(u)
    assert converged
    err = fem.form(ufl.inner(u - u_ex, u - u_ex) * ufl.dx(metadata={"quadrature_degree": qdeg + 2}))
    return np.sqrt(fem.assemble_scalar(err))


@pytest.mark.parametrize("degree, meshes, expected", [(1, (4, 8), 2.0), (2, (2, 4), 3.0)])
def test_l2_error_falls_at_degree_plus_one(degree, meshes, expected):
    e_coarse, e_fine = (l2_error(n, degree) for n in meshes)
    rate = np.log(e_coarse / e_fine) / np.log(meshes[1] / meshes[0])
    print(f"degree {degree}: L2 errors {e_coarse:.3e} -> {e_fine:.3e}, rate {rate:.2f}")
    assert rate > expected - 0.3
