"""The scene tables besides mesh, bodies, materials and contacts:
discretisation, loads, boundary conditions, steps, solver and output."""
from typing import Dict, Optional

from pydantic import root_validator, validator

from .base import SceneModel
from .errors import Invalid
from .fields import (AT_MOST_ONE, AXES, COORDINATES, MAGNITUDE, MAX_QUADRATURE_DEGREE, NON_NEGATIVE, PATH,
                     POSITIVE, Boolean, Table, Vector, from_to, integer, number, one_of, string, strings, vector)
from .petsc import check_petsc_options

FORMULATIONS = ("displacement", "sri", "mixed")
CONTROLS = ("load", "arclength", "displacement")


class Discretisation(SceneModel):
    degree: integer(one_of((1, 2), "1 or 2")) = 1
    quadrature_degree: integer(from_to(1, MAX_QUADRATURE_DEGREE, f"an integer from 1 to {MAX_QUADRATURE_DEGREE}")) = 2
    formulation: string(one_of(FORMULATIONS, '"displacement", "sri" (selective reduced integration) or "mixed" '
                                             '(Taylor–Hood u–p)')) = "displacement"

    @root_validator(pre=True)
    def quadrature_follows_the_elements(cls, values):
        """Without an explicit quadrature_degree: 2 (2×2×2 Gauss points) for linear
        elements, 4 (3×3×3) for quadratic and mixed ones — fewer leave the
        triquadratic hexahedron zero-energy (hourglass) modes."""
        if "quadrature_degree" not in values:
            quadratic = values.get("degree") == 2 or values.get("formulation") == "mixed"
            values = {**values, "quadrature_degree": 4 if quadratic else 2}
        return values

    @root_validator(skip_on_failure=True)
    def mixed_has_enough_points(cls, values):
        if values["formulation"] == "mixed" and values["quadrature_degree"] < 4:
            raise Invalid("the mixed formulation's quadratic hexahedra need 3×3×3 Gauss points (degree >= 4), "
                          f"found {values['quadrature_degree']}: fewer leave zero-energy modes", "quadrature_degree")
        return values


#: The name [[phase]] tables use for an entry of [[bc]] or of a load.
ENTRY_NAME = (lambda x: x == "" or x.replace("_", "a").replace("-", "a").isalnum(),
              "a name of letters, digits, _ and - (phases name the entry by it)")


class Pressure(SceneModel):
    """A follower pressure λ × value on a surface (with [[phase]]: the phases give its value)."""

    name: string(ENTRY_NAME) = ""
    surface: string()
    value: Optional[number(MAGNITUDE)] = None


class Traction(SceneModel):
    """A dead traction λ × value on a surface (with [[phase]]: the phases give its value)."""

    name: string(ENTRY_NAME) = ""
    surface: string()
    value: Optional[vector(COORDINATES)] = None


class BodyForce(SceneModel):
    """A dead body force λ × value per unit reference volume (with [[phase]]: the phases give its value)."""

    name: string(ENTRY_NAME) = ""
    value: Optional[vector(COORDINATES)] = None


class BoundaryCondition(SceneModel):
    """u_a = λ × motion_a on a surface, or at the mesh node at a point, for
    the fixed axes a (with [[phase]]: the phases move it)."""

    name: string(ENTRY_NAME) = ""
    surface: string() = ""
    #: instead of a surface: the mesh node at this point (within 1e-8 of the mesh's size), e.g. a pin
    #: that takes out a rigid translation a symmetric load leaves free
    point: Optional[vector(COORDINATES)] = None
    fix: strings(AXES)
    motion: vector(COORDINATES) = [0.0, 0.0, 0.0]

    @root_validator(skip_on_failure=True)
    def surface_or_point(cls, values):
        if bool(values["surface"]) == (values["point"] is not None):
            raise Invalid("expected either a surface or a point (the node a bc holds), found "
                          + ("both" if values["surface"] else "neither"), "surface")
        return values

    @root_validator(skip_on_failure=True)
    def moves_only_what_it_holds(cls, values):
        fix = values["fix"]
        if len(set(fix)) != len(fix):
            raise Invalid(f"repeated axis in {fix}", "fix")
        free_moving = [a for a, m in zip("xyz", values["motion"]) if m != 0 and a not in fix]
        if free_moving:
            raise Invalid(f"moves {', '.join(free_moving)}, which this bc's fix does not hold (fix = {fix})",
                          "motion")
        return values


class Steps(SceneModel):
    control: string(one_of(CONTROLS, '"load", "arclength" or "displacement"')) = "load"
    initial: number(POSITIVE, AT_MOST_ONE) = 0.1
    min: number(POSITIVE) = 1e-4
    max: number(POSITIVE, AT_MOST_ONE) = 0.25
    max_cutbacks: integer(NON_NEGATIVE) = 8
    grow_below: integer(NON_NEGATIVE) = 5
    growth: number((lambda x: x >= 1, ">= 1")) = 1.5
    grow_after: integer(NON_NEGATIVE) = 3
    max_steps: integer(POSITIVE) = 200
    chatter_warning: integer(POSITIVE) = 6
    target_iterations: integer(POSITIVE) = 5
    stop_probe: string() = ""
    stop_component: string(one_of(("x", "y", "z"), '"x", "y" or "z"')) = "x"
    stop_value: number() = 1.0
    locate_limits: Boolean = True
    predictor: string(one_of(("none", "secant"), '"none" or "secant"')) = "none"

    @root_validator(skip_on_failure=True)
    def min_below_initial(cls, values):
        if values["min"] > values["initial"]:
            raise Invalid(f"must not exceed steps.initial ({values['initial']}), found {values['min']}", "min")
        return values


class Solver(SceneModel):
    rtol: number(POSITIVE, (lambda x: x < 1, "< 1")) = 1e-10
    atol: number(POSITIVE) = 1e-10
    max_it: integer(from_to(1, 1000, "an integer from 1 to 1000")) = 25
    fallback_max_it: integer(from_to(0, 1000, "an integer from 0 to 1000 (0: max_it)")) = 0
    stall_decrease: number((lambda x: 0 <= x < 1, "a fraction from 0 (no stall stop) to below 1")) = 0.05
    stall_its: integer(from_to(0, 1000, "an integer from 0 to 1000 (0: no such stop)")) = 4
    linesearch: string(one_of(("auto", "basic", "bt", "l2", "cp"),
                              "auto or a PETSc SNES line search: basic, bt, l2 or cp")) = "auto"
    linear: string(one_of(("auto", "direct", "iterative"),
                          '"auto" (direct up to direct_max_unknowns, else iterative), "direct" (MUMPS LU) or '
                          '"iterative" (GMRES + GAMG with the rigid-body modes)')) = "auto"
    direct_max_unknowns: Optional[integer(POSITIVE)] = None  # None: the measured crossover (solve/newton.py)
    damp_inversion: Boolean = False
    petsc: Table = {}

    _petsc_options = validator("petsc", allow_reuse=True)(check_petsc_options)


class FiniteVector(Vector):
    what = "a list of three finite numbers"


class Output(SceneModel):
    dir: string(PATH) = "results"
    xdmf: Boolean = True
    symmetry_factor: number(POSITIVE) = 1.0
    probes: Dict[str, FiniteVector] = {}

    @validator("probes", pre=True)
    def probes_table(cls, probes):
        return Table.validate(probes)
