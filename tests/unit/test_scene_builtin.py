"""The built-in scenes and studies: package data of hypercontact.scenes
(the repository's scenes/ folder), every one valid, found by name."""
import fnmatch
import tomllib
from pathlib import Path

import pytest

import hypercontact.scenes
from hypercontact import scene
from hypercontact.study import load_study

ROOT = Path(__file__).resolve().parents[2]
SCENE_FILES = sorted((ROOT / "scenes").glob("*.toml"))
STUDY_FILES = sorted((ROOT / "scenes" / "studies").glob("*.toml"))


def test_the_package_is_the_repository_folder():
    assert scene.SCENES == Path(hypercontact.scenes.__file__).parent == ROOT / "scenes"
    assert scene.STUDIES == ROOT / "scenes" / "studies"


def test_an_install_ships_every_scene_and_study():
    """pyproject.toml maps hypercontact.scenes onto scenes/ and its package
    data patterns match every scene and study file."""
    tool = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    assert "hypercontact.scenes" in tool["packages"]
    folder = ROOT / tool["package-dir"]["hypercontact.scenes"]
    patterns = tool["package-data"]["hypercontact.scenes"]
    for path in SCENE_FILES + STUDY_FILES:
        relative = path.relative_to(folder).as_posix()
        assert any(fnmatch.fnmatch(relative, p) and relative.count("/") == p.count("/") for p in patterns), relative


@pytest.mark.parametrize("path", SCENE_FILES, ids=lambda p: p.stem)
def test_every_builtin_scene_loads_unchanged(path):
    sc = scene.load(path)
    assert sc["title"], "a built-in scene has a title (hypercontact scenes lists it)"


@pytest.mark.parametrize("path", STUDY_FILES, ids=lambda p: p.stem)
def test_every_builtin_study_and_its_scene_load(path):
    study = load_study(path)
    assert Path(study["scene_path"]).is_file() and study["base_scene"]["mesh"]


def test_names_find_builtin_scenes_and_studies(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # not the source tree
    assert scene.scene_path("punch") == ROOT / "scenes" / "punch.toml"
    assert scene.study_path("hertz") == ROOT / "scenes" / "studies" / "hertz.toml"
    (tmp_path / "punch").write_text("")  # an existing path wins over the built-in name
    assert scene.scene_path("punch") == Path("punch")
    assert scene.scene_path("nowhere") == Path("nowhere")
    names = [name for name, _ in scene.builtin.titles()]
    assert names == sorted(p.stem for p in SCENE_FILES)
