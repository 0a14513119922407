"""Scene fuzzing: every mutated scene is either run or rejected with a
one-paragraph error naming a scene key or a file, never a traceback.

A seeded generator takes a built-in scene (parsed with tomllib), applies 1–3
random mutations (deleted keys, array entries and tables; values of the
wrong type; values out of range: negative, zero, 1e±300, nan, ±inf, 2**63,
empty or over-long strings, NUL characters, unknown enum values; unknown
keys and near-miss spellings; vectors of the wrong length; duplicate contact
names; unknown surfaces; probes off the mesh; switched builders, laws,
formulations, controls and material parameters; PETSc options; broken
``--set`` overrides; and valid changes, so that a fair share passes), writes
it back as TOML and calls ``hypercontact check``. A scene that passes the
check is built (mesh, forms, contact, solver) at a tiny size, and a seeded
subset of those is also run for a few load steps.

Then a few deterministic regression cases for the bugs the fuzzer found.
"""
import copy
import math
import re
import time
import tomllib

import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI
from petsc4py import PETSc

from hypercontact import cli, scene
from hypercontact.simulation import Simulation

SCENES = {name: tomllib.loads((ROOT / "scenes" / f"{name}.toml").read_text())
          for name in ("punch", "sphere", "sphere_incompressible")}
CASES_PER_SCENE = 100          # 300 cases in all
RUN_FRACTION = 0.3             # of the accepted cases run for a few steps (about 20); the others are built
TINY = ["mesh.n=2", "mesh.m=1", "steps.max_steps=2"]  # a 2 × 2 × 1 box, a 3-cell shell; 2 continuation steps
KEY = re.compile(r"scene key '[^'\n]*'|scene file '[^'\n]*'|mesh file '[^'\n]*'|--set |material law 'python:")


# ---------------------------------------------------------------- TOML writer
# (tomli_w is not on this machine.) Every top-level key is written as
# ``"key" = <inline value>``: inline tables and arrays of inline tables parse
# to the same dicts and lists as [table] and [[array]] headers, and mixed or
# nested arrays are legal TOML 1.0.

def _toml_string(s):
    out = []
    for ch in s:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return _toml_string(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_toml_string(k)} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(f"cannot write {v!r} as TOML")


def dumps(data):
    return "".join(f"{_toml_string(k)} = {_toml_value(v)}\n" for k, v in data.items())


def _same(a, b):
    """Equality with nan == nan."""
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return type(a) is type(b) and a == b


# ------------------------------------------------------------------- mutations

WRONG_TYPES = ["text", "", 3, -2, 2.5, True, False, [], [1, 2], ["a", "b"], [1.0, 2.0, 3.0],
               {}, {"a": 1}, {"x": {"y": [1, {"z": "deep"}]}}, [{"a": 1}], [[1, 2], [3]],
               "x" * 400, {"k" + str(i): i for i in range(40)}]
BAD_NUMBERS = [-1, 0, -1.5, 0.0, -0.0, 1e300, -1e300, 1e-300, 1e200, 1e-200, float("nan"), float("inf"),
               float("-inf"), 2**63 - 1, -(2**63), 10**9, 7]
BAD_STRINGS = ["", "unknown", " ", "Box", "shell-octant", "mooney-rivlin", "neo_hooke", "xy", "μ",
               "a\x00b", "python:nowhere.py:psi", "python:law.py", "python:a:b:c", "../../etc",
               "x" * 300, "/".join(["y" * 200] * 30), "displacment", "arclenght", "plane ", "zmax"]
BAD_VECTORS = [[], [1.0], [1.0, 2.0], [1.0, 2.0, 3.0, 4.0], [[1.0, 2.0, 3.0]], ["1", "2", "3"],
               [1, True, 3], [float("nan"), 0.0, 0.0], [float("inf"), 0.0, 1.0], [0.0, 0.0, 0.0],
               [1e300, 1e300, 1e300], [-1e300, 0.0, 1.0], [1e-300, 1e-300, 1e-300], [-1.0, -1.0, -1.0],
               [1e9, 1e9, 1e9], [1e-6, 1.0, 1.0]]
