"""Model.symmetric_tangent picks MUMPS's LDLᵀ over LU: the flag must be true
only where the assembled tangent is symmetric, entry by entry, at a state in
contact, and false where it is not (so the check is not vacuous)."""
import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

SMALL = ["mesh.n=4", "mesh.m=1", "output.xdmf=false"]


def tangent_asymmetry(name, overrides, out):
    """(symmetric_tangent, effects, max|A − Aᵀ| / max|A|) at the end of a run."""
    sc = scene.load(ROOT / "scenes" / f"{name}.toml", SMALL + overrides + [f"output.dir={out}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=quiet)
    sim.run()
    problem = sim.model.problem
    x = sim.model.w.vector.copy()
    problem.jacobian(None, x, problem.A, problem.A)
    A = problem.A.convert("dense").getDenseArray()
    assert sim.model.contacts and max(c.num_closed() for c in sim.model.contacts) > 0  # a state in contact
    return sim.model.symmetric_tangent, sim.effects, np.abs(A - A.T).max() / np.abs(A).max()


@pytest.mark.parametrize("name, overrides", [
    ("punch", []),  # rigid box (its edges: ∂n/∂x ≠ 0) and rigid plane, penalty
    ("punch", ["discretisation.formulation=sri"]),
    ("punch", ["contact.0.enforcement=augmented_lagrangian", "contact.1.enforcement=augmented_lagrangian"]),
    ("punch_mu0_0", []),  # μ = 0 given explicitly: no friction law, symmetric
])
def test_symmetric_where_flagged(tmp_path, name, overrides):
    symmetric, effects, asym = tangent_asymmetry(name, overrides, tmp_path)
    assert symmetric and "direct linear solver (MUMPS LDLᵀ, symmetric tangent)" in effects
    assert asym <= 1e-13


@pytest.mark.parametrize("name, overrides", [
    # Coulomb friction with slipping points (punch_mu0.3_0 at this mesh ends all stuck,
    # and the stick tangent ε_T (I − n nᵀ) is symmetric): the slip tangent is not
    ("punch_mu0_1", []),
    ("punch_mu1_0", []),
])
def test_not_flagged_where_not_symmetric(tmp_path, name, overrides):
    symmetric, effects, asym = tangent_asymmetry(name, overrides, tmp_path)
    assert not symmetric and "direct linear solver (MUMPS LU)" in effects
    assert asym > 1e-6


def test_the_scene_can_ask_for_lu(tmp_path):
    """solver.petsc's pc_type wins over the automatic choice, and the effects say so."""
    sc = scene.load(ROOT / "scenes" / "punch.toml", SMALL + ['solver.petsc={pc_type="lu"}', f"output.dir={tmp_path}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=quiet)
    assert sim.model.symmetric_tangent and "direct linear solver (MUMPS LU)" in sim.effects
    sim.run()
    assert sim.snes.getKSP().getPC().getType() == "lu"
