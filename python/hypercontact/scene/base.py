"""The base of every scene table: unknown keys refused with the closest
valid name, required keys named when missing, a table demanded where one
is expected, arrays of tables ([[bc]]) accepted as one table too."""
import difflib
from typing import ClassVar

from pydantic import BaseModel, Extra, root_validator

from .errors import Invalid, describe


class SceneModel(BaseModel):
    """A scene table (TOML table) of typed keys.

    Subclasses may set ``missing`` (key → what to say when a required key
    is absent) and override :meth:`unknown_key` (what to say about a key
    they do not have)."""

    class Config:
        extra = Extra.forbid

    missing: ClassVar[dict] = {}

    @classmethod
    def validate(cls, value):
        """A table as a field of another table: a dict, or nothing else."""
        if not isinstance(value, dict):
            raise Invalid(f"expected a table, found {describe(value)}")
        return super().validate(value)

    @classmethod
    def unknown_key(cls, key):
        """What is wrong with ``key``, which this table does not have."""
        close = difflib.get_close_matches(key, list(cls.__fields__), n=1)
        return f"unknown key; did you mean '{close[0]}'?" if close else \
            f"unknown key; valid keys: {', '.join(cls.__fields__)}"

    @root_validator(pre=True)
    def known_and_present_keys(cls, values):
        for key in values:
            if key not in cls.__fields__:
                raise Invalid(cls.unknown_key(key), key)
        for name, field in cls.__fields__.items():
            if field.required and name not in values:
                raise Invalid(cls.missing.get(name, "missing (required)"), name)
        return values


def tables(value, name):
    """An array of tables ([[name]]) as a list of dicts: a single table
    becomes a list of one; anything else is refused."""
    if isinstance(value, dict):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
        raise Invalid(f"expected an array of tables ([[{name}]]), found {describe(value)}")
    return value