SURFACES = ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax", "inner", "outer", "top", "", "XMIN", "body"]
ENUMS = {
    "builder": ["box", "shell_octant", "file"],
    "law": ["mooney_rivlin", "neo_hookean", "python:law.py:psi", "python:missing.py:psi",
            "python:garbage.msh:psi", "ogden"],
    "formulation": ["displacement", "sri", "mixed", "hybrid"],
    "obstacle": ["plane", "box", "sphere"],
    "control": ["load", "arclength", "displacement", "force"],
    "stop_component": ["x", "y", "z", "w", "xy"],
    "linesearch": ["auto", "basic", "bt", "l2", "cp", "nleqerr", "shell"],
    "i2": ["usual", "paper", "other"],
    "ksp_type": ["preonly", "gmres", "cg", "nonsense"],
    "pc_type": ["lu", "ilu", "none", "nonsense"],
    "pc_factor_mat_solver_type": ["mumps", "petsc", "superlu_dist", "nonsense"],
}
VALID_KEYS = ["title", "mesh", "builder", "inner_radius", "thickness", "size", "origin", "n", "m", "file",
              "material", "law", "parameters", "alpha1", "alpha2", "K", "mu", "i2", "discretisation",
              "degree", "quadrature_degree", "formulation", "pressure", "surface", "value", "bc", "fix",
              "contact", "name", "obstacle", "point", "normal", "lo", "hi", "motion", "eps_n", "steps",
              "control", "initial", "max", "min", "max_cutbacks", "grow_below", "growth", "max_steps",
              "target_iterations", "stop_probe", "stop_component", "stop_value", "solver", "rtol", "atol",
              "max_it", "linesearch", "petsc", "output", "dir", "xdmf", "symmetry_factor", "probes",
              "ksp_type", "pc_type", "snes_max_it"]
BAD_OVERRIDES = ["mesh.n.x=1", "title.a=1", "contact.9.eps_n=1", "contact.x.eps_n=1", "nokey", "contact.0=1",
                 "mesh.size.0=3", "=3", ".=1", "mesh..n=2", "steps.max=", "mesh=3", "output.probes.edge=[1, 2]",
                 "material.parameters.K=inf", "material.parameters.K=-inf", "mesh.n=1e3", "steps.initial=nan",
                 "contact.0.lo.1=5", "bc.-1.fix=[\"x\"]", "pressure.0.value=[]", "solver.petsc.ksp_type=gmres",
                 "mesh.n=99999999999", "discretisation.quadrature_degree=1000000"]


