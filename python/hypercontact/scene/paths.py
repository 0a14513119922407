"""Files a scene names (a mesh file, a user law's Python file): resolved
against the scene's folder and checked to exist.

The folder is a context of the validation, not a key of the scene:
:func:`relative_to` sets it while a scene is parsed (the folder of the
scene file, or the ``base_dir`` given with a dict; the working directory
by default).
"""
import contextlib
import contextvars
from pathlib import Path

from .errors import Invalid, printable

_BASE_DIR = contextvars.ContextVar("scene_base_dir", default=Path("."))


@contextlib.contextmanager
def relative_to(base_dir):
    """Resolve relative paths of the scene parsed inside against ``base_dir``."""
    token = _BASE_DIR.set(Path(base_dir))
    try:
        yield
    finally:
        _BASE_DIR.reset(token)


def existing_file(text, what, loc=()):
    """The absolute path of ``text`` (relative: to the scene's folder);
    Invalid (at ``loc``) if it is no file or cannot even be looked up."""
    path = Path(text)
    if not path.is_absolute():
        path = (_BASE_DIR.get() / path).resolve()
    try:
        exists = path.is_file()
    except (OSError, ValueError) as err:
        raise Invalid(f"{what} '{printable(path, 200)}' cannot be looked up: {printable(err, 120)}", loc) from None
    if not exists:
        raise Invalid(f"{what} '{path}' does not exist", loc)
    return path
