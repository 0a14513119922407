"""The tangent's inertia as a diagnosis (NewtonSolver.negative_eigenvalues):
with a symmetric tangent factorised by MUMPS as LDLᵀ, the number of negative
pivots is the number of negative eigenvalues (Sylvester's law of inertia).
Checked against a dense symmetric eigensolver (LAPACK through numpy) on a
matrix with a known count, and on a path whose equilibrium turns unstable: a
plate wrapping round a punch edge rounded with r = 1 mm on cells about as
large (docs/studies.md), where the last converged state's tangent has
negative eigenvalues and the stop message says so."""
import json

import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation
from hypercontact.solve.load_stepping import StepFailure
from hypercontact.solve.newton_solver import NewtonSolver

SMALL = ["mesh.n=4", "mesh.m=1", "output.xdmf=false", "steps.initial=0.5", "steps.max=0.5"]


def test_negative_pivots_are_the_negative_eigenvalues(tmp_path):
    """A − σI with σ between the 3rd and 4th smallest eigenvalues of the punch's
    tangent has exactly three negative eigenvalues; its LDLᵀ says three."""
    sc = scene.load(ROOT / "scenes" / "punch.toml", SMALL + [f"output.dir={tmp_path}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=quiet)
    sim.run()
    model = sim.model
    assert model.symmetric_tangent
    newton = NewtonSolver(model, sc["solver"], sim.timers)
    assert newton.negative_eigenvalues() is None  # nothing factorised yet
    p = model.problem
    model.w.vector.copy(p.x)
    p.residual(None, p.x, p.b)
    p.jacobian(None, p.x, p.A, p.A)
    n = p.A.getSize()[0]
    dense = p.A.getValues(range(n), range(n))
    assert np.abs(dense - dense.T).max() <= 1e-12 * np.abs(dense).max()
    eigenvalues = np.linalg.eigvalsh(dense)
    assert eigenvalues[0] > 0  # the converged punch is a stable equilibrium
    for k in (0, 3):
        sigma = 0.0 if k == 0 else 0.5 * (eigenvalues[k - 1] + eigenvalues[k])
        shifted = p.A.copy()
        shifted.shift(-sigma)
        ksp = newton.snes.getKSP()
        ksp.setOperators(shifted)
        ksp.setUp()
        assert newton.negative_eigenvalues() == int(np.sum(eigenvalues < sigma)) == k


def test_the_mixed_formulation_counts_only_unstable_modes(tmp_path):
    """The mixed u–p tangent is a saddle point: at a stable state it has one
    negative eigenvalue per pressure unknown and no other. The count reported
    leaves those out: 0 on the punch with Q2–Q1 elements, while the dense
    eigensolver finds exactly Model.pressure_unknowns negative eigenvalues."""
    sc = scene.load(ROOT / "scenes" / "punch.toml", [
        "mesh.n=2", "mesh.m=1", "discretisation.degree=2", "discretisation.formulation=mixed",
        "discretisation.quadrature_degree=4", "output.xdmf=false", "steps.initial=0.5", "steps.max=0.5",
        f"output.dir={tmp_path}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=quiet)
    writer = sim.run()
    model = sim.model
    assert model.symmetric_tangent
    assert model.pressure_unknowns == 3 * 3 * 2  # the Q1 pressure's nodes of the 2 × 2 × 1 mesh
    assert [s["negative_eigenvalues"] for s in writer.steps] == [0] * len(writer.steps)
    p = model.problem
    model.w.vector.copy(p.x)
    p.residual(None, p.x, p.b)
    p.jacobian(None, p.x, p.A, p.A)
    n = p.A.getSize()[0]
    eigenvalues = np.linalg.eigvalsh(p.A.getValues(range(n), range(n)))
    assert int(np.sum(eigenvalues < 0)) == model.pressure_unknowns
    newton = NewtonSolver(model, sc["solver"], sim.timers)
    ksp = newton.snes.getKSP()
    ksp.setOperators(p.A)
    ksp.setUp()
    assert newton.negative_eigenvalues() == 0


def test_a_non_symmetric_tangent_has_no_inertia_to_report(tmp_path):
    """With friction the tangent is factorised by LU: no count, no key."""
    sc = scene.load(ROOT / "scenes" / "punch_mu0.3_0.toml", SMALL + [f"output.dir={tmp_path}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=quiet)
    writer = sim.run()
    assert not sim.model.symmetric_tangent
    assert all("negative_eigenvalues" not in s for s in writer.steps)


def test_an_unstable_equilibrium_is_diagnosed(tmp_path):
    """The frictionless punch with its edge rounded by the blended profile,
    r = 1 mm, on the graded 8 × 8 × 2 plate: the first steps are stable, then
    the wrapping surface's tangent turns indefinite and the path stops with
    that diagnosis; every converged step and failed attempt carries its count."""
    sc = scene.load(ROOT / "scenes" / "punch.toml", [
        "mesh.n=8", "mesh.m=2", "mesh.grading=[2.0, 2.0, 2.0]", "mesh.focus=[20.0, 20.0, 10.0]",
        "contact.0.eps_n=0", "contact.1.eps_n=0", "contact.0.edge_radius=1.0", "contact.0.edge_profile=blended",
        "output.xdmf=false", f"output.dir={tmp_path}"])
    lines = []
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: lines.append(" ".join(map(str, a))))
    with pytest.raises(StepFailure, match=r"the last converged step's tangent had \d+ negative eigenvalues?: that "
                                          r"equilibrium is unstable"):
        sim.run()
    summary = json.loads((tmp_path / "summary.json").read_text())
    counts = [s["negative_eigenvalues"] for s in summary["steps"]]
    assert counts[0] == 0 and max(counts) >= 1 and counts[-1] >= 1, counts
    assert all("negative_eigenvalues" in f for f in summary["failed_attempts"])
    # the console says so when it happens, once per change of the count
    warnings = [line for line in lines if "negative eigenvalue" in line and line.startswith("   the tangent has")]
    changes = sum(1 for a, b in zip([0] + counts, counts) if a != b and b > 0)
    assert len(warnings) == changes >= 1
