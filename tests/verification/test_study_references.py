"""The study command's field references: "hertz:a|p0|delta" (Hertz's closed
form at each case's force) and "patch:sigma_zz|pressure" (the contact patch
test's spread, reference 0). Checked against numbers worked out by hand and
against the result fields re-measured here without the study code."""
import csv
import math

import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import cli, hertz, scene
from hypercontact.simulation import Simulation
from reference.patch_spread import sigma_zz_spread  # the patch test's own σ_zz spread (UFL, by cell)

# Steel ball on a steel plane, both E = 210 GPa, ν = 0.3; R = 10 mm, F = 100 N (units mm, N, MPa).
# By hand: E* = E / (2 (1 − ν²)) = 210000 / 1.82 = 115384.615 MPa;
# a = (3 F R / 4E*)^(1/3) = (3000 / 461538.46)^(1/3) = 0.0065^(1/3) = 0.186626 mm;
# p0 = 3F / (2π a²) = 300 / (2π · 0.0348294) = 1370.87 MPa; δ = a²/R = 0.00348294 mm.
STEEL = dict(E=210000.0, nu=0.3, R=10.0, F=100.0, E_star=115384.615, a=0.186626, p0=1370.87, delta=0.00348294)


def test_hertz_closed_form_matches_the_textbook_numbers():
    s = STEEL
    E_star = hertz.contact_modulus((s["E"], s["nu"]), (s["E"], s["nu"]))
    assert E_star == pytest.approx(s["E_star"], rel=1e-6)
    a, p0, delta = hertz.closed_form(s["F"], s["R"], E_star)
    assert a == pytest.approx(s["a"], rel=1e-5)
    assert p0 == pytest.approx(s["p0"], rel=1e-5)
    assert delta == pytest.approx(s["delta"], rel=1e-5)
    # the other textbook forms: p0 = (6 F E*² / (π³ R²))^(1/3), δ = (9 F² / (16 R E*²))^(1/3), p0 = 3/2 · F/(π a²)
    assert p0 == pytest.approx((6 * s["F"] * E_star ** 2 / (math.pi ** 3 * s["R"] ** 2)) ** (1 / 3), rel=1e-12)
    assert delta == pytest.approx((9 * s["F"] ** 2 / (16 * s["R"] * E_star ** 2)) ** (1 / 3), rel=1e-12)
    assert p0 == pytest.approx(1.5 * s["F"] / (math.pi * a ** 2), rel=1e-12)
    # a rigid plane: E* = E / (1 − ν²), twice the two-body value
    assert hertz.contact_modulus((s["E"], s["nu"]), None) == pytest.approx(2 * s["E_star"], rel=1e-6)


def test_hertz_geometry_of_the_scene():
    """scenes/hertz.toml: μ = E/(2(1+ν)), K = E/(3(1−2ν)) with E = 10, ν = 0.3; R = 10."""
    geo = hertz.geometry(scene.load(cli.SCENES / "hertz.toml"))
    assert geo["R"] == 10.0 and geo["name"] == "hertz" and geo["symmetry_factor"] == 4.0
    assert hertz.young_poisson({"law": "neo_hookean", "parameters": {"mu": 10 / 2.6, "K": 10 / 1.2}}) == \
        pytest.approx((10.0, 0.3), rel=1e-12)
    assert geo["E_star"] == pytest.approx(10.0 / (2 * (1 - 0.09)), rel=1e-12)


def _study(tmp_path, text, name="s"):
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    out = tmp_path / f"out_{name}"
    assert cli.main(["study", str(path), "--out", str(out)]) == 0
    return out, list(csv.DictReader(open(out / "study.csv")))


HERTZ_TINY = ["mesh.n=6", "mesh.m=6", "body.0.n=4", "body.0.m=4"]


def test_hertz_reference_error_recomputed_from_the_case_profile(tmp_path):
    """One tiny Hertz case: the study's error equals the one computed here
    from the case's slave points (own least-squares fit, own Hertz formula)
    and the force of its curves.csv."""
    out, rows = _study(tmp_path, f'scene = "hertz"\nset = {HERTZ_TINY!r}\nreference = "hertz:p0"\ncases = [[]]\n'
                       .replace("'", '"'))
    row = rows[0]
    assert row["status"] == "completed"
    points = out / "case00" / "hertz_points.csv"
    header = points.read_text().splitlines()[0]
    F = float(header.split("F = ")[1].split(",")[0])
    # hertz:delta's approach: the ball's flat top is driven 0.3 mm down onto the block fixed at its base
    assert float(header.split("delta = ")[1]) == pytest.approx(0.3, rel=1e-9)
    curves = list(csv.DictReader(open(out / "case00" / "curves.csv")))
    assert F == pytest.approx(abs(float(curves[-1]["hertz_fz"])), rel=1e-9)  # whole-sphere force (× 4)
    data = np.loadtxt(points, delimiter=",", skiprows=2)
    r, p, closed = data[:, 0], data[:, 1], data[:, 2] > 0
    assert closed.sum() >= 3 and np.all(p[closed] > 0) and np.all(p[~closed] == 0)
    slope, intercept = np.polyfit(r[closed] ** 2, p[closed] ** 2, 1)
    p0_fit, a_fit = math.sqrt(intercept), math.sqrt(-intercept / slope)
    E_star = 10.0 / (2 * (1 - 0.3 ** 2))
    a_H = (3 * F * 10.0 / (4 * E_star)) ** (1 / 3)
    p0_H = 3 * F / (2 * math.pi * a_H ** 2)
    assert float(row["value"]) == pytest.approx(p0_fit, rel=1e-8)
    assert float(row["reference"]) == pytest.approx(p0_H, rel=1e-10)
    assert float(row["error"]) == pytest.approx(abs(p0_fit - p0_H) / p0_H, rel=1e-8)
    # a plausible contact: the fitted radius near Hertz's, the outermost closed point inside ~2 a_H
    assert abs(a_fit / a_H - 1) < 0.3 and r[closed].max() < 2 * a_H
    assert 0 < float(row["error"]) < 0.5


