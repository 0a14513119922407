"""Bad input stops with a message naming the key or the file; a run that
cannot converge stops clearly and keeps its converged steps on disk."""
import csv
import json
import re

import numpy as np
import pytest
import ufl
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import cli, scene
from hypercontact.simulation import Simulation, StepFailure

PUNCH = ROOT / "scenes" / "punch.toml"


def write_scene(tmp_path, old, new):
    text = PUNCH.read_text()
    assert old in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new, 1))
    return path


@pytest.mark.parametrize("old, new, expected", [
    ("n = 16", "nn = 16", "'mesh.nn': unknown key; did you mean 'n'?"),
    ("n = 16", 'n = "16"', "'mesh.n': expected an integer, found '16'"),
    ("size = [40.0, 40.0, 10.0]", "size = [40.0, 40.0, -10.0]", "'mesh.size': expected all sizes > 0"),
    ('builder = "box"', 'builder = "file"\nfile = "no/such/plate.msh"', "no/such/plate.msh' does not exist"),
    ("eps_n = 100.0", "eps_n = -1.0", "'contact[0].eps_n': expected >= 0"),
    ('surface = "zmax"', 'surface = "top"', "'contact[0].surface': the mesh has no surface 'top'"),
    ("[steps]", "[stepz]", "'stepz': unknown key; did you mean 'steps'?"),
    ("K = 5.0", "K = 5.0, beta = 1", "'material.parameters.beta': unknown parameter"),
])
def test_invalid_scene_names_the_key(tmp_path, capsys, old, new, expected):
    code = cli.main(["run", str(write_scene(tmp_path, old, new)), "--out", str(tmp_path / "out")])
    assert code == 2
    err = capsys.readouterr().err
    assert expected in err
    assert "Traceback" not in err


def test_unreadable_mesh_file_names_the_file(tmp_path, capsys):
    bad = tmp_path / "garbage.msh"
    bad.write_text("this is not a mesh\n")
    path = write_scene(tmp_path, 'builder = "box"', f'builder = "file"\nfile = "{bad}"')
    assert cli.main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "garbage.msh" in err and "Traceback" not in err


def test_set_override_and_check(capsys):
    assert cli.main(["check", str(PUNCH), "--set", "mesh.n=32", "--set", "contact.0.eps_n=10"]) == 0
    sc = scene.load(PUNCH, ["mesh.n=32", "contact.0.eps_n=10"])
    assert sc["mesh"]["n"] == 32 and sc["contact"][0]["eps_n"] == 10.0
    assert cli.main(["check", str(PUNCH), "--set", "mesh.q=3"]) == 2
    assert "'mesh.q': unknown key" in capsys.readouterr().err


def test_user_law_that_raises(tmp_path, capsys):
    law = tmp_path / "law.py"
    law.write_text("def psi(F, c):\n    raise ArithmeticError('c must be positive')\n")
    path = write_scene(tmp_path, 'law = "mooney_rivlin"\nparameters = { alpha1 = 0.1863, alpha2 = 0.0098, K = 5.0, i2 = "usual" }',
                       f'law = "python:{law}:psi"\nparameters = {{ c = -1 }}')
    assert cli.main(["check", str(path)]) == 0  # the scene is well-formed; the law fails when built
    assert cli.main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    assert "c must be positive" in capsys.readouterr().err


def test_driver_law_with_a_split_formulation_names_the_key():
    """A law a driver script passes has no isochoric part for sri or mixed to
    split off: refused before anything is built on it; a law name the scene
    cannot resolve (neither built-in nor python:) needs such a driver law."""
    sc = scene.load(PUNCH, ["mesh.n=2", "mesh.m=1", "discretisation.formulation=sri"])
    with pytest.raises(scene.SceneError, match=r"'discretisation\.formulation': 'sri' .* driver script's law"):
        Simulation(sc, MPI.COMM_SELF, law=lambda F, K: K * (ufl.det(F) - 1) ** 2, log=quiet)
    sc = scene.load(PUNCH, ["mesh.n=2", "mesh.m=1", "material.law=gent", "material.parameters={}"])
    with pytest.raises(scene.SceneError, match=r"'material\.law': .* found 'gent' .* driver script"):
        Simulation(sc, MPI.COMM_SELF, log=quiet)


def test_quadratic_hexahedra_with_too_few_gauss_points_are_refused():
    """The punch scene states quadrature_degree = 2 (2 × 2 × 2 points, right for its trilinear
    cells); switched to degree = 2 it would keep them and leave the 27-node hexahedra with
    zero-energy modes (Newton fails at the first step): refused naming the key, and accepted
    with quadrature_degree = 4 (3 × 3 × 3). Tetrahedra of degree 2 take the degree-2 rule."""
    sc = scene.load(PUNCH, ["mesh.n=2", "mesh.m=1", "discretisation.degree=2"])
    with pytest.raises(scene.SceneError, match=r"'discretisation\.quadrature_degree': 27-node hexahedra .* found 2"):
        Simulation(sc, MPI.COMM_SELF, log=quiet)
    Simulation(scene.load(PUNCH, ["mesh.n=2", "mesh.m=1", "discretisation.degree=2",
                                  "discretisation.quadrature_degree=4"]), MPI.COMM_SELF, log=quiet)
    Simulation(scene.load(PUNCH, ["mesh.n=2", "mesh.m=1", "discretisation.degree=2", 'mesh.cells="tetrahedra"']),
               MPI.COMM_SELF, log=quiet)


