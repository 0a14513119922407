"""Automatic penalty ε_N = s · M / h (penalty.py): unit-free, so the same
scene in mm/MPa and in m/Pa gives the same dimensionless results."""
import copy
import tomllib

import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import scene
from hypercontact.contact.penalty import indentation_modulus
from hypercontact.scene import SceneError
from hypercontact.simulation import Simulation

from conftest import ROOT


def punch(scale_length=1.0, scale_stress=1.0):
    """The punch scene, coarse, automatic penalty, in scaled units."""
    data = tomllib.loads((ROOT / "scenes" / "punch.toml").read_text())
    data["mesh"].update(n=8, m=2, size=[v * scale_length for v in data["mesh"]["size"]])
    for k in ("alpha1", "alpha2", "K"):
        data["material"]["parameters"][k] *= scale_stress
    for c in data["contact"]:
        c.pop("eps_n")
        for key in ("lo", "hi", "point", "motion"):
            if key in c:
                c[key] = [v * scale_length for v in c[key]]
    data["output"]["probes"] = {name: [v * scale_length for v in p] for name, p in data["output"]["probes"].items()}
    data["output"]["xdmf"] = False
    return data


def run(data, out):
    sc = scene.load(data, [f"output.dir={out}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    writer = sim.run(out_dir=str(out))
    return sim, writer


def test_same_scene_in_mm_mpa_and_m_pa_gives_the_same_results(tmp_path):
    sim_mm, w_mm = run(punch(), tmp_path / "mm")
    sim_m, w_m = run(punch(1e-3, 1e6), tmp_path / "m")
    # ε_N [N/mm³] = 1e-9 ε_N [N/m³]: the same physical penalty
    for c_mm, c_m in zip(sim_mm.contact_settings, sim_m.contact_settings):
        assert c_m.eps_n == pytest.approx(1e9 * c_mm.eps_n, rel=1e-12)
    assert len(w_mm.steps) == len(w_m.steps)
    for a, b in zip(w_mm.steps, w_m.steps):
        assert b["punch_fz"] == pytest.approx(a["punch_fz"], rel=1e-8)  # N in both
        assert b["edge_uz"] == pytest.approx(1e-3 * a["edge_uz"], rel=1e-8)
        assert b["corner_uz"] == pytest.approx(1e-3 * a["corner_uz"], rel=1e-8)


def test_automatic_penalty_value(tmp_path):
    """ε_N = s M / h with M = E/(1 − ν²) (E and ν from K and μ) and h the first element
    layer's thickness (10 mm / 2 layers = 5 mm on the coarse punch)."""
    data = punch()
    data["contact"][1]["penalty_factor"] = 30.0
    sc = scene.load(data, [f"output.dir={tmp_path}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    p = sc["material"]["parameters"]
    K, mu = p["K"], 2.0 * (p["alpha1"] + p["alpha2"])
    E, nu = 9.0 * K * mu / (3.0 * K + mu), (3.0 * K - 2.0 * mu) / (2.0 * (3.0 * K + mu))
    M = E / (1.0 - nu ** 2)
    assert indentation_modulus("mooney_rivlin", p) == pytest.approx(M, rel=1e-14)
    assert sim.contact_settings[0].eps_n == pytest.approx(100.0 * M / 5.0, rel=1e-12)
    assert sim.contact_settings[1].eps_n == pytest.approx(30.0 * M / 5.0, rel=1e-12)
    assert sim.contacts[1].eps_n == sim.contact_settings[1].eps_n
    assert sc["contact"][0]["eps_n"] == 0.0  # derived values are returned, the scene stays as written
    assert any("automatic penalty" in e for e in sim.effects)


def test_automatic_penalty_needs_a_built_in_law(tmp_path):
    data = punch()
    law = tmp_path / "law.py"
    law.write_text("import ufl\ndef psi(F, c=1.0):\n    return c * ufl.tr(F.T * F)\n")
    data["material"] = {"law": f"python:{law}:psi", "parameters": {}}
    with pytest.raises(SceneError, match=r"contact\[0\]\.eps_n.*automatic penalty"):
        scene.load(copy.deepcopy(data), base_dir=tmp_path)


def test_automatic_tangential_penalty_value_and_cap(tmp_path):
    """With friction and eps_t = 0: ε_T = 10 G / h (G = 2(α1 + α2) of the Mooney law, h = 5 mm on the
    coarse punch), capped at ε_N; frictionless contacts keep ε_T = ε_N (unused); a given eps_t stands."""
    data = punch()
    data["contact"][1]["mu"] = 0.3          # the base: automatic ε_N and ε_T
    data["contact"][0].update(mu=0.3, eps_n=0.5)  # the punch: ε_N below 10 G / h caps ε_T
    sc = scene.load(data, [f"output.dir={tmp_path}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    p = sc["material"]["parameters"]
    G = 2.0 * (p["alpha1"] + p["alpha2"])
    base, top = sim.contact_settings[1], sim.contact_settings[0]
    assert base.eps_t == pytest.approx(10.0 * G / 5.0, rel=1e-12)
    assert base.eps_t < base.eps_n / 10.0
    assert top.eps_t == top.eps_n == 0.5
    assert sim.contacts[1].law.eps_t == base.eps_t
    assert any("ε_T = " in e for e in sim.effects)
    data["contact"][1]["eps_t"] = 7.0
    data["contact"][0]["mu"] = 0.0
    sim = Simulation(scene.load(data, [f"output.dir={tmp_path}"]), MPI.COMM_SELF, log=lambda *a, **k: None)
    assert sim.contact_settings[1].eps_t == 7.0
    assert sim.contact_settings[0].eps_t == sim.contact_settings[0].eps_n


def test_automatic_tangential_penalty_is_unit_free(tmp_path):
    """ε_T [N/mm³] = 1e-9 ε_T [N/m³], and the frictional punch's forces are the same in both units."""
    runs = []
    for scale in ((1.0, 1.0), (1e-3, 1e6)):
        data = punch(*scale)
        data["contact"][1]["mu"] = 0.3
        runs.append(run(data, tmp_path / f"u{scale[0]:g}"))
    (sim_mm, w_mm), (sim_m, w_m) = runs
    assert sim_m.contact_settings[1].eps_t == pytest.approx(1e9 * sim_mm.contact_settings[1].eps_t, rel=1e-12)
    assert len(w_mm.steps) == len(w_m.steps)
    for a, b in zip(w_mm.steps, w_m.steps):
        assert b["punch_fz"] == pytest.approx(a["punch_fz"], rel=1e-8)
        assert b["base_fx"] == pytest.approx(a["base_fx"], rel=1e-7, abs=1e-9 * abs(a["punch_fz"]))
