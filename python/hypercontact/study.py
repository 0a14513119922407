"""What accuracy costs in time: run a scene over a sweep of settings, measure
each case's error against a reference and its wall time, and write a table
and a plot of error against time with the Pareto front marked.

A study is a TOML file::

    title = "Sphere, K = 200: limit pressure"
    scene = "sphere"                       # a built-in scene name or a path (relative to the study)
    set = ["material.parameters.K=200"]    # overrides for every case
    quantity = "max:pressure_inner"        # last:COLUMN | max:COLUMN | min:COLUMN | maxabs:COLUMN
                                           # of the run's curves.csv
    reference = "oracle:sphere_limit_pressure"   # a number, "richardson" (mesh sweeps), an oracle,
                                           # "hertz:a|p0|delta" or "patch:sigma_zz|pressure" (then no quantity)
    [[sweep]]                              # the cases: the product of all sweeps ...
    key = "mesh.n"
    values = [8, 16]
    # cases = [["mesh.n=4", "discretisation.degree=2"], ...]   # ... or an explicit list

Oracles: ``oracle:sphere_limit_pressure`` (the 1D sphere oracle of
:mod:`hypercontact.sphere1d` for the scene's law, parameters and shell).
``richardson`` extrapolates the quantity from the three cases with the
largest ``mesh.n`` (refinement ratio from their n; the estimated uncertainty,
|f∞ − f_finest|, goes into the table); it refuses non-monotone data.

Field references measure each finished case's fields themselves (the
study has no ``quantity`` then) and write the measured points into the
case's folder so that they can be checked by hand:

- ``hertz:a``, ``hertz:p0``, ``hertz:delta`` (:mod:`hypercontact.hertz`): a
  scene with a ``builder = "hemisphere"`` body whose surface is the slave of
  a frictionless contact against another body or a rigid obstacle. The
  Hertz profile p0 √(1 − r²/a²) is fitted to the closed slave points (nodes,
  or Gauss points with ``integration = "gauss"``; r from the sphere's axis,
  current configuration) and compared with Hertz's closed form for the
  case's own force F (the contact force × ``output.symmetry_factor``),
  E* from the bodies' small-strain E, ν and R from the hemisphere:
  a = (3FR/4E*)^(1/3), p0 = 3F/(2πa²), δ = a²/R. The error is relative.
  ``delta`` compares the FE approach of the sphere's top and the bottom of
  the master body on the axis with Hertz's approach of distant points of
  two half-spaces: on finite bodies it carries a geometric error that does
  not fall with h. Points: ``caseNN/hertz_points.csv`` (r, p, closed; F in
  the first line).
- ``patch:sigma_zz``, ``patch:pressure`` (:mod:`hypercontact.patch`): the
  contact patch test, whose exact field is uniform: the error is the
  relative spread (max − min)/|mean| of the Cauchy σ_zz at the cell
  midpoints (all bodies) or of the pressures at the closed slave points of
  the first contact; reference 0. Values: ``caseNN/patch_values.csv``.

A malformed reference, a quantity given with a field reference, or a scene
the reference cannot measure (no hemisphere, friction, no contact) stops
the study before its first case with a message naming the key.
"""
import csv
import itertools
import json
import math
import time
import tomllib
from pathlib import Path

from . import scene as scene_mod
from .scene import SceneError

QUANTITY_OPS = {"last": lambda v: v[-1], "max": max, "min": min, "maxabs": lambda v: max(abs(x) for x in v)}


def _fail(key, message):
    raise SceneError(f"study key '{key}': {message}")


