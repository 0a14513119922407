"""Bad input stops with a message naming the key or the file; a run that
cannot converge stops clearly and keeps its converged steps on disk."""
import csv
import json
import re

import pytest
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


def test_failed_step_keeps_converged_steps(out_dir):
    """Steps that grow too fast with too few Newton iterations allowed and no
    cut-back: the run stops with a clear message after some converged steps."""
    sc = scene.load(PUNCH, ["mesh.n=4", "mesh.m=2", f"output.dir={out_dir}", "steps.initial=0.01",
                            "steps.min=0.001", "steps.max=1.0", "steps.growth=20", "steps.max_cutbacks=0",
                            "solver.max_it=4"])
    sim = Simulation(sc, MPI.COMM_WORLD, log=quiet)
    with pytest.raises(StepFailure, match=r"did not converge after 0 cut-backs") as failure:
        sim.run()
    m = re.search(r"from λ = ([0-9.e-]+) .* (\d+) converged step", str(failure.value))
    lam_failed, converged = float(m.group(1)), int(m.group(2))
    assert converged >= 1 and 0 < lam_failed < 1
    if MPI.COMM_WORLD.rank == 0:
        summary = json.loads((out_dir / "summary.json").read_text())
        assert summary["status"] == "failed" and "did not converge" in summary["message"]
        rows = list(csv.DictReader(open(out_dir / "curves.csv")))
        assert len(rows) == converged == len(summary["steps"])
        assert float(rows[-1]["load_factor"]) == pytest.approx(lam_failed)
        assert (out_dir / "fields.h5").stat().st_size > 0