def test_patch_reference_is_the_spread_of_the_fields(tmp_path):
    """Blocks (scenes/blocks.toml), single pass and two-pass: the study's
    value equals the σ_zz spread of tests/verification/test_surface_contact.py and the
    pressure spread computed here, on independent runs of the same scene."""
    cases = [[], ["contact.0.passes=2"]]
    _, rows = _study(tmp_path, 'scene = "blocks"\nreference = "patch:sigma_zz"\n'
                     'cases = [[], ["contact.0.passes=2"]]\n', "sigma")
    _, prow = _study(tmp_path, 'scene = "blocks"\nreference = "patch:pressure"\ncases = [[]]\n', "pressure")
    spreads, pressure_spread = [], None
    for k, case in enumerate(cases):
        sim = Simulation(scene.load(cli.SCENES / "blocks.toml", case + ["output.xdmf=false"]), MPI.COMM_WORLD,
                         log=lambda *a, **kw: None)
        sim.run(out_dir=str(tmp_path / f"run{k}"))
        spreads.append(sigma_zz_spread(sim))
        if k == 0:
            st = sim.contacts[0].evaluate(sim.u)
            p = np.asarray(st.pressure)[np.asarray(st.gap) < 0]
            pressure_spread = (p.max() - p.min()) / abs(p.mean())
    for row, s in zip(rows, spreads):
        assert row["reference"] == "0.0"
        assert float(row["value"]) == pytest.approx(s, rel=1e-8)
        assert float(row["error"]) == float(row["value"])
    assert float(prow[0]["value"]) == pytest.approx(pressure_spread, rel=1e-10)
    # the single pass fails the patch test on these non-matching meshes, the two-pass much less so
    assert spreads[0] > 0.05 and spreads[1] < 0.5 * spreads[0]


@pytest.mark.parametrize("text, key, message", [
    ('scene = "hertz"\nreference = "hertz:radius"\ncases = [[]]\n', "reference", '"hertz:a"'),
    ('scene = "blocks"\nreference = "patch"\ncases = [[]]\n', "reference", '"patch:sigma_zz"'),
    ('scene = "hertz"\nreference = "hertz:a"\nquantity = "max:hertz_fz"\ncases = [[]]\n', "quantity",
     "measures its own quantity"),
    ('scene = "punch"\nreference = "hertz:p0"\ncases = [[]]\n', "reference", "hemisphere"),
    ('scene = "hertz"\nset = ["contact.0.mu=0.3", "contact.0.eps_t=10"]\nreference = "hertz:a"\ncases = [[]]\n',
     "reference", "frictionless"),
    ('scene = "sphere"\nreference = "patch:sigma_zz"\ncases = [[]]\n', "reference", "needs a scene with a contact"),
    ('scene = "blocks"\nreference = "uniform"\nquantity = "max:interface_fz"\ncases = [[]]\n', "reference",
     '"patch:pressure"'),
], ids=["hertz-unknown-quantity", "patch-bare", "quantity-given", "no-hemisphere", "friction", "no-contact",
        "unknown-reference"])
def test_bad_reference_specs_are_rejected_with_a_clear_message(tmp_path, capsys, text, key, message):
    study = tmp_path / "bad.toml"
    study.write_text(text)
    assert cli.main(["study", str(study), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert f"study key '{key}'" in err and message in err
    assert not (tmp_path / "o" / "case00").exists()  # rejected before any case ran


def test_built_in_studies_load():
    """Every study in scenes/studies validates (scene found, reference applicable)."""
    from hypercontact.study import cases_of, load_study

    paths = sorted((cli.SCENES / "studies").glob("*.toml"))
    assert {"hertz", "hertz_a", "patch", "punch_mu0.3"} <= {p.stem for p in paths}
    for path in paths:
        assert cases_of(load_study(path)), path.name