def fail_at(step, attempts=None):
    """A fail_attempt hook: every attempt at load step ``step`` fails (or
    only those numbered in ``attempts``)."""
    return lambda k, lam, dlam, attempt: k == step and (attempts is None or attempt in attempts)


def failing_punch(out_dir, overrides, fail_attempt, scene_file=PUNCH, log=quiet):
    sc = scene.load(scene_file, ["mesh.n=4", "mesh.m=2", f"output.dir={out_dir}", *overrides])
    sim = Simulation(sc, MPI.COMM_WORLD, log=log, fail_attempt=fail_attempt)
    with pytest.raises(StepFailure) as failure:
        sim.run()
    summary = json.loads((out_dir / "summary.json").read_text()) if MPI.COMM_WORLD.rank == 0 else None
    return str(failure.value), summary


@pytest.mark.mpi
def test_failed_step_keeps_converged_steps(out_dir):
    """Step 3 (from λ = 0.25) is made to fail, with no cut-back allowed: the
    run stops with a clear message, the two converged steps on disk."""
    message, summary = failing_punch(out_dir, ["steps.max_cutbacks=0"], fail_at(3))
    assert re.search(r"load step from λ = 0.25 did not converge after 0 cut-backs .* 2 converged step", message)
    if MPI.COMM_WORLD.rank == 0:
        assert summary["status"] == "failed" and summary["message"] == message
        rows = list(csv.DictReader(open(out_dir / "curves.csv")))
        assert len(rows) == 2 == len(summary["steps"])
        assert float(rows[-1]["load_factor"]) == pytest.approx(0.25)
        assert (out_dir / "fields.h5").stat().st_size > 0
        [failed] = summary["failed_attempts"]
        assert failed["step"] == 3 and failed["outcome"] == "stopped"


@pytest.mark.mpi
def test_message_counts_the_cut_backs_of_the_log(out_dir):
    """Every attempt at step 2 fails: two cut-backs are logged, the message
    says two, and summary.json has the three failed attempts."""
    messages = []
    message, summary = failing_punch(out_dir, ["steps.max_cutbacks=2"], fail_at(2), log=messages.append)
    logged = [m for m in messages if "failed (FORCED_FAILURE" in m]
    assert len(logged) == 3 and sum("cut back to" in m for m in logged) == 2 and "no cut-back left" in logged[-1]
    assert "after 2 cut-backs (last Δλ = 0.0375, reason FORCED_FAILURE)" in message
    if MPI.COMM_WORLD.rank == 0:
        attempts = summary["failed_attempts"]
        assert [a["attempt"] for a in attempts] == [0, 1, 2]
        assert [a["outcome"] for a in attempts] == ["cut back", "cut back", "stopped"]
        assert [a["dlam"] for a in attempts] == pytest.approx([0.15, 0.075, 0.0375])


@pytest.mark.mpi
def test_failed_attempt_leaves_its_story_in_the_summary(out_dir):
    """The first step of the punch with friction on the base, made to fail
    after its Newton solve: summary.json tells λ, Δλ, the reasons, the
    residual norm of every iterate, and the base's points that flipped most
    (open/closed and stick/slip), inside the plate."""
    _, summary = failing_punch(out_dir, ["mesh.m=1", "steps.max_cutbacks=0", "output.xdmf=false"], fail_at(1),
                               scene_file=ROOT / "scenes" / "punch_mu0_1.toml")
    if MPI.COMM_WORLD.rank == 0:
        [story] = summary["failed_attempts"]
        assert (story["step"], story["attempt"], story["load_factor"]) == (1, 0, 0.0)
        assert story["dlam"] == pytest.approx(0.1)
        assert story["reason"] == "FORCED_FAILURE" and story["snes_reason"].startswith("CONVERGED_")
        its = story["newton_iterations"]
        assert its >= 2 and len(story["residual_norms"]) == its + 1 and len(story["update_norms"]) == its
        assert (len(story["open_closed_flips_per_iteration"]) == len(story["stick_slip_flips_per_iteration"])
                == len(story["master_facet_flips_per_iteration"]) == its)
        assert story["most_master_facet_flips"] == []  # rigid obstacles only: no master facets
        assert story["residual_norms"][-1] < 1e-6 * story["residual_norms"][0]
        assert story["active_set_changes"] >= 1 and story["stick_slip_changes"] >= 1
        for kind in ("open_closed", "stick_slip"):
            flips = story[f"most_{kind}_flips"]
            assert 1 <= len(flips) <= 5 and sum(story[f"{kind}_flips_per_iteration"]) >= flips[0]["flips"]
            assert [f["flips"] for f in flips] == sorted((f["flips"] for f in flips), reverse=True)
            for f in flips:
                assert f["contact"] == "base" and f["flips"] >= 1
                assert np.all(np.array(f["point"]) >= -1e-9) and np.all(np.array(f["point"]) <= np.array([40, 40, 10]) + 1e-9)
                assert abs(f["point"][2]) < 1e-9  # the base's points are on z = 0
                assert np.linalg.norm(np.subtract(f["current"], f["point"])) < 1.0
        assert "inverted_element" not in story
