"""Scenes: TOML files describing one problem, validated against a schema.

A scene is only data; :func:`load` turns it into plain dicts with every
default filled in, or raises :class:`SceneError` naming the key path, what
was expected and what was found. Unknown keys are rejected with the closest
valid name suggested.
"""
import copy
import difflib
import tomllib
from pathlib import Path


class SceneError(ValueError):
    """Invalid scene; the message names the key path."""


REQUIRED = object()


def _num(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _vec3(x):
    return isinstance(x, list) and len(x) == 3 and all(_num(v) for v in x)


def _positive(x):
    return x > 0


def _positive_vec(x):
    return all(v > 0 for v in x)


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
AXES = (lambda x: len(x) > 0 and set(x) <= {"x", "y", "z"}, 'a non-empty subset of ["x", "y", "z"]')

SCHEMA = {
    "title": Key("string", ""),
    "mesh": {
        "builder": Key("string", "box", (lambda x: x in ("box", "shell_octant", "file"),
                                          '"box", "shell_octant" or "file"')),
        "inner_radius": Key("number", 95.0, POSITIVE),
        "thickness": Key("number", 1.0, POSITIVE),
        "size": Key("vector", [1.0, 1.0, 1.0], (_positive_vec, "all sizes > 0")),
        "origin": Key("vector", [0.0, 0.0, 0.0]),
        "n": Key("integer", 4, POSITIVE),
        "m": Key("integer", 4, POSITIVE),
        "file": Key("string", ""),
    },
    "material": {
        "law": Key("string", REQUIRED),
        "parameters": Key("table", {}),
    },
    "discretisation": {
        "degree": Key("integer", 1, (lambda x: x in (1, 2), "1 or 2")),
        "quadrature_degree": Key("integer", 2, POSITIVE),
        "formulation": Key("string", "displacement", (lambda x: x in ("displacement", "sri", "mixed"),
                                                      '"displacement", "sri" (selective reduced integration) '
                                                      'or "mixed" (Taylor–Hood u–p)')),
    },
    "pressure": [{
        "surface": Key("string", REQUIRED),
        "value": Key("number", REQUIRED),
    }],
    "bc": [{
        "surface": Key("string", REQUIRED),
        "fix": Key("strings", REQUIRED, AXES),
    }],
    "contact": [{
        "name": Key("string", REQUIRED),
        "surface": Key("string", REQUIRED),
        "obstacle": Key("string", REQUIRED, (lambda x: x in ("plane", "box"), '"plane" or "box"')),
        "point": Key("vector", [0.0, 0.0, 0.0]),
        "normal": Key("vector", [0.0, 0.0, 1.0], (lambda v: any(c != 0 for c in v), "a non-zero vector")),
        "lo": Key("vector", [0.0, 0.0, 0.0]),
        "hi": Key("vector", [1.0, 1.0, 1.0]),
        "motion": Key("vector", [0.0, 0.0, 0.0]),
        "eps_n": Key("number", REQUIRED, POSITIVE),
        "mu": Key("number", 0.0, NON_NEGATIVE),
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
        "max_steps": Key("integer", 200, POSITIVE),
        "target_iterations": Key("integer", 5, POSITIVE),
        "stop_probe": Key("string", ""),
        "stop_component": Key("string", "x", (lambda x: x in ("x", "y", "z"), '"x", "y" or "z"')),
        "stop_value": Key("number", 1.0),
    },
    "solver": {
        "rtol": Key("number", 1e-10, POSITIVE),
        "atol": Key("number", 1e-10, POSITIVE),
        "max_it": Key("integer", 25, POSITIVE),
        "linesearch": Key("string", "basic", (lambda x: x in ("basic", "bt", "l2", "cp"), "a PETSc SNES line search: basic, bt, l2 or cp")),
        "petsc": Key("table", {}),
    },
    "output": {
        "dir": Key("string", "results"),
        "xdmf": Key("boolean", True),
        "symmetry_factor": Key("number", 1.0, POSITIVE),
        "probes": Key("table", {}),
    },
}


def _fail(path, msg):
    raise SceneError(f"scene key '{path}': {msg}")


def _describe(value):
    return f"{value!r} ({type(value).__name__})"


def _validate(data, schema, path):
    if isinstance(schema, Key):
        ok, what = KINDS[schema.kind]
        if schema.kind == "number" and isinstance(data, int) and not isinstance(data, bool):
            data = float(data)
        if not ok(data):
            _fail(path, f"expected {what}, found {_describe(data)}")
        if schema.kind == "vector":
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


def _check_consistency(scene, base_dir):
    mesh = scene["mesh"]
    if mesh["builder"] == "file":
        if not mesh["file"]:
            _fail("mesh.file", 'missing: builder = "file" needs a mesh file path')
        f = Path(mesh["file"])
        if not f.is_absolute():
            f = (base_dir / f).resolve()
        if not f.is_file():
            _fail("mesh.file", f"mesh file '{f}' does not exist")
        mesh["file"] = str(f)
    elif mesh["file"]:
        _fail("mesh.file", 'given, but mesh.builder is not "file"')
    law = scene["material"]["law"]
    if law.startswith("python:") and law.count(":") == 2:
        _, path, func = law.split(":")
        if not Path(path).is_absolute():
            scene["material"]["law"] = f"python:{(base_dir / path).resolve()}:{func}"
    steps = scene["steps"]
    if steps["min"] > steps["initial"]:
        _fail("steps.min", f"must not exceed steps.initial ({steps['initial']}), found {steps['min']}")
    names = [c["name"] for c in scene["contact"]]
    for i, c in enumerate(scene["contact"]):
        if names.count(c["name"]) > 1:
            _fail(f"contact[{i}].name", f"duplicate contact name {c['name']!r}")
        if c["obstacle"] == "box" and not all(l < h for l, h in zip(c["lo"], c["hi"])):
            _fail(f"contact[{i}].hi", f"box needs lo < hi in every coordinate, found lo={c['lo']} hi={c['hi']}")
        if c["mu"] != 0.0:
            _fail(f"contact[{i}].mu", f"friction (mu > 0) is not implemented yet; found {c['mu']}")
    for name, point in scene["output"]["probes"].items():
        if not _vec3(point):
            _fail(f"output.probes.{name}", f"expected a list of three numbers, found {_describe(point)}")
    if steps["control"] != "load":
        if steps["stop_probe"] not in scene["output"]["probes"]:
            _fail("steps.stop_probe", f"{steps['control']} control needs a probe of output.probes "
                  f"(found {steps['stop_probe']!r}; probes: {', '.join(scene['output']['probes']) or 'none'})")
        if not scene["pressure"]:
            _fail("steps.control", f"{steps['control']} control needs a load: a [[pressure]] entry")
        if any(any(c["motion"]) for c in scene["contact"]):
            _fail("steps.control", f"{steps['control']} control with moving obstacles is not supported yet")
    for i, bc in enumerate(scene["bc"]):
        if len(set(bc["fix"])) != len(bc["fix"]):
            _fail(f"bc[{i}].fix", f"repeated axis in {bc['fix']}")


def parse_value(text):
    """A --set value: TOML syntax if it parses (numbers, lists, true), else a string."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def apply_override(data, assignment):
    """Apply ``key.path=value`` (array entries as ``contact.0.eps_n``)."""
    if "=" not in assignment:
        raise SceneError(f"--set {assignment!r}: expected key=value")
    path, text = assignment.split("=", 1)
    keys = path.strip().split(".")
    node = data
    for i, k in enumerate(keys[:-1]):
        if isinstance(node, list):
            if not k.isdigit() or int(k) >= len(node):
                raise SceneError(f"--set {path}: '{k}' is not an index of '{'.'.join(keys[:i])}' (0..{len(node) - 1})")
            node = node[int(k)]
        else:
            node = node.setdefault(k, {})
    last = keys[-1]
    if isinstance(node, list):
        raise SceneError(f"--set {path}: cannot assign a whole array entry")
    node[last] = parse_value(text.strip())


def load(source, overrides=(), base_dir=None):
    """Load and validate a scene from a path, TOML text or a dict."""
    if isinstance(source, dict):
        data = copy.deepcopy(source)
        base_dir = Path(base_dir or ".")
    else:
        path = Path(source)
        if not path.is_file():
            raise SceneError(f"scene file '{path}' does not exist")
        try:
            data = tomllib.loads(path.read_text())
        except tomllib.TOMLDecodeError as err:
            raise SceneError(f"scene file '{path}' is not valid TOML: {err}") from None
        base_dir = Path(base_dir or path.parent)
    for assignment in overrides:
        apply_override(data, assignment)
    scene = _validate(data, SCHEMA, "")
    _check_consistency(scene, base_dir)
    return scene