def load_study(path):
    """The validated study dict: the scene path resolved, the scene with the
    study's overrides validated (``base_scene``, the plain dict)."""
    path = Path(path)
    if not path.is_file():
        raise SceneError(f"study file '{path}' does not exist")
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as err:
        raise SceneError(f"study file '{path}' is not valid TOML: {err}") from None
    known = {"title", "scene", "set", "quantity", "reference", "sweep", "cases"}
    for key in data:
        if key not in known:
            _fail(key, f"unknown key (valid: {', '.join(sorted(known))})")
    for key in ("scene", "reference"):
        if key not in data:
            _fail(key, "missing (required)")
    ref = data["reference"]
    field = field_reference(ref)
    if field:
        if "quantity" in data:
            _fail("quantity", f"reference {ref!r} measures its own quantity ({FIELD_REFERENCES[field[0]][field[1]]}); "
                              "remove 'quantity'")
        data["quantity"] = ref
    else:
        if "quantity" not in data:
            _fail("quantity", "missing (required unless the reference is hertz:… or patch:…)")
        op, _, column = str(data["quantity"]).partition(":")
        if op not in QUANTITY_OPS or not column:
            _fail("quantity", f"expected OP:COLUMN with OP one of {', '.join(QUANTITY_OPS)}, found {data['quantity']!r}")
        if not (isinstance(ref, (int, float)) and not isinstance(ref, bool) and math.isfinite(ref)) and \
                ref not in ("richardson", "oracle:sphere_limit_pressure"):
            _fail("reference", "expected a number, \"richardson\", \"oracle:sphere_limit_pressure\", "
                               f"{', '.join(_field_names())}; found {ref!r}")
    if ("sweep" in data) == ("cases" in data):
        _fail("sweep", "give either [[sweep]] entries or a cases list, not both, not neither")
    for i, s in enumerate(data.get("sweep", [])):
        if set(s) != {"key", "values"} or not isinstance(s["values"], list) or not s["values"]:
            _fail(f"sweep[{i}]", "expected key = \"a.scene.key\" and a non-empty values list")
    scene_path = Path(data["scene"])
    if not scene_path.is_absolute():
        scene_path = (path.parent / scene_path) if (path.parent / scene_path).is_file() else \
            scene_mod.SCENES / f"{data['scene']}.toml"
    if not scene_path.is_file():
        _fail("scene", f"no scene file or built-in scene {data['scene']!r}")
    data["scene_path"] = str(scene_path)
    data.setdefault("set", [])
    data.setdefault("title", path.stem)
    # the scene with the study's overrides, validated once, before any case runs
    data["base_scene"] = scene_mod.load(scene_path, data["set"])
    if field:  # the scene must be one the reference applies to
        check_field_reference(field, data["base_scene"])
    return data


#: References measured on each case's fields (the quantity is the reference's own).
FIELD_REFERENCES = {
    "hertz": {"a": "the contact radius of the Hertz profile fitted to the closed slave points",
              "p0": "the peak pressure of the fitted Hertz profile",
              "delta": "the approach of the sphere's top and the master body's bottom on the axis"},
    "patch": {"sigma_zz": "the relative spread (max − min)/|mean| of the Cauchy stress σ_zz over the cells",
              "pressure": "the relative spread of the pressures at the closed slave points of the first contact"},
}


def _field_names():
    return [f'"{k}:{q}"' for k, qs in FIELD_REFERENCES.items() for q in qs]


def field_reference(ref):
    """(kind, quantity) of a hertz:… / patch:… reference, None for the others;
    SceneError for a malformed one."""
    if not isinstance(ref, str):
        return None
    kind, sep, what = ref.partition(":")
    if kind not in FIELD_REFERENCES:
        return None
    if not sep or what not in FIELD_REFERENCES[kind]:
        _fail("reference", f"{ref!r}: expected one of {', '.join(_field_names()[:3] if kind == 'hertz' else _field_names()[3:])}")
    return kind, what


def check_field_reference(field, scene):
    """SceneError if the scene cannot be measured by the reference."""
    kind, what = field
    if kind == "hertz":
        from . import hertz

        try:
            hertz.geometry(scene)
        except SceneError as err:
            _fail("reference", str(err))
    elif not scene["contact"]:
        _fail("reference", f"'patch:{what}' needs a scene with a contact (the patch test's interface)")


