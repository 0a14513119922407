"""Volumetric energies Ψ0(J) (material parameter ``volumetric``): the paper's
K/2 (J − 1)² and two that grow without bound as J → 0, all with the same
small-strain bulk modulus K; the mixed coupling that gives each back; a
homogeneous block against the closed form; and a bonded block squeezed by a
rigid plane that the paper's term cannot finish and the log term can."""
import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI
from scipy.optimize import minimize_scalar

from hypercontact import cli, scene
from hypercontact.forms import materials, volume
from hypercontact.simulation import Simulation, StepFailure
from reference.homogeneous import compressed_block, neo_hookean_principal
from reference.block import block_scene

K = 3.0
VARIANTS = list(materials.VOLUMETRIC)
GROWING = [v for v in VARIANTS if v != "quadratic"]


def psi0(v, J):
    """Ψ0(J) evaluated through UFL with a constant J (UFL folds it to a float)."""
    return float(materials.volumetric_penalty(J, K, v))


@pytest.mark.parametrize("v", VARIANTS)
def test_same_small_strain_bulk_modulus(v):
    h = 1e-4
    assert psi0(v, 1.0) == 0.0
    assert (psi0(v, 1 + h) - psi0(v, 1 - h)) / (2 * h) == pytest.approx(0.0, abs=1e-7)
    second = (psi0(v, 1 + h) - 2 * psi0(v, 1.0) + psi0(v, 1 - h)) / h**2
    assert second == pytest.approx(K, rel=1e-6)


@pytest.mark.parametrize("v", GROWING)
def test_grows_without_bound_as_J_goes_to_zero(v):
    """At least like K/2 |ln J|: squaring J (J < 1) at least doubles the rise."""
    rises = np.diff([psi0(v, J) for J in (1e-2, 1e-4, 1e-8, 1e-16)])
    assert np.all(rises > 0) and np.all(rises[1:] >= 1.9 * rises[:-1])
    assert psi0(v, 1e-16) > 10 * K


def test_the_papers_term_stays_bounded():
    assert psi0("quadratic", 1e-16) == pytest.approx(K / 2)


@pytest.mark.parametrize("v", VARIANTS)
def test_mixed_coupling_gives_the_energy_back(v):
    """sup_p p G(J) − Ψ0*(p) = Ψ0(J): eliminating the pressure returns the law."""
    G, _, conjugate = volume.MIXED_COUPLING[v]
    for J in (0.3, 0.8, 1.0, 1.5):
        best = minimize_scalar(lambda p: -(p * float(G(J)) - float(conjugate(p, K))),
                               bounds=(-50 * K, 50 * K), method="bounded", options={"xatol": 1e-10})
        assert -best.fun == pytest.approx(psi0(v, J), rel=1e-7, abs=1e-10)


def test_unknown_volumetric_names_the_key(tmp_path, capsys):
    assert cli.main(["check", str(ROOT / "scenes" / "punch.toml"), "--set", "material.parameters.volumetric=cubic"]) == 2
    err = capsys.readouterr().err
    assert "'material.parameters.volumetric': expected \"quadratic\", \"log\" or \"log_quadratic\"" in err


def test_default_is_the_papers_term():
    assert scene.load(ROOT / "scenes" / "punch.toml")["material"]["parameters"]["volumetric"] == "quadratic"


NH = dict(mu=1.0, K=K)


@pytest.mark.parametrize("v, formulation", [(v, "displacement") for v in VARIANTS] + [("log", "sri")])
def test_homogeneous_block_matches_closed_form(v, formulation, out_dir):
    """The block between two frictionless planes (test_block_compression)
    with a neo-Hookean law: the force against the closed form."""
    sc = block_scene(out_dir)
    sc["material"] = {"law": "neo_hookean", "parameters": {**NH, "volumetric": v}}
    sc["discretisation"] = {"formulation": formulation}
    sim = Simulation(scene.load(sc), MPI.COMM_WORLD, log=quiet)
    sim.run()
    _, _, P3 = compressed_block(lambda a, b, c: neo_hookean_principal(a, b, c, **NH, volumetric=v), 1.0, 0.2, 50.0)
    assert sim.contacts[0].force(sim.u)[2] == pytest.approx(P3, rel=1e-6)


@pytest.mark.parametrize("v", GROWING)
def test_mixed_formulation_homogeneous_stretch(v, out_dir):
    """Mixed u–p, Q2–Q1: a block compressed to λ3 = 0.6 by its top face with
    free sides expands laterally as the closed form says."""
    sc = {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 1, "m": 1},
        "material": {"law": "neo_hookean", "parameters": {**NH, "volumetric": v}},
        "discretisation": {"degree": 2, "quadrature_degree": 4, "formulation": "mixed"},
        "bc": [{"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]},
               {"surface": "zmin", "fix": ["z"]}, {"surface": "zmax", "fix": ["z"], "motion": [0, 0, -0.4]}],
        "steps": {"initial": 0.25, "max": 0.25},
        "solver": {"rtol": 1e-12, "atol": 1e-12},
        "output": {"dir": str(out_dir), "xdmf": False, "probes": {"corner": [1.0, 1.0, 1.0]}},
    }
    writer = Simulation(scene.load(sc), MPI.COMM_WORLD, log=quiet).run()
    psi = lambda a, b, c: neo_hookean_principal(a, b, c, **NH, volumetric=v)
    lateral = compressed_block(psi, 1.0, 0.4, np.inf)[0]
    assert 1.0 + writer.steps[-1]["corner_ux"] == pytest.approx(lateral, rel=1e-8)


def bonded_block(out, volumetric, d=0.7):
    """Quarter of a 2 × 2 × 1 neo-Hookean block (K/μ = 3) bonded to a rigid
    base, squeezed by a frictionless rigid plane to 30 % of its height."""
    return {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 4, "m": 4},
        "material": {"law": "neo_hookean", "parameters": {**NH, "volumetric": volumetric}},
        "bc": [{"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]},
               {"surface": "zmin", "fix": ["x", "y", "z"]}],
        "contact": [{"name": "top", "surface": "zmax", "obstacle": "plane", "point": [0, 0, 1.0],
                     "normal": [0, 0, -1.0], "motion": [0, 0, -d]}],
        "steps": {"initial": 0.1, "max": 0.25},
        "output": {"dir": str(out), "xdmf": False},
    }


def test_papers_term_stops_before_the_end(out_dir):
    sim = Simulation(scene.load(bonded_block(out_dir, "quadratic")), MPI.COMM_WORLD, log=quiet)
    with pytest.raises(StepFailure, match="did not converge"):
        sim.run()


def test_log_term_finishes(out_dir):
    messages = []
    writer = Simulation(scene.load(bonded_block(out_dir, "log")), MPI.COMM_WORLD, log=messages.append).run()
    assert writer.steps[-1]["load_factor"] == pytest.approx(1.0)
    assert not any("NAN" in m for m in messages)


def test_one_list_of_volumetric_energies():
    assert list(scene.VOLUMETRIC) == list(materials.VOLUMETRIC) == list(volume.MIXED_COUPLING)
    assert scene.STRING_PARAMETERS["volumetric"] == tuple(materials.VOLUMETRIC)
