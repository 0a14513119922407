"""Augmented Lagrangian (Uzawa) for rigid contact: the penetration reaches
the gap tolerance whatever the penalty, in a bounded number of
augmentations, and the contact force tends to the penalty-free limit."""
import tomllib

import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import scene
from hypercontact.contact.penalty import indentation_modulus
from hypercontact.simulation import Simulation

from conftest import ROOT
from reference.augmentations import run_counting_augmentations

TOL = 1e-3  # mm: gap tolerance


def run(tmp_path, factor, enforcement):
    data = tomllib.loads((ROOT / "scenes" / "punch.toml").read_text())
    data["mesh"].update(n=8, m=2)
    data["output"]["xdmf"] = False
    for c in data["contact"]:
        c.pop("eps_n")
        c.update(penalty_factor=factor, enforcement=enforcement, gap_tolerance=TOL, max_augmentations=30)
    sc = scene.load(data, [f"output.dir={tmp_path}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    writer, augmentations = run_counting_augmentations(sim, tmp_path)
    return sim, writer, augmentations


@pytest.mark.parametrize("factor", [1.0, 10.0, 100.0, 1000.0])
def test_penetration_reaches_the_tolerance_for_four_decades_of_penalty(tmp_path, factor):
    sim, writer, augmentations = run(tmp_path, factor, "augmented_lagrangian")
    for c in sim.contacts:
        assert c.max_penetration(sim.u) <= TOL
    # bounded: fewer augmentations the stiffer the penalty, never the limit
    assert max(augmentations) < 30
    if factor >= 1000.0:
        assert max(augmentations) <= 2


def test_force_tends_to_the_penalty_free_limit(tmp_path):
    """With augmentation, a soft penalty gives the force of a penalty 1000 × as stiff
    (penetration ≤ 1e-3 mm in both) to 0.5 %; pure penalty with the soft one is off by more."""
    _, w_soft_al, _ = run(tmp_path / "al", 1.0, "augmented_lagrangian")
    _, w_stiff, _ = run(tmp_path / "stiff", 1000.0, "penalty")
    _, w_soft, _ = run(tmp_path / "soft", 1.0, "penalty")
    f_al, f_stiff, f_soft = (w.steps[-1]["punch_fz"] for w in (w_soft_al, w_stiff, w_soft))
    assert abs(f_al - f_stiff) < 5e-3 * abs(f_stiff)
    assert abs(f_soft - f_stiff) > 2 * abs(f_al - f_stiff)


def test_with_friction_the_gap_tolerance_is_reached_and_the_cone_holds(tmp_path):
    """μ1 = 0.3 under the punch, soft penalty, augmented: the penetration
    reaches the tolerance, and every slipping node's traction is on the cone
    of the augmented pressure, |t| = μ ⟨λ − ε_N g⟩ (to 1e-9)."""
    data = tomllib.loads((ROOT / "scenes" / "punch.toml").read_text())
    data["mesh"].update(n=8, m=2)
    data["output"]["xdmf"] = False
    for c in data["contact"]:
        c.pop("eps_n")
        # ε_N = 12 × E* / h ≈ 3.4 N/mm³, soft against the scene's 100; ε_T = ε_N lets the rim slip
        c.update(penalty_factor=12.0, enforcement="augmented_lagrangian", gap_tolerance=TOL, max_augmentations=30)
    h = data["mesh"]["size"][2] / data["mesh"]["m"]  # the plate's first layer
    data["contact"][0].update(mu=0.3, eps_t=12.0 * indentation_modulus("mooney_rivlin",
                                                                        data["material"]["parameters"]) / h)
    sc = scene.load(data, [f"output.dir={tmp_path}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    sim.run(out_dir=str(tmp_path))
    punch = sim.contacts[0]
    assert punch.max_penetration(sim.u) <= TOL
    state = punch.law.committed
    slipping = np.asarray(state.state) == 2
    assert np.count_nonzero(slipping) > 3
    pressure = np.asarray(punch.evaluate(sim.u).pressure)
    t = np.linalg.norm(np.asarray(state.traction), axis=1)
    assert np.allclose(t[slipping], 0.3 * pressure[slipping], rtol=1e-9, atol=1e-12)
    # the multipliers are the pressures: they carry the load, not the soft penalty
    assert np.all(pressure[slipping] > 5 * punch.eps_n * TOL)


@pytest.mark.parametrize("key, value", [("enforcement", "lagrange"), ("gap_tolerance", -1e-3),
                                        ("max_augmentations", 0)])
def test_bad_augmented_lagrangian_values_are_refused(key, value):
    """Deformable masters accept the augmented Lagrangian (tests/verification/test_augmented_lagrangian_surface.py);
    bad values of its keys are refused with the key's name, rigid or not."""
    for name in ("blocks.toml", "punch.toml"):
        data = tomllib.loads((ROOT / "scenes" / name).read_text())
        data["contact"][0].update(enforcement="augmented_lagrangian")
        scene.load(data)
        data["contact"][0][key] = value
        with pytest.raises(scene.SceneError, match=rf"contact\[0\]\.{key}"):
            scene.load(data)
