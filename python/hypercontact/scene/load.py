"""Reading a scene: a TOML file or a dict, with ``--set`` overrides,
validated into a :class:`Scene` or refused with a SceneError."""
import copy
import tomllib
from pathlib import Path

from pydantic import ValidationError

from .errors import SceneError, printable, scene_error
from .overrides import apply_override
from .paths import relative_to
from .schema import Scene


def read(source, base_dir=None):
    """(data, base_dir) of a scene file's path or a dict (copied); relative
    paths in the scene are relative to the file's folder, or to base_dir."""
    if isinstance(source, dict):
        return copy.deepcopy(source), Path(base_dir or ".")
    path = Path(source)
    try:
        exists = path.is_file()
    except (OSError, ValueError) as err:
        raise SceneError(f"scene file '{printable(path, 200)}' cannot be looked up: {printable(err, 120)}") from None
    if not exists:
        raise SceneError(f"scene file '{printable(path, 200)}' does not exist")
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as err:
        raise SceneError(f"scene file '{path}' is not valid TOML: {err}") from None
    except UnicodeDecodeError as err:
        raise SceneError(f"scene file '{path}' is not UTF-8 text: {err}") from None
    return data, Path(base_dir or path.parent)


def load_model(source, overrides=(), base_dir=None):
    """The validated :class:`Scene` of a path or a dict, after the
    ``key.path=value`` overrides; SceneError naming the key otherwise."""
    data, base_dir = read(source, base_dir)
    for assignment in overrides:
        apply_override(data, assignment)
    with relative_to(base_dir):
        try:
            return Scene.parse_obj(data)
        except ValidationError as err:
            raise scene_error(err) from None


def to_dict(scene):
    """The plain dict of a Scene: every key, defaults filled in."""
    return scene.dict()


def load(source, overrides=(), base_dir=None):
    """Load and validate a scene from a path or a dict: plain dicts with
    every default filled in (see :func:`load_model` for the typed Scene)."""
    return to_dict(load_model(source, overrides, base_dir))
