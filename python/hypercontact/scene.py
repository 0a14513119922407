"""Scenes: TOML files describing one problem, validated against a schema.

A scene is only data; :func:`load` turns it into plain dicts with every
default filled in, or raises :class:`SceneError` naming the key path, what
was expected and what was found. Unknown keys are rejected with the closest
valid name suggested.
"""
import copy
import difflib
import math
import re
import tomllib
from pathlib import Path


class SceneError(ValueError):
    """Invalid scene; the message names the key path."""


REQUIRED = object()


def _num(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _finite(x):
    return _num(x) and math.isfinite(x)


def _vec3(x):
    return isinstance(x, list) and len(x) == 3 and all(_num(v) for v in x)


def _finite_vec3(x):
    return _vec3(x) and all(math.isfinite(v) for v in x)


def _magnitude_ok(x):
    """Numbers that scale the solution: beyond 1e±100 the squares in vector
    norms under- or overflow (an arc-length step then divides by a zero norm)."""
    return x == 0 or 1e-100 <= abs(x) <= 1e100


def _path_ok(text):
    """No NUL character, no name longer than the file system allows."""
    return "\0" not in text and all(len(part.encode("utf-8", "surrogateescape")) <= 255
                                    for part in text.split("/"))


def _is_file(path, key, what):
    """Whether ``path`` is a file; a path the OS cannot even look up is
    rejected naming ``key``."""
    try:
        return path.is_file()
    except (OSError, ValueError) as err:
        _fail(key, f"{what} '{_printable(path, 200)}' cannot be looked up: {_printable(err, 120)}")


def _positive(x):
    return x > 0


def _positive_vec(x):
    return all(v > 0 for v in x)


#: Largest coordinate or length a built-in mesh builder accepts (OpenCASCADE
#: and gmsh fail on values near their "infinite", about 1e100).
MAX_LENGTH = 1e12
#: Most hexahedra a built-in builder makes (a guard against n = 10**9).
MAX_CELLS = 10**8
#: Highest quadrature degree (degree 20 is already 11 × 11 × 11 points per
#: hexahedron; FFCx would hang on 10**6).
MAX_QUADRATURE_DEGREE = 20
#: The built-in laws (hypercontact.forms.materials.LAWS) and their parameters
#: (None = required); kept here so that checking a scene needs no UFL.
BUILTIN_LAWS = {
    "mooney_rivlin": {"alpha1": None, "alpha2": None, "K": None, "i2": "usual", "volumetric": "quadratic"},
    "neo_hookean": {"mu": None, "K": None, "volumetric": "quadratic"},
}
#: Values of the parameter ``volumetric``, the volumetric energy Ψ0(J)
#: (hypercontact.forms.materials.VOLUMETRIC): K/2 (J − 1)² (the paper's),
#: K/2 (ln J)², K/4 (J² − 1 − 2 ln J).
VOLUMETRIC = ("quadratic", "log", "log_quadratic")
#: The string parameters of the built-in laws and their values.
STRING_PARAMETERS = {"i2": ("usual", "paper"), "volumetric": VOLUMETRIC}
#: The surfaces of the built-in builders, each with the axis of its normal if
#: it is a plane x, y or z = const (None for the spheres).
BUILDER_SURFACES = {
    "box": {"xmin": 0, "xmax": 0, "ymin": 1, "ymax": 1, "zmin": 2, "zmax": 2},
    "shell_octant": {"inner": None, "outer": None, "xmin": 0, "ymin": 1, "zmin": 2},
    "hemisphere": {"curved": None, "flat": 2, "xmin": 0, "ymin": 1},
}


class Key:
    """One scene key: a type check (with its description), a default, and
    optional range checks (predicate, description)."""

    def __init__(self, kind, default=REQUIRED, *checks):
        self.kind, self.default, self.checks = kind, default, checks


KINDS = {
    "number": (_num, "a number"),
    "integer": (lambda x: isinstance(x, int) and not isinstance(x, bool), "an integer"),
    "string": (lambda x: isinstance(x, str), "a string"),
    "boolean": (lambda x: isinstance(x, bool), "true or false"),
    "vector": (_vec3, "a list of three numbers"),
    "strings": (lambda x: isinstance(x, list) and all(isinstance(v, str) for v in x),
                "a list of strings"),
    "table": (lambda x: isinstance(x, dict), "a table"),
}

POSITIVE = (_positive, "> 0")
NON_NEGATIVE = (lambda x: x >= 0, ">= 0")
LENGTH = (lambda x: x <= MAX_LENGTH, f"at most {MAX_LENGTH:g}")
COORDINATES = (lambda v: all(abs(c) <= MAX_LENGTH for c in v), f"coordinates of at most {MAX_LENGTH:g} in magnitude")
MAGNITUDE = (lambda x: _magnitude_ok(x), "0 or a magnitude from 1e-100 to 1e+100")
PATH = (lambda x: x != "" and _path_ok(x), "a non-empty path without NUL characters, each name at most 255 bytes")
GRADING = (lambda v: all(1.0 <= abs(g) <= 4.0 for g in v),
           "three numbers g with 1 <= |g| <= 4 (per axis: g > 1 clusters the cells towards the min side, "
           "g < -1 towards the max side; the hemisphere uses the first for x and y, the third towards its pole)")
AXES = (lambda x: len(x) > 0 and set(x) <= {"x", "y", "z"}, 'a non-empty subset of ["x", "y", "z"]')

SCHEMA = {
    "title": Key("string", ""),
    "mesh": {
        "builder": Key("string", "box", (lambda x: x in ("box", "shell_octant", "file"),
                                          '"box", "shell_octant" or "file"')),
        "inner_radius": Key("number", 95.0, POSITIVE, LENGTH),
        "thickness": Key("number", 1.0, POSITIVE, LENGTH),
        "size": Key("vector", [1.0, 1.0, 1.0], (_positive_vec, "all sizes > 0"), COORDINATES),
        "origin": Key("vector", [0.0, 0.0, 0.0], COORDINATES),
        "n": Key("integer", 4, POSITIVE),
        "m": Key("integer", 4, POSITIVE),
        "grading": Key("vector", [1.0, 1.0, 1.0], GRADING),
        "file": Key("string", "", (lambda x: _path_ok(x), "a path without NUL characters, each name at most "
                                                           "255 bytes")),
        # random node displacements of this fraction of the smallest cell's size (fixed per node):
        # a check that results move continuously with the data, not a modelling feature
        "perturbation": Key("number", 0.0, NON_NEGATIVE, (lambda x: x <= 1e-2, "at most 0.01")),
    },
    "material": {
        "law": Key("string", REQUIRED),
        "parameters": Key("table", {}),
    },
    "body": [{
        "name": Key("string", REQUIRED, (lambda x: re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", x) is not None,
                                         "a name of letters, digits and _ (it prefixes the body's surfaces)")),
        "builder": Key("string", "box", (lambda x: x in ("box", "shell_octant", "hemisphere"),
                                          '"box", "shell_octant" or "hemisphere"')),
        "size": Key("vector", [1.0, 1.0, 1.0], (_positive_vec, "all sizes > 0"), COORDINATES),
        "origin": Key("vector", [0.0, 0.0, 0.0], COORDINATES),
        "n": Key("integer", 4, POSITIVE),
        "m": Key("integer", 4, POSITIVE),
        "inner_radius": Key("number", 95.0, POSITIVE, LENGTH),
        "thickness": Key("number", 1.0, POSITIVE, LENGTH),
        "radius": Key("number", 1.0, POSITIVE, LENGTH),
        "grading": Key("vector", [1.0, 1.0, 1.0], GRADING),
        "material": {
            "law": Key("string", REQUIRED),
            "parameters": Key("table", {}),
        },
    }],
    "discretisation": {
        "degree": Key("integer", 1, (lambda x: x in (1, 2), "1 or 2")),
        "quadrature_degree": Key("integer", 2, (lambda x: 1 <= x <= MAX_QUADRATURE_DEGREE,
                                                f"an integer from 1 to {MAX_QUADRATURE_DEGREE}")),
        "formulation": Key("string", "displacement", (lambda x: x in ("displacement", "sri", "mixed"),
                                                      '"displacement", "sri" (selective reduced integration) '
                                                      'or "mixed" (Taylor–Hood u–p)')),
    },
    "pressure": [{
        "surface": Key("string", REQUIRED),
        "value": Key("number", REQUIRED, MAGNITUDE),
    }],
    "traction": [{
        "surface": Key("string", REQUIRED),
        "value": Key("vector", REQUIRED, COORDINATES),
    }],
    "body_force": [{
        "value": Key("vector", REQUIRED, COORDINATES),
    }],
    "bc": [{
        "surface": Key("string", REQUIRED),
        "fix": Key("strings", REQUIRED, AXES),
        "motion": Key("vector", [0.0, 0.0, 0.0], COORDINATES),
    }],
    "contact": [{
        "name": Key("string", REQUIRED),
        "surface": Key("string", REQUIRED),
        "obstacle": Key("string", REQUIRED, (lambda x: x in ("plane", "box", "cylinder", "surface"),
                                             '"plane", "box", "cylinder" (rigid) or "surface" (a deformable '
                                             'body\'s surface)')),
        "master": Key("string", ""),  # a surface name, or several joined by "+"
        "passes": Key("integer", 1, (lambda x: x in (1, 2), "1 (single pass, the paper) or 2 (two-pass)")),
        "integration": Key("string", "nodal", (lambda x: x in ("nodal", "gauss"),
                                               '"nodal" (the paper) or "gauss" (Gauss points of the slave facets)')),
        "capture": Key("number", 0.0, NON_NEGATIVE, LENGTH),
        "point": Key("vector", [0.0, 0.0, 0.0], COORDINATES),
        "normal": Key("vector", [0.0, 0.0, 1.0], (lambda v: 1e-100 <= math.hypot(*v) <= 1e100,
                                                  "a non-zero vector (length from 1e-100 to 1e+100)")),
        "lo": Key("vector", [0.0, 0.0, 0.0], COORDINATES),
        "hi": Key("vector", [1.0, 1.0, 1.0], COORDINATES),
        "axis": Key("vector", [0.0, 1.0, 0.0], (lambda v: 1e-100 <= math.hypot(*v) <= 1e100,
                                                "a non-zero vector (length from 1e-100 to 1e+100)")),
        "radius": Key("number", 0.0, NON_NEGATIVE, LENGTH),
        "motion": Key("vector", [0.0, 0.0, 0.0], COORDINATES),
        "eps_n": Key("number", 0.0, NON_NEGATIVE, (lambda x: x == 0 or 1e-100 <= x <= 1e100,
                                                   "0 (automatic: penalty_factor × M / h) or from 1e-100 to 1e+100")),
        "penalty_factor": Key("number", 100.0, POSITIVE, (lambda x: 1e-6 <= x <= 1e12, "from 1e-6 to 1e12")),
        "enforcement": Key("string", "penalty", (lambda x: x in ("penalty", "augmented_lagrangian"),
                                                 '"penalty" or "augmented_lagrangian"')),
        "gap_tolerance": Key("number", 0.0, NON_NEGATIVE, LENGTH),
        # the normal law's kink at g = 0 smoothed over |g| < smoothing × h (h: the first element
        # layer's thickness); 0: the paper's sharp <-g>
        "smoothing": Key("number", 1e-6, NON_NEGATIVE, (lambda x: x <= 0.1, "at most 0.1")),
        "max_augmentations": Key("integer", 20, (lambda x: 1 <= x <= 1000, "from 1 to 1000")),
        "mu": Key("number", 0.0, NON_NEGATIVE, (lambda x: x <= 1e3, "at most 1000")),
        "eps_t": Key("number", 0.0, NON_NEGATIVE, (lambda x: x == 0 or 1e-100 <= x <= 1e100,
                                                   "0 (= eps_n) or from 1e-100 to 1e+100")),
    }],
    "steps": {
        "control": Key("string", "load", (lambda x: x in ("load", "arclength", "displacement"),
                                          '"load", "arclength" or "displacement"')),
        "initial": Key("number", 0.1, POSITIVE, (lambda x: x <= 1, "<= 1")),
        "min": Key("number", 1e-4, POSITIVE),
        "max": Key("number", 0.25, POSITIVE, (lambda x: x <= 1, "<= 1")),
        "max_cutbacks": Key("integer", 8, NON_NEGATIVE),
        "grow_below": Key("integer", 5, NON_NEGATIVE),
        "growth": Key("number", 1.5, (lambda x: x >= 1, ">= 1")),
        "grow_after": Key("integer", 3, NON_NEGATIVE),
        "max_steps": Key("integer", 200, POSITIVE),
        "chatter_warning": Key("integer", 6, POSITIVE),
        "target_iterations": Key("integer", 5, POSITIVE),
        "stop_probe": Key("string", ""),
        "stop_component": Key("string", "x", (lambda x: x in ("x", "y", "z"), '"x", "y" or "z"')),
        "stop_value": Key("number", 1.0),
    },
    "solver": {
        "rtol": Key("number", 1e-10, POSITIVE, (lambda x: x < 1, "< 1")),
        "atol": Key("number", 1e-10, POSITIVE),
        "max_it": Key("integer", 25, (lambda x: 1 <= x <= 1000, "an integer from 1 to 1000")),
        "linesearch": Key("string", "auto", (lambda x: x in ("auto", "basic", "bt", "l2", "cp"),
                                             "auto or a PETSc SNES line search: basic, bt, l2 or cp")),
        "linear": Key("string", "auto", (lambda x: x in ("auto", "direct", "iterative"),
                                         '"auto" (direct up to direct_max_unknowns, else iterative), "direct" '
                                         '(MUMPS LU) or "iterative" (GMRES + GAMG with the rigid-body modes)')),
        "direct_max_unknowns": Key("integer", 200000, POSITIVE),
        "petsc": Key("table", {}),
    },
    "output": {
        "dir": Key("string", "results", PATH),
        "xdmf": Key("boolean", True),
        "symmetry_factor": Key("number", 1.0, POSITIVE),
        "probes": Key("table", {}),
    },
}


def _printable(text, limit):
    """``text`` on one line (control characters escaped), at most ``limit`` characters."""
    text = re.sub(r"[\x00-\x1f\x7f]", lambda m: repr(m.group())[1:-1], str(text))
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _fail(path, msg):
    raise SceneError(f"scene key '{_printable(path, 120)}': {msg}")


def _describe(value):
    return f"{_printable(repr(value), 80)} ({type(value).__name__})"


def _validate(data, schema, path):
    if isinstance(schema, Key):
        ok, what = KINDS[schema.kind]
        if schema.kind == "number" and isinstance(data, int) and not isinstance(data, bool):
            data = float(data)
        if not ok(data):
            _fail(path, f"expected {what}, found {_describe(data)}")
        if schema.kind == "number" and not math.isfinite(data):
            _fail(path, f"expected a finite number, found {_describe(data)}")
        if schema.kind == "vector":
            if not all(math.isfinite(v) for v in data):
                _fail(path, f"expected a list of three finite numbers, found {_describe(data)}")
            data = [float(v) for v in data]
        for check, what in schema.checks:
            if not check(data):
                _fail(path, f"expected {what}, found {_describe(data)}")
        return data
    if isinstance(schema, list):
        if isinstance(data, dict):
            data = [data]
        if not isinstance(data, list) or not all(isinstance(d, dict) for d in data):
            _fail(path, f"expected an array of tables ([[{path}]]), found {_describe(data)}")
        return [_validate(d, schema[0], f"{path}[{i}]") for i, d in enumerate(data)]
    if not isinstance(data, dict):
        _fail(path, f"expected a table, found {_describe(data)}")
    for key in data:
        if key not in schema:
            close = difflib.get_close_matches(key, list(schema), n=1)
            hint = f"; did you mean '{close[0]}'?" if close else f"; valid keys: {', '.join(schema)}"
            _fail(f"{path}.{key}" if path else key, f"unknown key{hint}")
    out = {}
    for key, sub in schema.items():
        p = f"{path}.{key}" if path else key
        if key in data:
            out[key] = _validate(data[key], sub, p)
        elif isinstance(sub, Key):
            if sub.default is REQUIRED:
                _fail(p, "missing (required)")
            out[key] = copy.deepcopy(sub.default)
        elif isinstance(sub, list):
            out[key] = []
        else:
            out[key] = _validate({}, sub, p)
    return out


def _check_mesh(mesh, where="mesh"):
    builder = mesh["builder"]
    if builder not in ("box", "hemisphere") and mesh["grading"] != [1.0, 1.0, 1.0]:
        _fail(f"{where}.grading", f"grading applies to the box and hemisphere builders, not {builder!r}")
    if builder == "hemisphere" and min(mesh["grading"]) < 1.0:
        _fail(f"{where}.grading", f"the hemisphere's grading clusters cells towards its pole only: expected "
              f"numbers >= 1, found {mesh['grading']}")
    if builder == "box":
        size = mesh["size"]
        if min(size) < 1e-4 * max(size):
            _fail("mesh.size", f"the smallest length must be at least 1e-4 × the largest (the surfaces are "
                  f"told apart by a relative tolerance), found {size}")
        if any(abs(o + s) > MAX_LENGTH for o, s in zip(mesh["origin"], size)):
            _fail("mesh.size", f"the box reaches beyond coordinates of {MAX_LENGTH:g} (origin {mesh['origin']})")
        cells = mesh["n"] * mesh["n"] * mesh["m"]
    elif builder == "shell_octant":
        if mesh["n"] % 2:
            _fail("mesh.n", f"the shell_octant builder needs an even n (n/2 elements on each of the three "
                  f"patches' edges), found {mesh['n']}")
        r, t = mesh["inner_radius"], mesh["thickness"]
        if t < 1e-6 * r or r < 1e-6 * t:
            _fail("mesh.thickness", f"expected thickness and inner_radius within a factor 1e6 of each other "
                  f"(the mesh degenerates otherwise), found thickness {t}, inner_radius {r}")
        cells = 3 * (mesh["n"] // 2) ** 2 * mesh["m"]
    else:
        return
    if cells > MAX_CELLS:
        _fail("mesh.n", f"n = {mesh['n']}, m = {mesh['m']} make {cells:.3g} hexahedra, more than {MAX_CELLS:.0e}")


def _check_probe_in_body(path, point, mesh):
    """A probe of a built-in mesh lies in the body (whether a mesh node is
    there is known once the mesh is built)."""
    if mesh["builder"] == "box":
        lo, size = mesh["origin"], mesh["size"]
        tol = 1e-6 * max(size)
        if any(not (l - tol <= p <= l + s + tol) for p, l, s in zip(point, lo, size)):
            hi = [l + s for l, s in zip(lo, size)]
            _fail(path, f"{point} is outside the body, the box from {lo} to {hi} (mesh.origin, mesh.size)")
    elif mesh["builder"] == "shell_octant":
        r, t = mesh["inner_radius"], mesh["thickness"]
        tol = 1e-6 * (r + t)
        radius = math.sqrt(sum(p * p for p in point))
        if min(point) < -tol or not (r - tol <= radius <= r + t + tol):
            _fail(path, f"{point} is outside the body, the octant x, y, z >= 0 of the shell "
                  f"{r:g} <= |x| <= {r + t:g} (mesh.inner_radius, mesh.thickness)")


def _check_parameters(material, formulation, where="material"):
    """Built-in laws: exactly their parameters, typed and in range; any law:
    numbers finite (K = inf only for the incompressible limit)."""
    law, params = material["law"], material["parameters"]
    for key, value in params.items():
        path = f"{where}.parameters.{key}"
        if isinstance(value, list):
            if not all(_finite(v) and _magnitude_ok(v) for v in value):
                _fail(path, f"expected a number, a string, true/false or a list of finite numbers "
                      f"({MAGNITUDE[1]}), found {_describe(value)}")
        elif _num(value):
            if math.isnan(value) or (math.isinf(value) and not (key == "K" and value > 0)):
                _fail(path, f"expected a finite number{' (or K = inf)' if key == 'K' else ''}, "
                      f"found {_describe(value)}")
            if math.isfinite(value) and not _magnitude_ok(value):
                _fail(path, f"expected {MAGNITUDE[1]}{' (or K = inf)' if key == 'K' else ''}, "
                      f"found {_describe(value)}")
        elif not isinstance(value, (str, bool)):
            _fail(path, f"expected a number, a string, true/false or a list of numbers, found {_describe(value)}")
    if law in BUILTIN_LAWS:
        expected = BUILTIN_LAWS[law]
        for key in params:
            if key not in expected:
                close = difflib.get_close_matches(key, list(expected), n=1)
                hint = f"; did you mean '{close[0]}'?" if close else ""
                _fail(f"{where}.parameters.{key}", f"unknown parameter of {law} (expected "
                      f"{', '.join(expected)}){hint}")
        for key, default in expected.items():
            if key not in params:
                if default is None:
                    _fail(f"{where}.parameters.{key}", f"missing (required by {law})")
                params[key] = default
        for key, value in params.items():
            path = f"{where}.parameters.{key}"
            if key in STRING_PARAMETERS:
                if value not in STRING_PARAMETERS[key]:
                    *first, last = (f'"{v}"' for v in STRING_PARAMETERS[key])
                    choices = f"{', '.join(first)} or {last}"
                    _fail(path, f"expected {choices}, found {_describe(value)}")
            elif not _num(value):
                _fail(path, f"expected a number, found {_describe(value)}")
            elif key == "K" and not value > 0:
                _fail(path, f"expected a bulk modulus > 0 (inf: incompressible), found {_describe(value)}")
        if law == "neo_hookean" and not params["mu"] > 0:
            _fail(f"{where}.parameters.mu", f"expected a shear modulus > 0, found {_describe(params['mu'])}")
        if law == "mooney_rivlin":
            a1, a2 = params["alpha1"], params["alpha2"]
            mu, formula = (2 * (a1 + a2), "2(alpha1 + alpha2)") if params["i2"] == "usual" else \
                (2 * a1 + 8 * a2, "2 alpha1 + 8 alpha2")
            if not mu > 0:
                _fail(f"{where}.parameters", f"the small-strain shear modulus {formula} must be > 0, "
                      f"found {mu:g} (alpha1 = {a1:g}, alpha2 = {a2:g}, i2 = {params['i2']!r})")
    K = params.get("K")
    if _num(K) and math.isinf(K) and formulation != "mixed":
        _fail(f"{where}.parameters.K", 'K = inf (incompressible) needs discretisation.formulation = "mixed"')


def _check_law(material, base_dir, where="material"):
    law = material["law"]
    if not law.startswith("python:"):
        return  # a built-in law, or a name for the function a driver script passes to Simulation
    parts = law.split(":")
    if len(parts) != 3 or not parts[1] or not parts[2]:
        _fail(f"{where}.law", f"expected 'python:FILE.py:FUNCTION', found {_describe(law)}")
    _, path, func = parts
    if not _path_ok(path):
        _fail(f"{where}.law", f"expected a file path without NUL characters, each name at most 255 bytes, "
              f"found {_describe(path)}")
    if not func.isidentifier():
        _fail(f"{where}.law", f"'{_printable(func, 60)}' is not a Python function name")
    f = Path(path)
    if not f.is_absolute():
        f = (base_dir / f).resolve()
    if not _is_file(f, f"{where}.law", "file"):
        _fail(f"{where}.law", f"file '{f}' does not exist")
    if f.suffix != ".py":
        _fail(f"{where}.law", f"file '{f}' is not a Python file (.py)")
    material["law"] = f"python:{f}:{func}"


def _check_discretisation(scene):
    disc, law = scene["discretisation"], scene["material"]["law"]
    formulation = disc["formulation"]
    if formulation != "displacement" and law not in BUILTIN_LAWS:
        _fail("discretisation.formulation", f"{formulation!r} needs a built-in law "
              f"({', '.join(BUILTIN_LAWS)}), found {_describe(law)}")
    if formulation == "mixed" and disc["quadrature_degree"] < 4:
        _fail("discretisation.quadrature_degree", "the mixed formulation's quadratic hexahedra need 3×3×3 "
              f"Gauss points (degree >= 4), found {disc['quadrature_degree']}: fewer leave zero-energy modes")
    if scene["contact"]:
        if formulation == "mixed":
            _fail("discretisation.formulation", "contact needs the displacement or sri formulation with "
                  "degree 1, found \"mixed\"")
        if disc["degree"] != 1:
            _fail("discretisation.degree", "contact needs the displacement or sri formulation with degree 1, "
                  f"found {disc['degree']}")


def _check_surface_name(path, name, surfaces):
    if name not in surfaces:
        close = difflib.get_close_matches(name, list(surfaces), n=1)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        _fail(path, f"the mesh has no surface {_printable(repr(name), 60)} "
              f"(it has {', '.join(sorted(surfaces))}){hint}")


def _check_surfaces(scene):
    """Surface names of the built-in meshes; loads that would do no work."""
    surfaces = BUILDER_SURFACES.get(scene["mesh"]["builder"])
    if surfaces is None:
        return  # a mesh file: its surfaces are known once it is read
    surfaces = dict(surfaces)
    for body in scene["body"]:
        surfaces.update({f"{body['name']}.{k}": v for k, v in BUILDER_SURFACES[body["builder"]].items()})
    for section in ("bc", "pressure", "traction", "contact"):
        for i, entry in enumerate(scene[section]):
            _check_surface_name(f"{section}[{i}].surface", entry["surface"], surfaces)
            if section == "contact" and entry["obstacle"] == "surface":
                for name in entry["master"].split("+"):
                    _check_surface_name(f"{section}[{i}].master", name, surfaces)
    seen = {}
    for i, pr in enumerate(scene["pressure"]):
        name = pr["surface"]
        if name in seen:
            _fail(f"pressure[{i}].surface", f"a second pressure on {name!r} (pressure[{seen[name]}]): "
                  "give one [[pressure]] per surface, with the sum of the values")
        seen[name] = i
        axis = surfaces[name]
        for j, bc in enumerate(scene["bc"]):
            if bc["surface"] != name:
                continue
            fixed = set(bc["fix"])
            if fixed == {"x", "y", "z"} or (axis is not None and "xyz"[axis] in fixed):
                _fail(f"pressure[{i}].surface", f"the pressure on {name!r} acts along a direction that "
                      f"bc[{j}] fixes ({bc['fix']}): it would do no work")


def _check_solver(solver):
    """PETSc options: names without '-', scalar values, known type names."""
    for key, value in solver["petsc"].items():
        path = f"solver.petsc.{key}"
        if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", key):
            hint = " (without the leading '-')" if key.startswith("-") else ""
            _fail(path, f"expected a PETSc option name{hint}")
        if not (isinstance(value, (str, bool)) or _finite(value)):
            _fail(path, f"expected a string, a finite number or true/false, found {_describe(value)}")
        types = _petsc_types().get(key)
        if types is not None and value not in types:
            close = difflib.get_close_matches(str(value), sorted(types), n=1)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            _fail(path, f"expected a PETSc {key.replace('_', ' ')}, found {_describe(value)}{hint}")
    petsc = solver["petsc"]
    if petsc.get("pc_type") in ("ilu", "icc") and petsc.get("pc_factor_mat_solver_type", "mumps") == "mumps":
        _fail("solver.petsc.pc_type", f"{petsc['pc_type']!r} needs pc_factor_mat_solver_type = \"petsc\" "
              "(the default, mumps, has no incomplete factorisations)")


_PETSC_TYPES = None


def _petsc_types():
    """Known values of the PETSc options that select a type."""
    global _PETSC_TYPES
    if _PETSC_TYPES is None:
        try:
            from petsc4py import PETSc
        except ImportError:  # pragma: no cover - petsc4py is a dependency
            _PETSC_TYPES = {}
            return _PETSC_TYPES

        def names(cls):
            return {v for k, v in vars(cls).items() if not k.startswith("_") and isinstance(v, str)}

        _PETSC_TYPES = {
            "ksp_type": names(PETSc.KSP.Type), "pc_type": names(PETSc.PC.Type),
            "snes_type": names(PETSc.SNES.Type), "pc_factor_mat_solver_type": names(PETSc.Mat.SolverType),
            "snes_linesearch_type": {"basic", "bt", "l2", "cp", "nleqerr", "shell"},
        }
    return _PETSC_TYPES


def _check_bodies(scene, base_dir):
    """[[body]] entries: unique names, a built-in main mesh, their own
    materials checked like [material]."""
    if scene["body"] and scene["mesh"]["builder"] == "file":
        _fail("body", 'several bodies need a built-in mesh.builder ("box" or "shell_octant"), found "file"')
    if scene["body"] and scene["discretisation"]["formulation"] == "mixed":
        _fail("discretisation.formulation", 'several bodies need the "displacement" or "sri" formulation, '
              'found "mixed"')
    names = []
    for i, body in enumerate(scene["body"]):
        where = f"body[{i}]"
        if body["name"] in names:
            _fail(f"{where}.name", f"duplicate body name {body['name']!r}")
        names.append(body["name"])
        _check_mesh({**body, "file": ""}, where) if body["builder"] != "box" else None
        if body["builder"] == "box" and min(body["size"]) < 1e-4 * max(body["size"]):
            _fail(f"{where}.size", f"the smallest length must be at least 1e-4 × the largest, found {body['size']}")
        if body["builder"] == "shell_octant" and body["n"] % 2:
            _fail(f"{where}.n", f"the shell_octant builder needs an even n, found {body['n']}")
        cells = body["n"] * body["n"] * body["m"]
        if cells > MAX_CELLS:
            _fail(f"{where}.n", f"n = {body['n']}, m = {body['m']} make {cells:.3g} hexahedra, more than "
                  f"{MAX_CELLS:.0e}")
        _check_law(body["material"], base_dir, f"{where}.material")
        _check_parameters(body["material"], scene["discretisation"]["formulation"], f"{where}.material")
        if scene["discretisation"]["formulation"] != "displacement" and body["material"]["law"] not in BUILTIN_LAWS:
            _fail(f"{where}.material.law", f"formulation {scene['discretisation']['formulation']!r} needs a "
                  f"built-in law ({', '.join(BUILTIN_LAWS)}), found {_describe(body['material']['law'])}")


def _law_of_surface(scene, surface):
    """The [material] or [[body]].material that a surface belongs to."""
    prefix = surface.split(".")[0] if "." in surface else None
    for body in scene["body"]:
        if body["name"] == prefix:
            return body["material"], f"body.{prefix}.material"
    return scene["material"], "material"


def _check_contact_kind(c, where, scene=None):
    """Keys that belong to one kind of contact only; an automatic penalty
    needs a built-in law on the slave side (its small-strain modulus)."""
    if scene is not None and c["eps_n"] == 0:
        material, key = _law_of_surface(scene, c["surface"])
        if material["law"] not in BUILTIN_LAWS:
            _fail(f"{where}.eps_n", f"0 (automatic penalty) needs the slave body's small-strain modulus, "
                  f"but its law ({_describe(material['law'])}, {key}) is not built in: give eps_n")
    if c["obstacle"] == "surface":
        if not c["master"]:
            _fail(f"{where}.master", 'obstacle = "surface" needs the master surface\'s name '
                  '(e.g. "punch.zmin")')
        if c["surface"] in c["master"].split("+"):
            _fail(f"{where}.master", f"the master surface must differ from the slave surface "
                  f"({c['surface']!r}); self-contact is not supported")
        if c["passes"] == 2 and "+" in c["master"]:
            _fail(f"{where}.passes", "two-pass contact needs a single master surface (one name, no '+')")
        if c["mu"] > 0 and (c["passes"] == 2 or c["integration"] == "gauss"):
            _fail(f"{where}.mu", "friction against a deformable surface needs passes = 1 and "
                  'integration = "nodal"')
    else:
        for key, default in (("master", ""), ("passes", 1), ("integration", "nodal"), ("capture", 0.0)):
            if c[key] != default:
                _fail(f"{where}.{key}", f"applies to obstacle = \"surface\" only (this contact's obstacle "
                      f"is {c['obstacle']!r})")


def _check_consistency(scene, base_dir):
    mesh = scene["mesh"]
    if mesh["builder"] == "file":
        if not mesh["file"]:
            _fail("mesh.file", 'missing: builder = "file" needs a mesh file path')
        f = Path(mesh["file"])
        if not f.is_absolute():
            f = (base_dir / f).resolve()
        if not _is_file(f, "mesh.file", "mesh file"):
            _fail("mesh.file", f"mesh file '{f}' does not exist")
        mesh["file"] = str(f)
    elif mesh["file"]:
        _fail("mesh.file", 'given, but mesh.builder is not "file"')
    _check_mesh(mesh)
    _check_law(scene["material"], base_dir)
    _check_parameters(scene["material"], scene["discretisation"]["formulation"])
    _check_bodies(scene, base_dir)
    _check_discretisation(scene)
    _check_surfaces(scene)
    _check_solver(scene["solver"])
    steps = scene["steps"]
    if steps["min"] > steps["initial"]:
        _fail("steps.min", f"must not exceed steps.initial ({steps['initial']}), found {steps['min']}")
    names = [c["name"] for c in scene["contact"]]
    for i, c in enumerate(scene["contact"]):
        if not c["name"]:
            _fail(f"contact[{i}].name", "expected a non-empty name (it names the CSV columns)")
        if names.count(c["name"]) > 1:
            _fail(f"contact[{i}].name", f"duplicate contact name {_printable(repr(c['name']), 60)}")
        _check_contact_kind(c, f"contact[{i}]", scene)
        if c["obstacle"] == "box" and not all(l < h for l, h in zip(c["lo"], c["hi"])):
            _fail(f"contact[{i}].hi", f"box needs lo < hi in every coordinate, found lo={c['lo']} hi={c['hi']}")
        if c["obstacle"] == "cylinder" and not c["radius"] > 0:
            _fail(f"contact[{i}].radius", f"a cylinder needs a radius > 0 (its axis passes through point, along "
                  f"axis), found {c['radius']}")
        if c["obstacle"] != "cylinder" and c["radius"] != 0.0:
            _fail(f"contact[{i}].radius", f"applies to obstacle = \"cylinder\" only (this contact's obstacle is "
                  f"{c['obstacle']!r})")
        if c["obstacle"] == "box":
            # lo + λ motion < hi + λ motion must still hold in floating point
            reach = max(abs(v + f * m) for f in (0.0, 1.0) for corner in (c["lo"], c["hi"])
                        for v, m in zip(corner, c["motion"]))
            if min(h - l for l, h in zip(c["lo"], c["hi"])) < 1e-9 * reach:
                _fail(f"contact[{i}].hi", f"box sides must be at least 1e-9 × the largest coordinate the box "
                      f"reaches ({reach:g}, with its motion), found lo={c['lo']} hi={c['hi']}")
    for name, point in scene["output"]["probes"].items():
        if not _finite_vec3(point):
            _fail(f"output.probes.{name}", f"expected a list of three finite numbers, found {_describe(point)}")
        scene["output"]["probes"][name] = [float(v) for v in point]
        if not scene["body"]:  # with several bodies, Probe checks for a node when the mesh exists
            _check_probe_in_body(f"output.probes.{name}", scene["output"]["probes"][name], mesh)
    if steps["control"] != "load":
        if steps["stop_probe"] not in scene["output"]["probes"]:
            _fail("steps.stop_probe", f"{steps['control']} control needs a probe of output.probes "
                  f"(found {_printable(repr(steps['stop_probe']), 60)}; probes: "
                  f"{_printable(', '.join(scene['output']['probes']) or 'none', 200)})")
        loads = ([p["value"] != 0 for p in scene["pressure"]] + [any(t["value"]) for t in scene["traction"]]
                 + [any(b["value"]) for b in scene["body_force"]])
        if not loads:
            _fail("steps.control", f"{steps['control']} control needs a load: a [[pressure]], [[traction]] "
                  "or [[body_force]] entry")
        if not any(loads):
            first = next(f"{s}[0].value" for s in ("pressure", "traction", "body_force") if scene[s])
            _fail(first, f"{steps['control']} control needs a non-zero load, found only zero loads")
        if any(any(c["motion"]) for c in scene["contact"]):
            _fail("steps.control", f"{steps['control']} control with moving obstacles is not supported yet")
        for i, c in enumerate(scene["contact"]):
            if c["obstacle"] == "surface":
                _fail(f"contact[{i}].obstacle", f"{steps['control']} control with a deformable master "
                      f"(obstacle = \"surface\") is not supported yet (its contact search runs between the load "
                      f"steps of load control); use load control or a rigid obstacle")
            if c["enforcement"] == "augmented_lagrangian":
                _fail(f"contact[{i}].enforcement", f"the augmented Lagrangian's updates run between the Newton "
                      f"solves of load control; with {steps['control']} control use \"penalty\"")
        if any(any(bc["motion"]) for bc in scene["bc"]):
            _fail("steps.control", f"{steps['control']} control with prescribed motion is not supported yet")
    for i, bc in enumerate(scene["bc"]):
        if len(set(bc["fix"])) != len(bc["fix"]):
            _fail(f"bc[{i}].fix", f"repeated axis in {bc['fix']}")
        free_moving = [a for a, m in zip("xyz", bc["motion"]) if m != 0 and a not in bc["fix"]]
        if free_moving:
            _fail(f"bc[{i}].motion", f"moves {', '.join(free_moving)}, which bc[{i}].fix does not hold "
                  f"(fix = {bc['fix']})")


def parse_value(text):
    """A --set value: TOML syntax if it parses (numbers, lists, true), else a string."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def apply_override(data, assignment):
    """Apply ``key.path=value`` (array entries as ``contact.0.eps_n``)."""
    if "=" not in assignment:
        raise SceneError(f"--set {_printable(repr(assignment), 80)}: expected key=value")
    path, text = assignment.split("=", 1)
    path = path.strip()
    keys = path.split(".")
    shown = _printable(path, 80)
    if not all(keys):
        raise SceneError(f"--set {shown}: empty key in the key path")
    node = data
    for i, k in enumerate(keys[:-1]):
        where = ".".join(keys[:i]) or "the scene"
        if isinstance(node, list):
            if not k.isdigit() or int(k) >= len(node):
                valid = f"0..{len(node) - 1}" if node else "it is empty"
                raise SceneError(f"--set {shown}: '{_printable(k, 40)}' is not an index of '{where}' ({valid})")
            node = node[int(k)]
        elif isinstance(node, dict):
            node = node.setdefault(k, {})
        else:
            raise SceneError(f"--set {shown}: '{where}' is {_describe(node)}, not a table")
    last = keys[-1]
    value = parse_value(text.strip())
    if isinstance(node, list):
        if not last.isdigit() or int(last) >= len(node):
            valid = f"0..{len(node) - 1}" if node else "it is empty"
            raise SceneError(f"--set {shown}: '{_printable(last, 40)}' is not an index of "
                             f"'{'.'.join(keys[:-1])}' ({valid})")
        if isinstance(node[int(last)], dict):
            raise SceneError(f"--set {shown}: cannot assign a whole array entry")
        node[int(last)] = value
    elif isinstance(node, dict):
        node[last] = value
    else:
        raise SceneError(f"--set {shown}: '{'.'.join(keys[:-1])}' is {_describe(node)}, not a table")


def load(source, overrides=(), base_dir=None):
    """Load and validate a scene from a path, TOML text or a dict."""
    if isinstance(source, dict):
        data = copy.deepcopy(source)
        base_dir = Path(base_dir or ".")
    else:
        path = Path(source)
        try:
            exists = path.is_file()
        except (OSError, ValueError) as err:
            raise SceneError(f"scene file '{_printable(path, 200)}' cannot be looked up: "
                             f"{_printable(err, 120)}") from None
        if not exists:
            raise SceneError(f"scene file '{_printable(path, 200)}' does not exist")
        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
        except tomllib.TOMLDecodeError as err:
            raise SceneError(f"scene file '{path}' is not valid TOML: {err}") from None
        except UnicodeDecodeError as err:
            raise SceneError(f"scene file '{path}' is not UTF-8 text: {err}") from None
        base_dir = Path(base_dir or path.parent)
    for assignment in overrides:
        apply_override(data, assignment)
    scene = _validate(data, SCHEMA, "")
    _check_consistency(scene, base_dir)
    return scene