def cases_of(study):
    """Each case's list of 'key=value' overrides (after the study's own)."""
    if "cases" in study:
        return [list(c) for c in study["cases"]]
    sweeps = study["sweep"]
    return [[f"{s['key']}={_toml_value(v)}" for s, v in zip(sweeps, combo)]
            for combo in itertools.product(*[s["values"] for s in sweeps])]


def _toml_value(v):
    return json.dumps(v) if isinstance(v, str) else repr(v).lower() if isinstance(v, bool) else repr(v)


def quantity_of(rows, quantity):
    op, _, column = quantity.partition(":")
    values = [float(r[column]) for r in rows]
    if not values:
        raise ValueError(f"quantity {quantity!r}: the run wrote no steps")
    return QUANTITY_OPS[op](values)


def pareto_front(points):
    """Indices of the (time, error) points no other point beats in both
    (≤ in both and < in one)."""
    front = []
    for i, (t, e) in enumerate(points):
        if not any((t2 <= t and e2 <= e) and (t2 < t or e2 < e) for j, (t2, e2) in enumerate(points) if j != i):
            front.append(i)
    return front


def richardson(ns, values):
    """(f∞, uncertainty, order) from the three finest levels of a mesh sweep."""
    order = sorted(range(len(ns)), key=lambda i: ns[i])[-3:]
    if len(order) < 3:
        raise ValueError("richardson: needs at least three mesh levels")
    (n1, f1), (n2, f2), (n3, f3) = [(ns[i], values[i]) for i in order]
    r = n2 / n1
    if abs(n3 / n2 - r) > 1e-9 * r:
        raise ValueError(f"richardson: needs a constant refinement ratio, found n = {n1}, {n2}, {n3}")
    d1, d2 = f2 - f1, f3 - f2
    if d1 == 0 or d2 / d1 <= 0 or abs(d2) >= abs(d1):
        raise ValueError(f"richardson: the quantity does not converge monotonically ({f1:.6g}, {f2:.6g}, {f3:.6g}); "
                         "no extrapolation is meaningful")
    p = math.log(d1 / d2) / math.log(r)
    f_inf = f3 + d2 / (r**p - 1.0)
    return f_inf, abs(f_inf - f3), p


def reference_value(study, base_scene, results):
    ref = study["reference"]
    if isinstance(ref, (int, float)):
        return float(ref), 0.0, "given"
    if ref == "oracle:sphere_limit_pressure":
        from .sphere1d import limit_point

        mesh, mat = base_scene["mesh"], base_scene["material"]
        A = mesh["inner_radius"]
        _, p = limit_point(mat["law"], mat["parameters"], A=A, B=A + mesh["thickness"])
        scale = base_scene["pressure"][0]["value"] if study["quantity"].endswith("load_factor") else 1.0
        return p / scale, 0.0, "1D oracle (hypercontact.sphere1d)"
    family = mesh_family(results)
    ns, values = [r["mesh.n"] for r in family], [r["value"] for r in family]
    try:
        f_inf, unc, p = richardson(ns, values)
        return f_inf, unc, f"Richardson extrapolation over n = {sorted(ns)[-3:]} (order {p:.2f})"
    except ValueError as err:
        # Not extrapolable: the finest case is the reference, the last change its uncertainty.
        order = sorted(range(len(ns)), key=lambda i: ns[i])
        if len(order) < 2:
            raise
        fine, prev = values[order[-1]], values[order[-2]]
        return fine, abs(fine - prev), f"finest mesh n = {ns[order[-1]]}; {err}"


def mesh_family(results):
    """The cases that differ from the finest-mesh case in mesh.* keys only,
    one per mesh.n (for Richardson extrapolation)."""
    def others(r):
        return sorted(s for s in r["settings"].split() if not s.startswith("mesh."))

    finest = max(results, key=lambda r: r["mesh.n"])
    family = {}
    for r in results:
        if others(r) == others(finest):
            family.setdefault(r["mesh.n"], r)
    return list(family.values())


