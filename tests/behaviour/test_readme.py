"""The README's and the docs pages' examples work as written: their scene
snippets load, their command lines name valid scenes and keys, the README's
material law and driver script run."""
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
#: The README and every page of docs/, by path: the examples moved out of the README live there.
PAGES = {"README.md": README, **{p.relative_to(ROOT).as_posix(): p.read_text() for p in sorted(ROOT.glob("docs/*.md"))}}


def blocks(language, text=README):
    return re.findall(rf"```{language}\n(.*?)```", text, flags=re.S)


def hypercontact_commands(text=README):
    """Every `hypercontact run|check|study ...` command in the sh blocks of a page."""
    for block in blocks("sh", text):
        for line in block.splitlines():
            line = line.split("#", 1)[0]
            for part in line.split("&&"):
                if "bin/hypercontact " in part:
                    yield shlex.split(part.split("bin/hypercontact ", 1)[1])


COMMANDS = [(page, argv) for page, text in PAGES.items() for argv in hypercontact_commands(text)]


def test_readme_has_examples():
    assert len(list(hypercontact_commands())) >= 6
    assert blocks("toml") and blocks("python")
    # the command lines that moved out of the README are tested where they are now
    assert {"docs/verification.md", "docs/studies.md"} <= {page for page, _ in COMMANDS}


@pytest.mark.parametrize("page, argv", COMMANDS, ids=[f"{page}: {' '.join(argv)}" for page, argv in COMMANDS])
def test_command_lines_are_valid(page, argv, capsys, monkeypatch):
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
    full = {page: [b for b in blocks("toml", text) if "[mesh]" in b] for page, text in PAGES.items()}
    assert full["README.md"], "the README shows a complete scene"
    assert full["docs/scenes.md"], "docs/scenes.md documents every key in a complete scene"
    for page, texts in full.items():
        for i, text in enumerate(texts):
            path = tmp_path / f"{page.replace('/', '_')}_{i}.toml"
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
