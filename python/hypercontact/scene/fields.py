"""The value types of scene keys, strict (TOML's types, no coercion but
int → float for numbers), each with its range checks.

``number(POSITIVE, LENGTH)`` is the type of a finite number > 0 and at most
MAX_LENGTH; a failed check raises :class:`Invalid` with "expected <what the
check says>, found <the value>". A check is a pair (predicate, description).
"""
import math

from .errors import Invalid, describe

#: Largest coordinate or length a built-in mesh builder accepts (OpenCASCADE
#: and gmsh fail on values near their "infinite", about 1e100).
MAX_LENGTH = 1e12
#: Most hexahedra a built-in builder makes (a guard against n = 10**9).
MAX_CELLS = 10**8
#: Highest quadrature degree (degree 20 is already 11 × 11 × 11 points per
#: hexahedron; FFCx would hang on 10**6).
MAX_QUADRATURE_DEGREE = 20


def is_number(x):
    """int or float, not bool (TOML's numbers)."""
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def is_finite(x):
    return is_number(x) and math.isfinite(x)


def magnitude_ok(x):
    """Numbers that scale the solution: beyond 1e±100 the squares in vector
    norms under- or overflow (an arc-length step then divides by a zero norm)."""
    return x == 0 or 1e-100 <= abs(x) <= 1e100


def path_ok(text):
    """No NUL character, no name longer than the file system allows."""
    return "\0" not in text and all(len(part.encode("utf-8", "surrogateescape")) <= 255
                                    for part in text.split("/"))


def one_of(values, what):
    return (lambda x: x in values, what)


def from_to(lo, hi, what=None):
    return (lambda x: lo <= x <= hi, what or f"from {lo:g} to {hi:g}")


POSITIVE = (lambda x: x > 0, "> 0")
NON_NEGATIVE = (lambda x: x >= 0, ">= 0")
AT_MOST_ONE = (lambda x: x <= 1, "<= 1")
LENGTH = (lambda x: x <= MAX_LENGTH, f"at most {MAX_LENGTH:g}")
ALL_POSITIVE = (lambda v: all(c > 0 for c in v), "all sizes > 0")
COORDINATES = (lambda v: all(abs(c) <= MAX_LENGTH for c in v),
               f"coordinates of at most {MAX_LENGTH:g} in magnitude")
MAGNITUDE = (magnitude_ok, "0 or a magnitude from 1e-100 to 1e+100")
NON_ZERO_VECTOR = (lambda v: 1e-100 <= math.hypot(*v) <= 1e100,
                   "a non-zero vector (length from 1e-100 to 1e+100)")
FILE_NAME = (path_ok, "a path without NUL characters, each name at most 255 bytes")
PATH = (lambda x: x != "" and path_ok(x),
        "a non-empty path without NUL characters, each name at most 255 bytes")
GRADING = (lambda v: all(1.0 <= abs(g) <= 4.0 for g in v),
           "three numbers g with 1 <= |g| <= 4 (per axis: g > 1 clusters the cells towards the min side, "
           "g < -1 towards the max side; the hemisphere uses the first for x and y, the third towards its pole)")
AXES = (lambda x: len(x) > 0 and set(x) <= {"x", "y", "z"}, 'a non-empty subset of ["x", "y", "z"]')


class Checked:
    """A scene value type: ``accepts`` (with its description ``what``), then
    ``convert``, then each of ``checks``; pydantic calls :meth:`validate`."""

    what = "a value"
    json_schema = {}
    checks = ()

    @staticmethod
    def accepts(value):
        return True

    @staticmethod
    def convert(value):
        return value

    @classmethod
    def __get_validators__(cls):
        yield cls.validate

    @classmethod
    def __modify_schema__(cls, schema):
        schema.update(cls.json_schema)
        if cls.checks:
            schema["description"] = "; ".join(what for _, what in cls.checks)

    @classmethod
    def validate(cls, value):
        if not cls.accepts(value):
            raise Invalid(f"expected {cls.what}, found {describe(value)}")
        value = cls.convert(value)
        for check, what in cls.checks:
            if not check(value):
                raise Invalid(f"expected {what}, found {describe(value)}")
        return value


def _finite_float(value):
    if not math.isfinite(value):
        raise Invalid(f"expected a finite number, found {describe(value)}")
    return float(value)


def _finite_floats(value):
    if not all(math.isfinite(v) for v in value):
        raise Invalid(f"expected a list of three finite numbers, found {describe(value)}")
    return [float(v) for v in value]


class Number(Checked):
    what, json_schema = "a number", {"type": "number"}
    accepts, convert = staticmethod(is_number), staticmethod(_finite_float)


class Integer(Checked):
    what, json_schema = "an integer", {"type": "integer"}
    accepts = staticmethod(lambda x: isinstance(x, int) and not isinstance(x, bool))


class String(Checked):
    what, json_schema = "a string", {"type": "string"}
    accepts = staticmethod(lambda x: isinstance(x, str))


class Boolean(Checked):
    what, json_schema = "true or false", {"type": "boolean"}
    accepts = staticmethod(lambda x: isinstance(x, bool))


class Vector(Checked):
    what = "a list of three numbers"
    json_schema = {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3}
    accepts = staticmethod(lambda x: isinstance(x, list) and len(x) == 3 and all(is_number(v) for v in x))
    convert = staticmethod(_finite_floats)


def _finite_pair(value):
    if not all(math.isfinite(v) for v in value):
        raise Invalid(f"expected a list of two finite numbers, found {describe(value)}")
    return [float(v) for v in value]


class Pair(Checked):
    what = "a list of two numbers"
    json_schema = {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2}
    accepts = staticmethod(lambda x: isinstance(x, list) and len(x) == 2 and all(is_number(v) for v in x))
    convert = staticmethod(_finite_pair)


class Strings(Checked):
    what, json_schema = "a list of strings", {"type": "array", "items": {"type": "string"}}
    accepts = staticmethod(lambda x: isinstance(x, list) and all(isinstance(v, str) for v in x))


class Table(Checked):
    what, json_schema = "a table", {"type": "object"}
    accepts = staticmethod(lambda x: isinstance(x, dict))


def _with(kind, checks):
    return type(kind.__name__, (kind,), {"checks": tuple(checks)}) if checks else kind


def number(*checks):
    return _with(Number, checks)


def integer(*checks):
    return _with(Integer, checks)


def string(*checks):
    return _with(String, checks)


def vector(*checks):
    return _with(Vector, checks)


def pair(*checks):
    return _with(Pair, checks)


def strings(*checks):
    return _with(Strings, checks)
