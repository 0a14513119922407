"""The README's examples work as written: its scene snippets load, its
command lines name valid scenes and keys, its driver script runs."""
import re
import shlex
import sys
import tomllib

import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import cli, scene
from hypercontact.simulation import Simulation

README = (ROOT / "README.md").read_text()


def blocks(language):
    return re.findall(rf"```{language}\n(.*?)```", README, flags=re.S)


def hypercontact_commands():
    """Every `hypercontact run|check ...` command in the README's sh blocks."""
    for block in blocks("sh"):
        for line in block.splitlines():
            line = line.split("#", 1)[0]
            for part in line.split("&&"):
                if "bin/hypercontact " in part:
                    yield shlex.split(part.split("bin/hypercontact ", 1)[1])


def test_readme_has_examples():
    assert len(list(hypercontact_commands())) >= 6
    assert blocks("toml") and blocks("python")


@pytest.mark.parametrize("argv", list(hypercontact_commands()), ids=" ".join)
def test_command_lines_are_valid(argv, capsys, monkeypatch):
    """Each command, as `check` (same scene, same --set overrides)."""
    args, skip = [], False
    for a in argv[1:]:
        if skip:
            skip = False
        elif a in ("--out", "--np"):
            skip = True
        elif a != "--resume":
            args.append(a)
    monkeypatch.chdir(ROOT)
    if argv[0] == "study":  # a study file (or built-in study): it must load and name a valid scene
        from hypercontact.study import load_study

        path = ROOT / "scenes" / "studies" / f"{args[0]}.toml"
        study = load_study(path if path.is_file() else args[0])
        assert cli.main(["check", study["scene_path"], *[f"--set={o}" for o in study["set"]]]) == 0
        return
    assert cli.main(["check", *args]) == 0, capsys.readouterr().err


def test_scene_reference_block_is_a_valid_scene(tmp_path):
    full = [b for b in blocks("toml") if "[mesh]" in b]
    assert full, "the README documents a complete scene"
    for i, text in enumerate(full):
        path = tmp_path / f"scene{i}.toml"
        path.write_text(text)
        scene.load(path)


def test_material_law_example_and_driver_script_run(tmp_path, monkeypatch):
    law_code = next(b for b in blocks("python") if "def gent" in b)
    driver = next(b for b in blocks("python") if "Simulation(" in b)
    (tmp_path / "mylaw.py").write_text(law_code)
    (tmp_path / "scenes").symlink_to(ROOT / "scenes")
    monkeypatch.chdir(tmp_path)
    monkeypatch.syspath_prepend(str(tmp_path))
    # the scene snippet that uses the law: the punch with that [material] table
    material = next(b for b in blocks("toml") if "python:mylaw.py:gent" in b)
    data = tomllib.loads((ROOT / "scenes" / "punch.toml").read_text())
    data.update(tomllib.loads(material))
    sc = scene.load(data, ["mesh.n=2", "mesh.m=1", f"output.dir={tmp_path / 'law'}"], base_dir=tmp_path)
    Simulation(sc, MPI.COMM_WORLD, log=quiet)  # builds: the law resolves and compiles
    # the driver script, as written (the full 16 × 16 × 4 punch with the Gent law)
    namespace = {}
    exec(compile(driver, "README driver script", "exec"), namespace)
    assert namespace["writer"].steps[-1]["punch_fz"] < 0
    sys.modules.pop("mylaw", None)
