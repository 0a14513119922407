"""[[phase]]: a load history in phases, one after the other (Abaqus' steps,
CalculiX's *STEP, FEBio's load curves within a step).

Each phase has a length (its span of the accumulated load parameter τ, the
``time`` column of curves.csv), its own [steps] and [solver] keys, and says
what changes while its parameter s goes 0 → 1. Everything a phase does not
name holds its value; everything starts at zero (no motion, no load; μ and
the obstacles' places as the [[contact]] entries give them). Values are
absolute — where a bc or an obstacle is, the load's value, μ — at the end
of the phase (reached linearly from where the phase starts) or along a
curve of points [s, value] (piecewise linear; the phase's start value at
s = 0; the last value held after the last point):

    [[phase]]
    name = "press"
    bc = { lid = [0.0, 0.0, -0.2] }                  # bc "lid" ends at u = (0, 0, -0.2)
    [[phase]]
    name = "pressurise"
    steps = { max = 0.05 }
    pressure = { seal = [[0.5, 1.0], [1.0, 0.4]] }  # up to 1.0 at mid-phase, back to 0.4
    contact = { roller = { motion = [4, 0, -1], rotation = 1.3 } }
"""
import math
from typing import Dict, Optional

from pydantic import validator

from .base import SceneModel
from .errors import Invalid, describe
from .fields import POSITIVE, Boolean, Table, is_number, number, string

#: How a curve is written, for the messages.
CURVE_HELP = ("a value at the end of the phase, or a curve: a list of points [s, value] with 0 <= s <= 1 "
              "increasing")


def _finite(values, where):
    if not all(is_number(v) and math.isfinite(v) for v in values):
        raise Invalid(f"expected finite numbers, found {describe(values)}", where)
    return [float(v) for v in values]


class _Curve:
    """A value of a phase: its end value or a piecewise-linear curve of the
    phase's parameter s, kept as the list of points [(s, value), ...] (an end
    value v is [(1, v)]); ``size``: 1 (a scalar) or 3 (a vector)."""

    size = 1

    @classmethod
    def __get_validators__(cls):
        yield cls.validate

    @classmethod
    def _value(cls, value):
        if cls.size == 1 and is_number(value):
            return _finite([value], ())[0]
        if cls.size == 3 and isinstance(value, list) and len(value) == 3 and all(is_number(v) for v in value):
            return _finite(value, ())
        return None

    @classmethod
    def validate(cls, value):
        what = "a number" if cls.size == 1 else "a list of three numbers"
        end = cls._value(value)
        if end is not None:
            return [[1.0, end]]
        if not (isinstance(value, list) and value and all(isinstance(p, list) for p in value)):
            raise Invalid(f"expected {what} ({CURVE_HELP}), found {describe(value)}")
        points = []
        for k, point in enumerate(value):
            if len(point) != 1 + cls.size:
                raise Invalid(f"expected a point [s, {'value' if cls.size == 1 else 'x, y, z'}] "
                              f"({1 + cls.size} numbers), found {describe(point)}", k)
            s, *v = _finite(point, k)
            if not 0.0 <= s <= 1.0:
                raise Invalid(f"expected an abscissa s from 0 to 1 (the phase's parameter), found {s:g}", k)
            if points and s <= points[-1][0]:
                raise Invalid(f"the abscissae must increase: s = {s:g} follows s = {points[-1][0]:g}", k)
            points.append([s, v[0] if cls.size == 1 else v])
        return points


class ScalarCurve(_Curve):
    size = 1


class VectorCurve(_Curve):
    size = 3


class PhaseContact(SceneModel):
    """What a phase changes of a [[contact]]: the rigid obstacle's
    translation from its place in the [[contact]] entry, its rotation angle
    (radians, right-handed about rotation_axis through rotation_point,
    which moves with the translation), the friction coefficient, and
    whether the pair acts at all (``active``: from the phase's first step
    on, until a later phase says otherwise)."""

    motion: Optional[VectorCurve] = None
    rotation: Optional[ScalarCurve] = None
    mu: Optional[ScalarCurve] = None
    active: Optional[Boolean] = None

    @validator("mu")
    def non_negative_mu(cls, points):
        for k, (_, mu) in enumerate(points or []):
            if not 0.0 <= mu <= 1e3:
                raise Invalid(f"expected μ from 0 to 1000, found {mu:g}", k)
        return points


class Phase(SceneModel):
    name: string() = ""
    length: number(POSITIVE, (lambda x: x <= 1e12, "at most 1e12")) = 1.0
    steps: Table = {}
    solver: Table = {}
    bc: Dict[str, VectorCurve] = {}
    pressure: Dict[str, ScalarCurve] = {}
    traction: Dict[str, VectorCurve] = {}
    body_force: Dict[str, VectorCurve] = {}
    contact: Dict[str, PhaseContact] = {}

    @validator("bc", "pressure", "traction", "body_force", "contact", pre=True)
    def tables_of_names(cls, value):
        return Table.validate(value)
