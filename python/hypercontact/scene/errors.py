"""Scene errors: one line naming the key path, what was expected and what
was found ("scene key 'contact[0].mu': expected >= 0, found -1.0 (float)").

The models raise :class:`Invalid` (a ValueError, so pydantic collects it
with the location of the field it checks); :func:`scene_error` turns the
first error of a pydantic ValidationError into a :class:`SceneError` whose
key path is that location plus the key the Invalid names inside it.
"""
import re

from pydantic import ValidationError
from pydantic.error_wrappers import ErrorWrapper


class SceneError(ValueError):
    """Invalid scene; the message names the key path."""


class Invalid(ValueError):
    """A failed check: ``message`` says what was expected and what was found;
    ``loc`` is where, relative to the field or model that checks (a tuple of
    keys and array indices; empty: the field itself)."""

    def __init__(self, message, loc=()):
        super().__init__(message)
        self.message = message
        self.loc = tuple(loc) if isinstance(loc, (tuple, list)) else (loc,)


def printable(text, limit):
    """``text`` on one line (control characters escaped), at most ``limit`` characters."""
    text = re.sub(r"[\x00-\x1f\x7f]", lambda m: repr(m.group())[1:-1], str(text))
    return text if len(text) <= limit else text[: limit - 3] + "..."


def describe(value):
    """How a found value is shown: its repr (shortened) and its type."""
    return f"{printable(repr(value), 80)} ({type(value).__name__})"


def key_path(loc):
    """'contact[0].mu' of the location ('contact', 0, 'mu')."""
    path = ""
    for part in loc:
        if isinstance(part, int):
            path += f"[{part}]"
        else:
            path += f".{part}" if path else str(part)
    return path


def fail(path, message):
    """Raise the SceneError of key ``path`` (a dotted string)."""
    raise SceneError(f"scene key '{printable(path, 120)}': {message}")


#: Location parts that name no key: pydantic's marker of a model-wide check
#: and the class names it inserts for the member of a tagged union
#: (filled in by the modules that define unions).
HIDDEN_LOCATIONS = {"__root__"}


def first_error(errors, loc=()):
    """(location, exception) of the first error in pydantic's nested lists."""
    for error in errors:
        if isinstance(error, list):
            found = first_error(error, loc)
        else:
            assert isinstance(error, ErrorWrapper)
            here = loc + error.loc_tuple()
            found = first_error(error.exc.raw_errors, here) if isinstance(error.exc, ValidationError) \
                else (here, error.exc)
        if found is not None:
            return found
    return None


def scene_error(err):
    """The SceneError of a pydantic ValidationError: its first error, with
    the key path of its location."""
    loc, exc = first_error(err.raw_errors)
    if isinstance(exc, Invalid):
        loc, message = loc + exc.loc, exc.message
    else:  # a check of pydantic's own (every field has a type of ours: not expected)
        message = printable(exc, 300)
    loc = tuple(part for part in loc if part not in HIDDEN_LOCATIONS)
    return SceneError(f"scene key '{printable(key_path(loc), 120)}': {message}")