def _num(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _paths(node, prefix=()):
    """Every path (tuple of keys / indices) in a parsed TOML tree, containers included."""
    out = [prefix] if prefix else []
    if isinstance(node, dict):
        for k, v in node.items():
            out += _paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out += _paths(v, prefix + (i,))
    return out


def _tables(node, prefix=()):
    out = [prefix] if isinstance(node, dict) else []
    if isinstance(node, dict):
        for k, v in node.items():
            out += _tables(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out += _tables(v, prefix + (i,))
    return out


def _get(data, path):
    for k in path:
        data = data[k]
    return data


def _set(data, path, value):
    _get(data, path[:-1])[path[-1]] = value


def _pick(rng, seq):
    return seq[int(rng.integers(len(seq)))]


def _near_miss(rng, word):
    if len(word) < 2:
        return word + "x"
    i = int(rng.integers(len(word) - 1))
    kind = int(rng.integers(5))
    if kind == 0:    # swap two letters
        return word[:i] + word[i + 1] + word[i] + word[i + 2:]
    if kind == 1:    # drop a letter
        return word[:i] + word[i + 1:]
    if kind == 2:    # double a letter
        return word[:i] + word[i] + word[i:]
    if kind == 3:
        return word.upper()
    return word + "s"


def _surface_paths(data):
    return [p for p in _paths(data) if p and p[-1] == "surface"]


def mutate(rng, data, notes):
    """Apply one random mutation to ``data`` in place; append a description
    to ``notes``; return extra ``--set`` overrides for the check."""
    kind = _pick(rng, ["benign"] * 6 + ["delete", "delete", "wrong_type", "wrong_type", "number",
                       "string", "unknown_key",
                       "vector", "duplicate_contact", "surface", "probe", "switch", "add_entry",
                       "override", "enum", "stop_probe", "petsc", "parameters"])
    paths = _paths(data)
    if kind == "benign":  # a valid change: a number scaled, a valid enum value, an optional key dropped
        # (Numbers that enter the compiled forms are left alone: every new value
        # is a new JIT compilation of several seconds.)
        numeric = [p for p in paths if _num(_get(data, p)) and p[0] not in ("material", "pressure", "discretisation")]
        enums = [p for p in paths if isinstance(p[-1], str) and p[-1] in ENUMS and isinstance(_get(data, p), str)]
        choice = rng.random()
        if numeric and choice < 0.5:
            path = _pick(rng, numeric)
            old = _get(data, path)
            new = old * float(rng.uniform(0.5, 2.0))
            _set(data, path, max(1, round(new)) if isinstance(old, int) else new)
        elif enums and choice < 0.8:
            path = _pick(rng, enums)
            _set(data, path, _pick(rng, ENUMS[path[-1]][:3]))
        else:
            optional = [p for p in paths if p[-1] in ("title", "steps", "solver", "discretisation", "initial",
                                                      "max", "symmetry_factor", "xdmf", "dir", "origin")]
            if not optional:
                return mutate(rng, data, notes)
            path = _pick(rng, optional)
            del _get(data, path[:-1])[path[-1]]
    elif kind == "delete":
        path = _pick(rng, paths)
        del _get(data, path[:-1])[path[-1]]
    elif kind == "wrong_type":
        path = _pick(rng, paths)
        value = copy.deepcopy(_pick(rng, WRONG_TYPES))
        _set(data, path, value)
    elif kind == "number":
        numeric = [p for p in paths if _num(_get(data, p))] or paths
        path = _pick(rng, numeric)
        value = _pick(rng, BAD_NUMBERS)
        _set(data, path, value)
    elif kind == "string":
        strings = [p for p in paths if isinstance(_get(data, p), str)] or paths
        path = _pick(rng, strings)
        value = _pick(rng, BAD_STRINGS)
        _set(data, path, value)
    elif kind == "unknown_key":
        path = _pick(rng, _tables(data))
        table = _get(data, path)
        if table and rng.random() < 0.6:
            key = _near_miss(rng, _pick(rng, list(table)))
        elif rng.random() < 0.5:
            key = _pick(rng, VALID_KEYS)
        else:
            key = "".join(_pick(rng, list("abcxyz_.- 0")) for _ in range(int(rng.integers(1, 8))))
        value = copy.deepcopy(_pick(rng, WRONG_TYPES + BAD_NUMBERS))
        table[key] = value
        path = path + (key,)
    elif kind == "vector":
        vectors = [p for p in paths if isinstance(_get(data, p), list) and len(_get(data, p)) == 3
                   and all(isinstance(x, (int, float)) for x in _get(data, p))] or paths
        path = _pick(rng, vectors)
        value = copy.deepcopy(_pick(rng, BAD_VECTORS))
        _set(data, path, value)
    elif kind == "duplicate_contact":
        contacts = data.setdefault("contact", [])
        if isinstance(contacts, list) and contacts and isinstance(contacts[0], dict):
            if len(contacts) > 1 and isinstance(contacts[1], dict) and rng.random() < 0.5:
                contacts[1]["name"] = contacts[0].get("name", "x")
            else:
                contacts.append(copy.deepcopy(contacts[0]))
        else:
            data["contact"] = [{"name": "c", "surface": "outer", "obstacle": "plane", "point": [0.0, 0.0, 200.0],
                                "normal": [0.0, 0.0, -1.0], "eps_n": 10.0}] * 2
        path = ("contact",)
    elif kind == "surface":
        surfaces = _surface_paths(data)
        if not surfaces:
            return mutate(rng, data, notes)
        path = _pick(rng, surfaces)
        _set(data, path, _pick(rng, SURFACES))
    elif kind == "probe":
        output = data.setdefault("output", {})
        probes = output.setdefault("probes", {}) if isinstance(output, dict) else None
        if not isinstance(probes, dict):
            return mutate(rng, data, notes)
        name = _pick(rng, list(probes)) if probes and rng.random() < 0.7 else "extra"
        value = _pick(rng, [[1000.0, 0.0, 0.0], [95.5, 0.0, 0.0], [40.0, 0.1, 0.0], [0.0, 0.0, 0.0],
                            [float("nan")] * 3, [float("inf"), 0.0, 0.0], [1.0, 2.0], "edge", {"x": 1.0},
                            [[1.0, 2.0, 3.0]], 5.0])
        probes[name] = copy.deepcopy(value)
        path = ("output", "probes", name)
    elif kind == "switch":
        key, path = _pick(rng, [("builder", ("mesh", "builder")), ("law", ("material", "law")),
                                ("formulation", ("discretisation", "formulation")),
                                ("control", ("steps", "control")), ("degree", ("discretisation", "degree")),
                                ("K", ("material", "parameters", "K")),
                                ("quadrature_degree", ("discretisation", "quadrature_degree")),
                                ("file", ("mesh", "file"))])
        values = {"degree": [1, 2, 3], "K": [float("inf"), 0.0, -5.0, 1e-12, 1e12],
                  "quadrature_degree": [1, 2, 4, 0, 30, 10**6],
                  "file": ["box.msh", "garbage.msh", "missing.msh", "", "."]}.get(key) or ENUMS[key]
        parent = data
        for k in path[:-1]:
            if not isinstance(parent, dict):
                break
            parent = parent.setdefault(k, {})
        if isinstance(parent, dict):
            parent[path[-1]] = _pick(rng, values)
            if parent[path[-1]] == "file" and rng.random() < 0.8:
                parent["file"] = _pick(rng, ["box.msh", "garbage.msh", "missing.msh"])
    elif kind == "add_entry":
        key = _pick(rng, ["contact", "bc", "pressure"])
        entry = _pick(rng, [{}, {"surface": "outer", "value": 0.01}, {"surface": "xmax", "fix": ["x", "y", "z"]},
                            {"name": "wall", "surface": "xmax", "obstacle": "plane", "point": [40.0, 0.0, 0.0],
                             "normal": [-1.0, 0.0, 0.0], "eps_n": 50.0, "motion": [-0.5, 0.0, 0.0]},
                            {"surface": "xmin", "fix": []}, {"surface": "zmin", "fix": ["x", "x"]}])
        target = data.setdefault(key, [])
        if isinstance(target, list):
            target.append(copy.deepcopy(entry))
        else:
            data[key] = [copy.deepcopy(entry)]
        path = (key,)
    elif kind == "override":
        text = _pick(rng, BAD_OVERRIDES)
        notes.append(f"--set {text}")
        return [text]
    elif kind == "enum":
        candidates = [p for p in paths if p and isinstance(p[-1], str) and p[-1] in ENUMS] or paths
        path = _pick(rng, candidates)
        options = ENUMS.get(path[-1], BAD_STRINGS) if isinstance(path[-1], str) else BAD_STRINGS
        value = _pick(rng, options) if rng.random() < 0.7 else _near_miss(rng, str(_get(data, path)))
        _set(data, path, value)
    elif kind == "petsc":  # PETSc options passed through solver.petsc
        solver = data.setdefault("solver", {})
        if not isinstance(solver, dict):
            return mutate(rng, data, notes)
        # Only what the scene can check without running PETSc: option names,
        # value types, the type-selecting options. (A wrong value of any other
        # option, e.g. mat_mumps_icntl_14 = true, fails inside PETSc: see
        # test_petsc_option_value_errors_are_not_caught_yet.)
        key = _pick(rng, ["ksp_type", "pc_type", "pc_factor_mat_solver_type", "snes_type", "snes_linesearch_type",
                          "-ksp_type", "ksp type", "", "snes_max_it", "ksp_rtol", "pc_factor_mat_ordering_type"])
        if key in ("snes_max_it", "ksp_rtol", "pc_factor_mat_ordering_type"):
            options = {"snes_max_it": [30, 1], "ksp_rtol": [1e-8], "pc_factor_mat_ordering_type": ["nd"]}[key]
            options = options + [[1, 2], {"a": 1}, float("nan"), float("inf")]
        else:
            options = ENUMS.get(key, []) + ["nonsense", 3, 2.5, True, float("nan"), [1, 2], {"a": 1}, "", 50]
        value = _pick(rng, options)
        petsc = solver.setdefault("petsc", {})
        if isinstance(petsc, dict):
            petsc[key] = copy.deepcopy(value)
        path = ("solver", "petsc", key)
    elif kind == "parameters":  # material parameters: the law's names, wrong values, another law's names
        material = data.get("material")
        if not isinstance(material, dict):
            return mutate(rng, data, notes)
        params = material.setdefault("parameters", {})
        if not isinstance(params, dict):
            return mutate(rng, data, notes)
        key = _pick(rng, ["alpha1", "alpha2", "K", "mu", "i2", "beta", "Alpha1"])
        if rng.random() < 0.3 and key in params:
            del params[key]
        else:
            params[key] = copy.deepcopy(_pick(rng, BAD_NUMBERS + [0.1, -0.1, "paper", "usual", "other", True, [1.0],
                                                              {"a": 1}, "5"]))
        path = ("material", "parameters", key)
    else:  # stop_probe: rename or remove the probe the continuation stops on
        steps = data.setdefault("steps", {})
        probes = data.get("output", {}).get("probes") if isinstance(data.get("output"), dict) else None
        if isinstance(steps, dict) and rng.random() < 0.5:
            steps["stop_probe"] = _pick(rng, ["", "nowhere", "edge", "pole", "EQUATOR"])
            steps.setdefault("control", _pick(rng, ["arclength", "displacement"]))
        elif isinstance(probes, dict) and probes:
            del probes[_pick(rng, list(probes))]
        path = ("steps", "stop_probe")
    notes.append(f"{kind} {'.'.join(map(str, path))}")
    return []


def _case(scene_name, index):
    rng = np.random.default_rng([2024, list(SCENES).index(scene_name), index])
    data = copy.deepcopy(SCENES[scene_name])
    notes, overrides = [], []
    for _ in range(_pick(rng, [1, 1, 1, 2, 2, 3])):
        overrides += mutate(rng, data, notes)
    runs = np.random.default_rng([7, list(SCENES).index(scene_name), index]).random() < RUN_FRACTION
    return data, overrides, notes, runs


CASES = [(name, i) for name in SCENES for i in range(CASES_PER_SCENE)]
LATE_REJECTIONS = []  # valid for `check`, rejected once the mesh is built
STATS = {"cases": 0, "rejected by check": 0, "built": 0, "rejected by build": 0, "run": 0,
         "run completed": 0, "run failed step (3)": 0, "run rejected (2)": 0, "seconds": 0.0}


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """The files that mutated scenes may name: a real mesh file, a garbage
    one, a user law."""
    from hypercontact import geometry

    d = tmp_path_factory.mktemp("fuzzfiles")
    if MPI.COMM_WORLD.rank == 0:
        gmsh = geometry._gmsh()
        gmsh.clear()
        geometry.box_model(gmsh, [40.0, 40.0, 10.0], 2, 1)
        gmsh.write(str(d / "box.msh"))
        gmsh.clear()
    (d / "garbage.msh").write_text("this is not a mesh\n")
    (d / "law.py").write_text("import ufl\n\ndef psi(F, mu=0.4, K=5.0, alpha1=0.0, alpha2=0.0, i2='usual'):\n"
                              "    J = ufl.det(F)\n"
                              "    I1 = J ** (-2.0 / 3.0) * ufl.tr(F.T * F)\n"
                              "    return 0.5 * mu * (I1 - 3) + 0.5 * K * (J - 1) ** 2\n")
    return d


@pytest.fixture(autouse=True)
def clean_petsc_options():
    """Options a scene sets with solver.petsc stay in PETSc's global database;
    remove them so that cases do not leak into each other."""
    yield
    opts = PETSc.Options()
    for key in list(opts.getAll()):
        if key.startswith(("hc_", "hcc_")):
            opts.delValue(key)


def assert_one_paragraph(err, code):
    assert "Traceback" not in err, err
    if code == 2:
        message = err.strip()
        assert message, "exit code 2 without a message"
        assert "\n\n" not in message, f"more than one paragraph:\n{err}"
        assert len(message) < 600, f"message of {len(message)} characters:\n{err}"
        assert KEY.search(message), f"names neither a scene key nor a file:\n{err}"


def build(path, overrides):
    """Load and build a scene as ``hypercontact run`` does, without running:
    (exit code, message) with cli's classification of errors."""
    try:
        sc = scene.load(path, overrides)
        Simulation(sc, MPI.COMM_WORLD, log=quiet)
    except scene.SceneError as e:
        return 2, f"hypercontact: invalid scene: {e}\n"
    except (FileNotFoundError, ValueError) as e:
        return 2, f"hypercontact: {e}\n"
    return 0, ""


def run_overrides(path):
    """Make a valid scene tiny and short without undoing its mutations:
    smallest mesh, at most 2 continuation steps, few cut-backs and Newton
    iterations, and load steps of at least 0.25."""
    sc = scene.load(path)
    st, sv = sc["steps"], sc["solver"]
    return TINY + [f"steps.initial={max(st['initial'], 0.25)!r}", f"steps.max={max(st['max'], 0.5)!r}",
                   f"steps.max_cutbacks={min(st['max_cutbacks'], 2)}", f"solver.max_it={min(sv['max_it'], 12)}",
                   "output.xdmf=false"]


@pytest.mark.parametrize("scene_name, index", CASES, ids=[f"{n}-{i}" for n, i in CASES])
def test_mutated_scene_runs_or_is_rejected(scene_name, index, files, tmp_path, capsys):
    t0 = time.perf_counter()
    data, overrides, notes, runs = _case(scene_name, index)
    text = dumps(data)
    assert _same(tomllib.loads(text), data)  # the writer is faithful
    path = files / f"{scene_name}-{index}.toml"  # beside box.msh, garbage.msh and law.py
    path.write_text(text)
    STATS["cases"] += 1
    args = ["check", str(path)] + [a for o in overrides for a in ("--set", o)]
    code = cli.main(args)
    err = capsys.readouterr().err
    assert code in (0, 2), f"{notes}: exit code {code}\n{err}"
    assert_one_paragraph(err, code)
    if code == 2:
        STATS["rejected by check"] += 1
        STATS["seconds"] += time.perf_counter() - t0
        return
    if runs:
        STATS["run"] += 1
        tiny = [a for o in run_overrides(path) for a in ("--set", o)]
        code = cli.main(["run", str(path), "--out", str(tmp_path / "out")] + tiny)
        err = capsys.readouterr().err
        assert code in (0, 2, 3), f"{notes}: exit code {code}\n{err}"
        STATS[{0: "run completed", 2: "run rejected (2)", 3: "run failed step (3)"}[code]] += 1
        if code == 2:
            LATE_REJECTIONS.append(f"{scene_name}-{index} (run): {err.strip()[:150]}")
    else:
        code, err = build(path, TINY)
        STATS["built" if code == 0 else "rejected by build"] += 1
        if code:
            LATE_REJECTIONS.append(f"{scene_name}-{index} (build): {err.strip()[:150]}")
    assert_one_paragraph(err, code)
    STATS["seconds"] += time.perf_counter() - t0


def test_fuzz_summary(capsys):
    """The fuzzer reaches every outcome (and reports its counts)."""
    with capsys.disabled():
        print("\nscene fuzz:", ", ".join(f"{k} {v:.0f}" if k == "seconds" else f"{k} {v}"
                                         for k, v in STATS.items()))
        for line in LATE_REJECTIONS:
            print("  rejected after check:", line)
    if STATS["cases"] == len(CASES):  # the whole fuzz ran
        assert STATS["rejected by check"] > 100
        assert STATS["built"] + STATS["rejected by build"] >= 30 and STATS["run"] >= 15


# ------------------------------------------------------ regression cases
# Each was found by the fuzzer (or next to what it found); the comment says
# what happened before the scene checked it.

NAN, INF = float("nan"), float("inf")


def edited(scene_name, edits):
    """A built-in scene with ``{"a.0.b": value}`` edits (value None deletes)."""
    data = copy.deepcopy(SCENES[scene_name])
    for dotted, value in edits.items():
        keys = [int(k) if k.isdigit() else k for k in dotted.split(".")]
        if value is None:
            del _get(data, keys[:-1])[keys[-1]]
        else:
            parent = data
            for k in keys[:-1]:
                parent = parent.setdefault(k, {}) if isinstance(parent, dict) else parent[k]
            parent[keys[-1]] = value
    return data


REGRESSIONS = [
    # PETSc error 63 in SNESSetTolerances (rtol must be < 1)
    ("punch", {"solver.rtol": INF}, "'solver.rtol': expected a finite number, found inf"),
    ("punch", {"solver.rtol": 1.0}, "'solver.rtol': expected < 1"),
    # OverflowError / huge allocation in SNES setTolerances / setConvergenceHistory
    ("punch", {"solver.max_it": 2**63 - 1}, "'solver.max_it': expected an integer from 1 to 1000"),
    # FFCx wrote "nan * ..." into C: the JIT compilation failed (cffi VerificationError)
    ("punch", {"material.parameters.alpha2": NAN}, "'material.parameters.alpha2': expected a finite number"),
    ("punch", {"material.parameters.K": -INF}, "'material.parameters.K': expected a finite number (or K = inf)"),
    # ZeroDivisionError in the mixed forms (compliance 1/K)
    ("sphere_incompressible", {"material.parameters.K": 0.0}, "'material.parameters.K': expected a bulk modulus > 0"),
    # "material law ... raised: i2 must be 'usual' or 'paper'": no key named
    ("sphere", {"material.parameters.i2": 2.5}, "'material.parameters.i2': expected \"usual\" or \"paper\""),
    ("punch", {"material.parameters.alpha1": -0.1}, "'material.parameters': the small-strain shear modulus"),
    # vector norms underflow to 0: ZeroDivisionError in the arc-length predictor
    ("sphere", {"material.parameters.alpha2": 1e200}, "'material.parameters.alpha2': expected 0 or a magnitude from"),
    ("sphere", {"pressure.0.value": 1e-300}, "'pressure[0].value': expected 0 or a magnitude from 1e-100 to 1e+100"),
    ("punch", {"contact.0.eps_n": 1e300}, "'contact[0].eps_n': expected 0 (automatic: penalty_factor × M / h) or from 1e-100 to 1e+100"),
    # ValueError "RigidBox: need lo < hi" from the C++ kernels at lo + λ motion (no key named)
    ("punch", {"contact.0.motion": [0.0, 0.0, -2.0**63]}, "'contact[0].motion': expected coordinates of at most"),
    ("punch", {"contact.0.hi": [20.0, 20.0, 10.000001], "contact.0.motion": [0.0, 0.0, -1e10]},
     "'contact[0].hi': box sides must be at least 1e-9 × the largest coordinate"),
    # ValueError "normal: must be a finite non-zero vector" from the C++ kernels (squared norm underflows)
    ("punch", {"contact.1.normal": [0.0, 0.0, 1e-200]}, "'contact[1].normal': expected a non-zero vector"),
    # ... and the normal of [1e200, 1e200, 0] was silently normalised to [0, 0, 0] (the squared norm overflows)
    ("punch", {"contact.1.normal": [1e200, 1e200, 0.0]}, "'contact[1].normal': expected a non-zero vector"),
    # basix TypeError for 2**63 - 1 (FFCx hangs on large degrees)
    ("sphere", {"discretisation.quadrature_degree": 2**63 - 1},
     "'discretisation.quadrature_degree': expected an integer from 1 to 20"),
    # arc length with a load that does no work: ZeroDivisionError in the predictor
    ("sphere_incompressible", {"pressure.0.surface": "ymin"},
     "'pressure[0].surface': the pressure on 'ymin' acts along a direction that bc[1] fixes"),
    ("sphere", {"pressure.0.value": 0.0}, "'pressure[0].value': arclength control needs a non-zero load"),
    # AttributeError in importlib: an existing file that is not Python
    ("sphere", {"material.law": "python:garbage.msh:psi"}, "garbage.msh' is not a Python file (.py)"),
    ("punch", {"material.law": "python:law.py"}, "'material.law': expected 'python:FILE.py:FUNCTION'"),
    # PETSc error 86 (unknown type) in SNESSetFromOptions; error 92 (mumps has no ILU)
    ("punch", {"solver.petsc": {"ksp_type": "gmress"}}, "'solver.petsc.ksp_type': expected a PETSc ksp type, "
                                                        "found 'gmress' (str); did you mean 'gmres'?"),
    ("punch", {"solver.petsc": {"ksp_type": {"a": 1}}}, "'solver.petsc.ksp_type': expected a string, a finite number"),
    ("punch", {"solver.petsc": {"pc_type": "ilu"}}, "'solver.petsc.pc_type': 'ilu' needs pc_factor_mat_solver_type"),
    ("punch", {"solver.petsc": {"-ksp_type": "gmres"}}, "(without the leading '-')"),
    # OpenCASCADE / gmsh raised a bare Exception (traceback)
    ("punch", {"mesh.size": [1e300, 40.0, 10.0]}, "'mesh.size': expected coordinates of at most 1e+12"),
    ("punch", {"mesh.origin": [1e300, 0.0, 0.0]}, "'mesh.origin': expected coordinates of at most 1e+12"),
    ("sphere", {"mesh.inner_radius": 1e300}, "'mesh.inner_radius': expected at most 1e+12"),
    ("sphere", {"mesh.inner_radius": 1e-300}, "'mesh.thickness': expected thickness and inner_radius within"),
    # box surfaces mislabelled (told apart by a relative tolerance)
    ("punch", {"mesh.size": [1e-6, 40.0, 10.0]}, "'mesh.size': the smallest length must be at least 1e-4"),
    # ValueError from shell.py naming 'n', not 'mesh.n'
    ("sphere", {"mesh.n": 15}, "'mesh.n': the shell_octant builder needs an even n"),
    ("punch", {"mesh.n": 10**9}, "'mesh.n': n = 1000000000, m = 4 make 4e+18 hexahedra, more than 1e+08"),
    # a NaN probe was silently put on mesh node 0
    ("sphere", {"output.probes.equator": [NAN, 0.0, 0.0]},
     "'output.probes.equator': expected a list of three finite numbers"),
    ("punch", {"output.probes.edge": [1000.0, 0.0, 0.0]},
     "'output.probes.edge': [1000.0, 0.0, 0.0] is outside the body"),
    # ValueError "embedded null byte" without a key
    ("punch", {"output.dir": "a\x00b"}, "'output.dir': expected a non-empty path without NUL characters"),
    # OSError "File name too long" from Path.is_file / mkdir
    ("punch", {"mesh.builder": "file", "mesh.file": "x" * 300}, "'mesh.file': expected a path without NUL characters, "
                                                                "each name at most 255 bytes"),
    ("punch", {"mesh.builder": "file", "mesh.file": "/".join(["y" * 200] * 30)}, "' cannot be looked up: [Errno 36]"),
    ("punch", {"material.law": f"python:{'z' * 300}.py:psi"}, "'material.law': expected a file path"),
    ("punch", {"output.dir": "d" * 256}, "'output.dir': expected a non-empty path without NUL characters"),
    # messages of thousands of characters, or over several lines
    ("punch", {"mesh.size": {f"k{i}": i for i in range(40)}}, "'mesh.size': expected a list of three numbers"),
    ("punch", {"mesh.n": "x" * 400}, "'mesh.n': expected an integer, found 'xxxx"),
    ("punch", {"mesh.n\n\nx": 1}, "'mesh.n\\n\\nx': unknown key"),
    # two pressures on one surface wrote one CSV column
    ("sphere", {"pressure": [{"surface": "inner", "value": 0.01}, {"surface": "inner", "value": 0.02}]},
     "'pressure[1].surface': a second pressure on 'inner'"),
    # found only when the mesh or the forms were built; now by `check`
    ("punch", {"contact.1.surface": "inner"}, "'contact[1].surface': the mesh has no surface 'inner'"),
    ("sphere", {"mesh.cells": "tetrahedra"}, "'mesh.cells': cells = 'tetrahedra' applies to the box"),
    ("punch", {"discretisation.formulation": "sri", "material.law": "python:law.py:psi"},
     "'discretisation.formulation': 'sri' needs a built-in law"),
    ("sphere", {"material.parameters.K": INF}, "K = inf (incompressible) needs discretisation.formulation"),
    ("sphere_incompressible", {"discretisation.quadrature_degree": 2}, "(degree >= 4)"),
    ("punch", {"contact.0.name": ""}, "'contact[0].name': expected a non-empty name"),
]


@pytest.mark.parametrize("scene_name, edits, expected", REGRESSIONS,
                         ids=[f"{n}:{','.join(e)[:40]}" for n, e, _ in REGRESSIONS])
def test_regression_rejected_by_check(scene_name, edits, expected, files, capsys):
    path = files / "regression.toml"
    path.write_text(dumps(edited(scene_name, edits)))
    assert cli.main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert expected in err
    assert_one_paragraph(err, 2)


@pytest.mark.parametrize("override, expected", [
    ("title.a=1", "--set title.a: 'title' is 'Rigid square punch"),        # was TypeError
    ("mesh.n.x=1", "--set mesh.n.x: 'mesh.n' is 16 (int), not a table"),   # was TypeError
    ("contact.9.eps_n=1", "'9' is not an index of 'contact' (0..1)"),
    ("mesh..n=2", "--set mesh..n: empty key in the key path"),
    ("contact.0=1", "cannot assign a whole array entry"),
])
def test_regression_bad_override(override, expected, capsys):
    assert cli.main(["check", str(ROOT / "scenes" / "punch.toml"), "--set", override]) == 2
    err = capsys.readouterr().err
    assert expected in err
    assert_one_paragraph(err, 2)


def test_override_sets_a_vector_component():
    sc = scene.load(ROOT / "scenes" / "punch.toml", ["mesh.size.2=5", "material.parameters.K=inf",
                                                    "discretisation.formulation=mixed",
                                                    "discretisation.quadrature_degree=4", "contact=[]"])
    assert sc["mesh"]["size"] == [40.0, 40.0, 5.0] and math.isinf(sc["material"]["parameters"]["K"])


def test_scene_that_is_not_utf8_names_the_file(tmp_path, capsys):
    """Was a UnicodeDecodeError, printed without the file's name."""
    path = tmp_path / "utf16.toml"
    path.write_bytes('title = "Mooney–Rivlin"\n'.encode("utf-16"))
    assert cli.main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "utf16.toml' is not UTF-8 text" in err
    assert_one_paragraph(err, 2)


def test_petsc_option_value_errors_get_a_message(files, tmp_path, capsys):
    """A wrong value of a PETSc option that the scene cannot know (here MUMPS's
    ICNTL(14)) fails inside PETSc's solve: a message, not a traceback."""
    path = files / "icntl.toml"
    path.write_text(dumps(edited("punch", {"solver.petsc": {"mat_mumps_icntl_14": True}})))
    assert cli.main(["check", str(path)]) == 0
    code = cli.main(["run", str(path), "--out", str(tmp_path / "out")] + [a for o in TINY for a in ("--set", o)])
    assert code in (2, 3)
    assert_one_paragraph(capsys.readouterr().err, code)
