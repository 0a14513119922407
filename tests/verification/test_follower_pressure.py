"""The tangent of the sphere's system (volume with selective reduced
integration + follower pressure) against central finite differences of its
residual, at a deformed state with the pressure on."""
import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation


@pytest.mark.mpi
@pytest.mark.parametrize("formulation", ["displacement", "sri"])
@pytest.mark.parametrize("load_factor", [0.4, 5000.0])
def test_follower_pressure_tangent_matches_finite_differences(formulation, load_factor, out_dir):
    """λ = 0.4: the sphere's working pressure (0.004 MPa), where the load
    stiffness is a small part of the tangent; λ = 5000 (50 MPa): a pressure
    whose load stiffness is a large part, so that its linearisation is
    checked on its own merit."""
    sc = scene.load(ROOT / "scenes" / "sphere.toml",
                    ["mesh.n=4", "mesh.m=1", f"discretisation.formulation={formulation}", f"output.dir={out_dir}"])
    sim = Simulation(sc, MPI.COMM_WORLD, log=quiet)
    p = sim.problem
    sim.set_load_factor(load_factor)
    x = p.x
    rng = np.random.default_rng(1 + MPI.COMM_WORLD.rank)
    X = sim.V.tabulate_dof_coordinates()[: sim.V.dofmap.index_map.size_local]
    # an inflated, slightly perturbed state satisfying the symmetry conditions
    u = 0.2 * X + 0.05 * rng.standard_normal(X.shape)
    x.array[:] = u.ravel()
    bc_dofs = np.concatenate([bc.dof_indices()[0] for bc in sim.bcs])
    owned = bc_dofs[bc_dofs < x.array.size]
    x.array[owned] = 0.0
    b = p.b.duplicate()
    p.residual(None, x, b)
    p.jacobian(None, x, p.A, p.A)
    dx = x.duplicate()
    dx.array[:] = rng.standard_normal(x.array.size)
    dx.array[owned] = 0.0
    Jdx = x.duplicate()
    p.A.mult(dx, Jdx)
    h = 1e-6
    bp, bm = b.duplicate(), b.duplicate()
    xp, xm = x.copy(), x.copy()
    xp.axpy(h, dx)
    xm.axpy(-h, dx)
    p.residual(None, xp, bp)
    p.residual(None, xm, bm)
    fd = bp.copy()
    fd.axpy(-1.0, bm)
    fd.scale(1.0 / (2 * h))
    fd.axpy(-1.0, Jdx)
    assert fd.norm() <= 1e-6 * Jdx.norm()
    # the follower-pressure share of the tangent (zero without the pressure)
    sim.set_load_factor(0.0)
    p.jacobian(None, x, p.A, p.A)
    J0dx = x.duplicate()
    p.A.mult(dx, J0dx)
    J0dx.axpy(-1.0, Jdx)
    share = J0dx.norm() / Jdx.norm()
    assert share > (0.05 if load_factor > 1 else 1e-7)
