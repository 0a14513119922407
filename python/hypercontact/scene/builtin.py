"""The built-in scenes and studies: the TOML files of the package
``hypercontact.scenes`` (the repository's scenes/ folder, installed with
the package), found by name."""
import importlib.resources
import tomllib
from pathlib import Path

#: The folder of the built-in scenes; studies are in its studies/ folder.
SCENES = Path(str(importlib.resources.files("hypercontact.scenes")))
STUDIES = SCENES / "studies"


def _named(folder, name):
    """``folder/name.toml`` if ``name`` is no existing path but names a
    file there; ``name`` as a path otherwise."""
    path = Path(name)
    try:
        if not path.exists() and (folder / f"{name}.toml").is_file():
            return folder / f"{name}.toml"
    except OSError:  # e.g. a name too long for the file system: loading the path says so
        pass
    return path


def scene_path(name):
    """The path of a scene file, or of the built-in scene ``name``."""
    return _named(SCENES, name)


def study_path(name):
    """The path of a study file, or of the built-in study ``name``."""
    return _named(STUDIES, name)


def titles():
    """(name, title) of each built-in scene, by name."""
    out = []
    for path in sorted(SCENES.glob("*.toml")):
        try:
            title = tomllib.loads(path.read_text(encoding="utf-8")).get("title", "")
        except (tomllib.TOMLDecodeError, UnicodeDecodeError):
            title = "(not valid TOML)"
        out.append((path.stem, title))
    return out
