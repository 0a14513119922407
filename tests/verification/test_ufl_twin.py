"""The C++ rigid-plane penalty equals the same term written in UFL.

Twin: R = ∫_Γ ε_N ⟨g⟩₋ n·v dA with g = (X + u − p)·n, integrated with the
vertex (2-point Gauss–Lobatto) rule, which is exactly nodal integration
with A_i = ∫ N_i dA on the rectangular facets of a box mesh."""
import numpy as np
import pytest
import ufl
from conftest import quiet
from mpi4py import MPI
from petsc4py import PETSc

from hypercontact import _dolfinx as dfx
from hypercontact import scene
from hypercontact.simulation import Simulation

EPS = 7.0
POINT = np.array([0.1, -0.2, 0.05])
NORMAL = np.array([0.1, 0.2, 1.0]) / np.linalg.norm([0.1, 0.2, 1.0])


@pytest.mark.mpi
def test_rigid_plane_residual_and_tangent_match_ufl(tmp_path):
    sc = scene.load({
        "mesh": {"builder": "box", "size": [1.0, 1.0, 0.5], "n": 4, "m": 2},
        "material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 10.0}},
        "contact": [{"name": "base", "surface": "zmin", "obstacle": "plane",
                     "point": POINT.tolist(), "normal": NORMAL.tolist(), "eps_n": EPS}],
        "output": {"xdmf": False},
    })
    sim = Simulation(sc, MPI.COMM_WORLD, log=quiet)
    u, V, (contact,) = sim.u, sim.V, sim.contacts
    # a state in which part of the surface penetrates the plane and part is open
    u.interpolate(lambda x: np.vstack([0.03 * x[1] * x[2], -0.02 * x[0], -0.1 - 0.2 * x[0] * x[1] + 0.05 * x[1]]))
    dfx.update_ghosts(u)

    # C++ kernel
    b_cpp = dfx.create_vector(sim.problem.R)
    with b_cpp.localForm() as bl:
        bl.set(0.0)
        contact.prepare(u)
        contact.add_residual(bl.array_w)
    b_cpp.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    A_cpp = dfx.create_matrix(sim.problem.J)
    A_cpp.zeroEntries()
    contact.add_tangent(A_cpp)
    A_cpp.assemble()

    # UFL twin
    v, du = ufl.TestFunction(V), ufl.TrialFunction(V)
    X = ufl.SpatialCoordinate(V.mesh)
    n = ufl.as_vector(NORMAL.tolist())
    g = ufl.dot(X + u - ufl.as_vector(POINT.tolist()), n)
    ds = dfx.facet_integration_measure(V.mesh, sim.body.facet_tags, quadrature_degree=1, rule="GLL")
    R = EPS * ufl.conditional(ufl.le(g, 0.0), g, 0.0) * ufl.dot(n, v) * ds(sim.body.surfaces["zmin"])
    R_form = dfx.compile_form(R)
    J_form = dfx.compile_form(ufl.derivative(R, u, du))
    b_ufl = dfx.assemble_vector_owned(R_form)
    import dolfinx.fem.petsc
    A_ufl = dolfinx.fem.petsc.assemble_matrix(J_form)
    A_ufl.assemble()

    closed = MPI.COMM_WORLD.allreduce(contact.evaluate(u).num_closed, op=MPI.SUM)
    assert 0 < closed < contact.geometry.num_points, "the state must have open and closed nodes"
    scale = b_ufl.norm()
    assert scale > 0
    b_ufl.axpy(-1.0, b_cpp)
    assert b_ufl.norm() <= 1e-12 * scale
    scale = A_ufl.norm()
    A_ufl.axpy(-1.0, A_cpp, structure=PETSc.Mat.Structure.DIFFERENT_NONZERO_PATTERN)
    assert A_ufl.norm() <= 1e-12 * scale