FIELD_HOW = {"hertz": "Hertz's closed form at each case's own contact force (column reference; "
                      "hypercontact.hertz)",
             "patch": "the patch test's exact uniform field: reference 0, the error is the relative spread itself"}


def measure_field(field, scene, sim, case_dir=None):
    """(value, reference) of a finished case for a hertz:… / patch:…
    reference; writes the measured points into case_dir (rank 0) so that
    the numbers can be checked by hand: hertz_points.csv (r, p, closed; the
    force F in its first line) or patch_values.csv."""
    kind, what = field
    if kind == "hertz":
        from . import hertz

        geo = hertz.geometry(scene)
        m = hertz.measure(sim, geo)
        a_H, p0_H, d_H = hertz.closed_form(m["F"], geo["R"], geo["E_star"])
        value, ref = {"a": (m["a_fit"], a_H), "p0": (m["p0_fit"], p0_H), "delta": (m["delta"], d_H)}[what]
        if case_dir is not None:
            with open(case_dir / "hertz_points.csv", "w", newline="") as f:
                f.write(f"# F = {m['F']!r}, R = {geo['R']!r}, E* = {geo['E_star']!r}, delta = {m['delta']!r}\n")
                w = csv.writer(f)
                w.writerow(["r", "p", "closed"])
                w.writerows(zip(m["r"].tolist(), m["p"].tolist(), m["closed"].astype(int).tolist()))
        return value, ref
    from . import patch

    v = patch.values(sim, what)
    if case_dir is not None:
        (case_dir / "patch_values.csv").write_text(what + "\n" + "\n".join(repr(float(x)) for x in v) + "\n")
    return patch.spread(v), 0.0


def field_error(field, value, ref):
    """Relative error against Hertz; the spread itself for the patch test."""
    if field[0] == "patch":
        return value
    return abs(value - ref) / abs(ref) if ref else float("nan")


def run_study(study_path, out_dir, comm=None, log=print):
    """Run every case; write study.csv, study.md and study.png into out_dir."""
    from mpi4py import MPI

    from .simulation import Simulation, StepFailure

    comm = comm or MPI.COMM_WORLD
    study = load_study(study_path)
    field = field_reference(study["reference"])
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    base = study["base_scene"]
    results = []
    for k, case in enumerate(cases_of(study)):
        sc = scene_mod.load(study["scene_path"], study["set"] + case + ["output.xdmf=false"])
        case_dir = out / f"case{k:02d}"
        t0 = time.perf_counter()
        status = "completed"
        sim = Simulation(sc, comm, log=lambda *a, **kw: None)
        t1 = time.perf_counter()  # setup (mesh, JIT compilation of the forms: cached across cases) excluded
        try:
            sim.run(out_dir=str(case_dir))
        except StepFailure:
            status = "failed"
        wall, setup = time.perf_counter() - t1, t1 - t0
        rows = list(csv.DictReader(open(case_dir / "curves.csv"))) if (case_dir / "curves.csv").is_file() else []
        case_ref = float("nan") if field else None
        if field and status == "completed":
            value, case_ref = measure_field(field, sc, sim, case_dir if comm.rank == 0 else None)
        else:
            value = quantity_of(rows, study["quantity"]) if rows and status == "completed" else float("nan")
        newton = sum(int(r["newton_iterations"]) for r in rows)
        results.append({"case": k, "settings": " ".join(case), "value": value, "wall_s": wall, "setup_s": setup,
                        "newton": newton, "steps": len(rows), "status": status, "mesh.n": sc["mesh"]["n"],
                        "reference": case_ref})
        log(f"case {k}: {' '.join(case)}: {study['quantity']} = {value:.8g}, {wall:.1f} s, {newton} Newton its")
    ok = [r for r in results if r["status"] == "completed"]
    if field:
        ref, unc, how = None, 0.0, FIELD_HOW[field[0]]
        for r in results:
            r["error"] = field_error(field, r["value"], r["reference"]) if r["status"] == "completed" else float("nan")
    else:
        ref, unc, how = reference_value(study, base, ok)
        for r in results:
            r["reference"] = ref
            r["error"] = abs(r["value"] - ref) / abs(ref) if r["status"] == "completed" else float("nan")
    ok = [r for r in ok if math.isfinite(r["error"])]
    front = set(pareto_front([(r["wall_s"], r["error"]) for r in ok]))
    for i, r in enumerate(ok):
        r["pareto"] = i in front
    if comm.rank == 0:
        _write(out, study, results, ref, unc, how)
    return results, ref


