"""Dead tractions, body forces and prescribed displacements on a block in a
homogeneous state, against closed forms and equilibrium."""
import pytest
from conftest import quiet
from mpi4py import MPI
from scipy.optimize import brentq

from hypercontact import scene
from hypercontact.simulation import Simulation
from reference.homogeneous import mooney_rivlin_principal, nominal_stress

PARAMS = dict(alpha1=0.1863, alpha2=0.0098, K=5.0)


def psi(a, b, c):
    return mooney_rivlin_principal(a, b, c, **PARAMS)


def lateral_stretch(l3):
    """λ_lat with P_1(λ_lat, λ_lat, λ3) = 0 (free lateral faces)."""
    return brentq(lambda lat: nominal_stress(psi, (lat, lat, l3), 0), 0.5, 2.0, xtol=1e-15)


def block(out, **extra):
    data = {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 2, "m": 2},
        "material": {"law": "mooney_rivlin", "parameters": PARAMS},
        "bc": [{"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]}],
        "contact": [{"name": "base", "surface": "zmin", "obstacle": "plane", "eps_n": 50.0}],
        "steps": {"initial": 0.5, "max": 0.5},
        "solver": {"rtol": 1e-12, "atol": 1e-13},
        "output": {"dir": str(out), "xdmf": False, "probes": {"corner": [1.0, 1.0, 1.0]}},
    }
    data.update(extra)
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet)
    return sim, sim.run()


@pytest.mark.mpi
def test_dead_traction_gives_the_closed_form_uniaxial_state(out_dir):
    t = -0.05  # MPa per reference area, compressive
    sim, writer = block(out_dir, traction=[{"surface": "zmax", "value": [0.0, 0.0, t]}])
    assert "1 traction" in sim.effects
    f_base = writer.steps[-1]["base_fz"]
    assert f_base == pytest.approx(-t * 1.0, rel=1e-9)  # equilibrium with the base
    l3 = brentq(lambda s: nominal_stress(psi, (lateral_stretch(s), lateral_stretch(s), s), 2) - t, 0.5, 1.0,
                xtol=1e-15)
    corner = writer.steps[-1]
    assert 1 + corner["corner_ux"] == pytest.approx(lateral_stretch(l3), rel=1e-6)
    gap = t / 50.0  # the base penalty gap under the nominal pressure −t
    assert 1 + corner["corner_uz"] == pytest.approx(gap + l3, rel=1e-6)


@pytest.mark.mpi
def test_body_force_is_carried_by_the_base(out_dir):
    b = [0.0, 0.0, -0.02]  # N/mm³
    sim, writer = block(out_dir, body_force=[{"value": b}])
    assert "1 body force" in sim.effects
    assert writer.steps[-1]["base_fz"] == pytest.approx(0.02 * 1.0, rel=1e-9)
    assert writer.steps[-1]["base_fx"] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.mpi
def test_prescribed_displacement_gives_the_closed_form_lateral_stretch(out_dir):
    d = 0.2
    sim, writer = block(out_dir, contact=[], bc=[
        {"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]},
        {"surface": "zmin", "fix": ["z"]}, {"surface": "zmax", "fix": ["z"], "motion": [0.0, 0.0, -d]}])
    assert "1 prescribed displacement" in sim.effects
    last = writer.steps[-1]
    assert last["corner_uz"] == pytest.approx(-d, rel=1e-12)
    assert 1 + last["corner_ux"] == pytest.approx(lateral_stretch(1 - d), rel=1e-6)
    assert len(writer.steps) == 2  # λ = 0.5 then 1: the motion follows the load factor


def test_motion_of_a_free_component_is_rejected(tmp_path):
    with pytest.raises(scene.SceneError, match=r"bc\[0\].motion.*moves x"):
        scene.load({"material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 1.0}},
                    "bc": [{"surface": "xmin", "fix": ["z"], "motion": [0.1, 0.0, 0.0]}],
                    "output": {"dir": str(tmp_path)}})
