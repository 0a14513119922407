"""[material] (and a [[body]]'s material): a law and its parameters.

The law is a built-in one (forms/registry.py: exactly its parameters,
typed and in range, the optional ones filled in), a user's Python function
"python:FILE.py:FUNCTION" (the file resolved and checked to exist), or any
other name, for the function a driver script passes to Simulation. Every
numeric parameter is finite (K = inf only: the incompressible limit).
"""
import difflib
import math

from pydantic import root_validator, validator

from ..forms.registry import LAWS, REQUIRED
from .base import SceneModel
from .builders import choices
from .errors import Invalid, describe, printable
from .fields import MAGNITUDE, Table, is_finite, is_number, magnitude_ok, path_ok, string
from .paths import existing_file

PYTHON_LAW = "python:"


class Material(SceneModel):
    law: string()
    parameters: Table = {}

    @validator("law")
    def python_file_exists(cls, law):
        """'python:FILE.py:FUNCTION' with FILE resolved: an existing .py file."""
        if not law.startswith(PYTHON_LAW):
            return law
        parts = law.split(":")
        if len(parts) != 3 or not parts[1] or not parts[2]:
            raise Invalid(f"expected 'python:FILE.py:FUNCTION', found {describe(law)}")
        _, path, func = parts
        if not path_ok(path):
            raise Invalid(f"expected a file path without NUL characters, each name at most 255 bytes, "
                          f"found {describe(path)}")
        if not func.isidentifier():
            raise Invalid(f"'{printable(func, 60)}' is not a Python function name")
        file = existing_file(path, "file")
        if file.suffix != ".py":
            raise Invalid(f"file '{file}' is not a Python file (.py)")
        return f"{PYTHON_LAW}{file}:{func}"

    @validator("parameters")
    def finite_values(cls, params):
        for key, value in params.items():
            _check_any_law_value(key, value)
        return params

    @root_validator(skip_on_failure=True)
    def builtin_law_parameters(cls, values):
        law = LAWS.get(values["law"])
        if law is not None:
            values["parameters"] = _checked_parameters(law, values["parameters"])
        return values

    @property
    def builtin(self):
        """Whether the law is a built-in one (forms/registry.py)."""
        return self.law in LAWS

    @property
    def incompressible(self):
        """K = inf: the incompressible limit."""
        K = self.parameters.get("K")
        return is_number(K) and math.isinf(K)


def _check_any_law_value(key, value):
    """A parameter of any law: a string, true/false, a finite number of a
    sane magnitude (K = inf too) or a list of those numbers."""
    k_inf = " (or K = inf)" if key == "K" else ""
    if isinstance(value, list):
        if not all(is_finite(v) and magnitude_ok(v) for v in value):
            raise Invalid(f"expected a number, a string, true/false or a list of finite numbers "
                          f"({MAGNITUDE[1]}), found {describe(value)}", key)
    elif is_number(value):
        if math.isnan(value) or (math.isinf(value) and not (key == "K" and value > 0)):
            raise Invalid(f"expected a finite number{k_inf}, found {describe(value)}", key)
        if math.isfinite(value) and not magnitude_ok(value):
            raise Invalid(f"expected {MAGNITUDE[1]}{k_inf}, found {describe(value)}", key)
    elif not isinstance(value, (str, bool)):
        raise Invalid(f"expected a number, a string, true/false or a list of numbers, found {describe(value)}", key)


def _checked_parameters(law, params):
    """A built-in law's parameters: exactly its own, typed and in range,
    the optional ones at their defaults."""
    for key in params:
        if key not in law.parameters:
            close = difflib.get_close_matches(key, list(law.parameters), n=1)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            raise Invalid(f"unknown parameter of {law.name} (expected {', '.join(law.parameters)}){hint}",
                          ("parameters", key))
    for key, default in law.parameters.items():
        if default is REQUIRED and key not in params:
            raise Invalid(f"missing (required by {law.name})", ("parameters", key))
    params = law.with_defaults(params)
    for key, value in params.items():
        where = ("parameters", key)
        if key in law.choices:
            if value not in law.choices[key]:
                raise Invalid(f"expected {choices(law.choices[key])}, found {describe(value)}", where)
        elif not is_number(value):
            raise Invalid(f"expected a number, found {describe(value)}", where)
        elif key == "K" and not value > 0:
            raise Invalid(f"expected a bulk modulus > 0 (inf: incompressible), found {describe(value)}", where)
    if law.name == "neo_hookean" and not params["mu"] > 0:
        raise Invalid(f"expected a shear modulus > 0, found {describe(params['mu'])}", ("parameters", "mu"))
    mu, formula = law.shear_modulus(params)
    if law.name == "mooney_rivlin" and not mu > 0:
        raise Invalid(f"the small-strain shear modulus {formula} must be > 0, found {mu:g} (alpha1 = "
                      f"{params['alpha1']:g}, alpha2 = {params['alpha2']:g}, i2 = {params['i2']!r})", "parameters")
    return params