def _write(out, study, results, ref, unc, how):
    keys = ["case", "settings", "value", "reference", "error", "wall_s", "setup_s", "newton", "steps", "status",
            "pareto"]
    per_case = ref is None  # hertz:… / patch:…: a reference per case
    with open(out / "study.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        for r in results:
            w.writerow({**r, "pareto": r.get("pareto", False)})
    if per_case:
        kind, what = field_reference(study["reference"])
        head = f"Quantity: {FIELD_REFERENCES[kind][what]} (`{study['reference']}`); reference: {how}."
    else:
        head = (f"Quantity: `{study['quantity']}`; reference {ref:.8g} ({how}"
                + (f", uncertainty ±{unc:.3g}" if unc else "") + ").")
    lines = [f"# {study['title']}", "", head, "",
             "Wall time: the solve (load steps, output), without the setup (mesh, form compilation: "
             "cached across runs, so the first case would pay for it). Measured on whatever machine ran the "
             "study; on a shared one the times are noisy (compare them within one run: the ratios hold).", "",
             "| case | settings | value |" + (" reference |" if per_case else "")
             + " error | wall (s) | setup (s) | Newton its | Pareto |",
             "|---|---|---|" + ("---|" if per_case else "") + "---|---|---|---|---|"]
    for r in results:
        lines.append(f"| {r['case']} | {r['settings'] or '(the study set only)'} | {r['value']:.6g} |" + (f" {r['reference']:.6g} |" if per_case else "")
                     + f" {100 * r['error']:.3g} % | {r['wall_s']:.1f} | "
                     f"{r['setup_s']:.1f} | {r['newton']} | {'yes' if r.get('pareto') else ''} |")
    for target in (1e-2, 1e-3):
        hit = [r for r in results if r.get("error", math.inf) <= target]
        best = min(hit, key=lambda r: r["wall_s"]) if hit else None
        lines.append("")
        lines.append(f"Cheapest within {100 * target:g} %: "
                     + (f"{best['settings']} ({best['wall_s']:.1f} s)" if best else "none of these cases"))
    (out / "study.md").write_text("\n".join(lines) + "\n")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ok = [r for r in results if r["status"] == "completed" and math.isfinite(r["error"])]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    floor = 1e-8
    ax.loglog([r["wall_s"] for r in ok], [max(r["error"], floor) for r in ok], "o", color="0.6", label="cases")
    front = sorted([r for r in ok if r["pareto"]], key=lambda r: r["wall_s"])
    ax.loglog([r["wall_s"] for r in front], [max(r["error"], floor) for r in front], "o-", color="C3",
              label="Pareto front")
    for r in ok:  # case numbers: the settings are in study.md's table
        ax.annotate(str(r["case"]), (r["wall_s"], max(r["error"], floor)), fontsize=8,
                    xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("wall time (s); points labelled by case number (study.md)")
    ax.set_ylabel(f"relative error of {study['quantity']}")
    ax.set_title(study["title"], fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "study.png", dpi=110)
    plt.close(fig)
