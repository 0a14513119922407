"""The project's key figures, measured through its public interface only, so
that the same script measures the code before and after a refactor.

    .venv/bin/python bench/key_figures.py --label before       # → bench/results/key_figures_before.{json,md}
    .venv/bin/python bench/key_figures.py --label after --only hertz   # one case again, merged into the file
    .venv/bin/python bench/key_figures.py --quick              # a smoke subset → key_figures_<label>_quick.*
    .venv/bin/python bench/key_figures.py --compare            # before against after → key_figures_compare.md
    .venv/bin/python bench/key_figures.py --label after --quick; .venv/bin/python bench/key_figures.py --compare --quick

Every run is a subprocess with one thread (OMP_NUM_THREADS = OPENBLAS_NUM_THREADS
= 1): the command line ``hypercontact run SCENE --set KEY=VALUE … --out DIR``
(built-in scene names), ``hypercontact study patch``, and the driver
``bench/ironing.py --die rigid --eps-t 5`` for the two-phase ironing path. The
figures are read from what the runs write: curves.csv and summary.json
(study.csv, ironing_rigid.json); results folders and console logs go to
/tmp/key_figures/<label>/. The settings are those of the tests and benchmarks
the README quotes (named per case below), with output.xdmf = false (no fields
file; the physics does not depend on it).

Cost of a run, from its summary.json (``time_split`` is wall time per phase):
    N    = Σ_steps newton_iterations (curves.csv) + Σ_failed attempts newton_iterations
    T    = wall_time − time_split["output"]        (the run after its set-up, without output)
    s/it = T / N
    share(word) = Σ_{phase name contains word} time_split[phase] / T
with the words "contact" (evaluation and search), "volume", "linear". Only ratios
within one run are to be trusted on a shared machine; the load average
(/proc/loadavg, 1-min value) is recorded at the start and end of every run.
A benchmark reports; it asserts nothing.
"""
import argparse
import csv
import json
import os
import shlex
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "bench" / "results"
WORK = Path("/tmp/key_figures")
ENV = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
NO_FIELDS = ["output.xdmf=false"]
MU_PUNCH = 2.0 * (0.1863 + 0.0098)  # small-strain shear modulus of the punch's Mooney law (usual I2)
K_RATIOS = (10.0, 1e2, 1e3, 1e4)  # K/μ of tests/hard/test_incompressible_punch.py
FRICTION = ("punch_mu0.3_0", "punch_mu1_0", "punch_mu0_1", "punch_mu0.3_1")
#: the runs whose cost the issue asks for: (case, row)
COST_ROWS = (("punch", "32x32x8"), ("hertz", "hertz"), ("friction", "punch_mu0.3_0"))


# ---------------------------------------------------------------- running
def loadavg():
    """The 1-, 5- and 15-minute load averages of the machine."""
    return [float(v) for v in Path("/proc/loadavg").read_text().split()[:3]]


def hypercontact():
    """The console script next to this Python (the project's .venv), else on PATH."""
    exe = Path(sys.executable).with_name("hypercontact")
    return str(exe) if exe.exists() else (shutil.which("hypercontact") or "hypercontact")


def run_process(args, out):
    """Run ``args`` in the repository with one thread; the console goes to
    OUT.log beside the (emptied) results folder OUT."""
    shutil.rmtree(out, ignore_errors=True)
    out.parent.mkdir(parents=True, exist_ok=True)
    log = out.parent / f"{out.name}.log"
    start, t0 = loadavg(), time.perf_counter()
    print(f"  $ {shlex.join(args)}   (load {start[0]:.2f})", flush=True)
    with open(log, "w") as f:
        done = subprocess.run(args, stdout=f, stderr=subprocess.STDOUT, env=ENV, cwd=ROOT)
    info = {"command": shlex.join(args), "out": str(out), "log": str(log), "returncode": done.returncode,
            "wall_process_s": time.perf_counter() - t0, "load_start": start, "load_end": loadavg()}
    print(f"    exit {done.returncode} after {info['wall_process_s']:.1f} s (load {info['load_end'][0]:.2f})",
          flush=True)
    return info


def number(text):
    try:
        return float(text)
    except ValueError:
        return text


def run_scene(scene, sets, out):
    """``hypercontact run SCENE --set … --out OUT``; returns the process info
    with the rows of curves.csv (numbers) and summary.json."""
    args = [hypercontact(), "run", scene, "--out", str(out)]
    for s in [*NO_FIELDS, *sets]:
        args += ["--set", s]
    info = run_process(args, out)
    curves, summary = out / "curves.csv", out / "summary.json"
    with open(curves) if curves.exists() else open(os.devnull) as f:
        info["rows"] = [{k: number(v) for k, v in r.items()} for r in csv.DictReader(f)]
    info["summary"] = json.loads(summary.read_text()) if summary.exists() else {}
    return info


# ---------------------------------------------------------------- figures of a run
def final(run, column):
    return run["rows"][-1][column] if run["rows"] else float("nan")


def newton(run):
    """Load steps, cut-backs and Newton iterations of the converged steps."""
    its = [int(r["newton_iterations"]) for r in run["rows"]]
    return {"status": run["summary"].get("status", f"exit {run['returncode']}"), "steps": len(its),
            "cutbacks": len(run["summary"].get("failed_attempts", [])), "newton_per_step": its,
            "newton_mean": sum(its) / len(its) if its else float("nan"), "newton_max": max(its, default=0),
            "newton_total": sum(its)}


def cost(run):
    """Wall time, Newton iterations and time split of a run (module docstring)."""
    s = run["summary"]
    split = s.get("time_split", {})
    failed = sum(int(a.get("newton_iterations", 0)) for a in s.get("failed_attempts", []))
    its = sum(int(r["newton_iterations"]) for r in run["rows"]) + failed
    solve = s.get("wall_time", float("nan")) - split.get("output", 0.0)
    share = {w: sum(v for k, v in split.items() if w in k) / solve if solve > 0 else float("nan")
             for w in ("contact", "volume", "linear")}
    return {"wall_process_s": run["wall_process_s"], "wall_run_s": s.get("wall_time", float("nan")),
            "solve_s": solve, "newton_total": its, "newton_failed_attempts": failed,
            "s_per_newton": solve / its if its else float("nan"),
            **{f"{w}_share": v for w, v in share.items()},
            "load_start": run["load_start"][0], "load_end": run["load_end"][0], "time_split": split}


def record(run, figures):
    """A row of a case: its figures, and the run's command, cost and load."""
    keep = ("command", "out", "log", "returncode")
    return {"figures": figures, "run": {**{k: run[k] for k in keep}, "cost": cost(run)}}


def vertex(u, p):
    """The vertex (u*, p*) of the parabola through the highest point of p(u)
    and its two neighbours (the limit point read off the computed curve)."""
    import numpy as np

    k = int(np.argmax(p))
    if k == 0 or k == len(p) - 1:
        return float("nan"), float("nan")
    a, b, c = np.polyfit(u[k - 1:k + 2], p[k - 1:k + 2], 2)
    return float(-b / (2 * a)), float(c - b * b / (4 * a))


# ---------------------------------------------------------------- the cases
def case_punch(work, quick):
    """Frictionless rigid punch (scenes/punch.toml, default steps, as bench/punch.py)
    on four quarter meshes; 32×32×8 is also a cost run."""
    rows = {}
    for n, m in ((4, 1), (8, 2)) + (() if quick else ((16, 4), (32, 8))):
        run = run_scene("punch", [f"mesh.n={n}", f"mesh.m={m}"], work / f"punch_{n}x{n}x{m}")
        rows[f"{n}x{n}x{m}"] = record(run, {
            "punch_force_N": -final(run, "punch_fz"), "base_force_N": final(run, "base_fz"),
            "edge_uz_mm": final(run, "edge_uz"), "corner_uz_mm": final(run, "corner_uz"), **newton(run)})
    return rows


def case_friction(work, quick):
    """The friction scenes as they are (16×16×4, ε_T = 10); punch_mu0.3_0 is also a cost run."""
    rows = {}
    for name in ("punch_mu1_0",) if quick else FRICTION:
        run = run_scene(name, [], work / name)
        rows[name] = record(run, {
            "punch_force_N": -final(run, "punch_fz"), "edge_uz_mm": final(run, "edge_uz"),
            "corner_uz_mm": final(run, "corner_uz"), "dissipation_Nmm": final(run, "dissipation"), **newton(run)})
    return rows


SPHERES = {  # row: results folder, scene, --set, the displacement column the limit point is read against
    "sphere K=5 (steps.max=0.15, as bench/sphere.py --figure)": ("sphere_max0.15", "sphere", ["steps.max=0.15"],
                                                                  "equator_ux"),
    "sphere K=5 (scene as is)": ("sphere", "sphere", [], "equator_ux"),
    "sphere_incompressible": ("sphere_incompressible", "sphere_incompressible", [], "equator_ux"),
    "sphere_plane mu=0": ("sphere_plane_mu0", "sphere_plane", [], "pole_uz"),
    "sphere_plane mu=0.3": ("sphere_plane_mu0.3", "sphere_plane", ["contact.0.mu=0.3"], "pole_uz"),
}


def case_sphere(work, quick):
    """The inflated sphere through its limit point (arc length): the first
    limit point of summary.json, the pressure there (kPa) and the parabola's vertex."""
    import numpy as np

    rows = {}
    for label, (folder, scene, sets, ucol) in SPHERES.items():
        if quick and label != "sphere_plane mu=0":
            continue
        run = run_scene(scene, sets, work / folder)
        limits = run["summary"].get("limit_points", [])
        u = np.array([r[ucol] for r in run["rows"]])
        p = 1e3 * np.array([r["pressure_inner"] for r in run["rows"]])
        at = limits[0]["after_step"] - 1 if limits else None
        u_star, p_star = vertex(u, p) if len(p) >= 3 else (float("nan"), float("nan"))
        figures = {"limit_load_factor": limits[0]["load_factor"] if limits else float("nan"),
                   "limit_points": len(limits), "p_at_limit_kPa": p[at] if at is not None else float("nan"),
                   f"{ucol}_at_limit_mm": u[at] if at is not None else float("nan"),
                   "parabola_p_max_kPa": p_star, f"parabola_{ucol}_mm": u_star,
                   f"final_{ucol}_mm": u[-1] if len(u) else float("nan")}
        if scene == "sphere_plane":
            figures.update(plane_force_N=abs(final(run, "wall_fx")), closed_nodes=final(run, "wall_closed_nodes"))
        rows[label] = record(run, {**figures, **newton(run)})
    return rows


def case_patch(work, quick):
    """The contact patch test (`hypercontact study patch`: scenes/blocks.toml,
    spread (max − min)/|mean| of σ_zz over the cells) for every setting of the study."""
    out = work / "study_patch"
    run = run_process([hypercontact(), "study", "patch", "--out", str(out)], out)
    rows = {}
    with open(out / "study.csv") as f:
        for r in csv.DictReader(f):
            label = r["settings"].replace("contact.0.", "").replace('"', "")
            rows[label] = {"figures": {"sigma_zz_spread": float(r["value"]), "status": r["status"],
                                       "steps": int(r["steps"]), "newton_total": int(r["newton"])}}
    rows["(the study)"] = {"figures": {}, "run": {k: run[k] for k in ("command", "out", "log", "returncode")}
                           | {"wall_process_s": run["wall_process_s"], "load": [run["load_start"], run["load_end"]]}}
    return rows


def case_hertz(work, quick):
    """Hertz (scenes/hertz.toml as it is): whole-sphere force; also a cost run."""
    if quick:
        return {}
    run = run_scene("hertz", [], work / "hertz")
    return {"hertz": record(run, {"force_N": abs(final(run, "hertz_fz")), "top_uz_mm": final(run, "top_uz"),
                                  **newton(run)})}


def case_ironing(work, quick):
    """Ironing with the rigid smooth die (bench/ironing.py --die rigid --eps-t 5,
    the full path: press 1.4 in 10 steps, slide 4 in 40): steady |Fx/Fz| for s ≥ 1.5."""
    if quick:
        return {}
    out = work / "ironing_rigid"
    run = run_process([sys.executable, str(ROOT / "bench" / "ironing.py"), "--die", "rigid", "--eps-t", "5",
                       "--out", str(out)], out)
    data = json.loads((out / "ironing_rigid.json").read_text())
    a, steps = data.get("analysis", {}), data["rows"]
    slide = [r["s"] for r in steps if r["phase"] == "slide"]
    figures = {"ratio_mean": a.get("ratio_mean"), "ratio_min": a.get("ratio_min"), "ratio_max": a.get("ratio_max"),
               "local_ratio": a.get("local_ratio"), "Fx_mean": a.get("Fx_mean"), "Fz_mean": a.get("Fz_mean"),
               "status": data["status"], "slide_reached": slide[-1] if slide else 0.0, "steps": len(steps),
               "cutbacks": sum(r.get("cutbacks", 0) for r in steps),
               "newton_total": sum(r.get("newton", 0) for r in steps)}
    return {"rigid die": {"figures": figures, "run": {k: run[k] for k in ("command", "out", "log", "returncode")}
                          | {"wall_process_s": run["wall_process_s"], "wall_driver_s": data.get("wall_s"),
                             "load": [run["load_start"], run["load_end"]]}}}


def case_incompressible(work, quick):
    """The near-incompressible punch (tests/hard/test_incompressible_punch.py's
    case: 8×8×2, K = (K/μ)·μ, sri and the plain formulation) and two nearly
    incompressible blocks (scenes/blocks_incompressible.toml as it is)."""
    rows = {}
    for formulation in ("sri", "displacement"):
        for ratio in K_RATIOS[:1] if quick else K_RATIOS:
            label = f"punch 8x8x2 {formulation} K/mu={ratio:g}"
            sets = ["mesh.n=8", "mesh.m=2", f"material.parameters.K={ratio * MU_PUNCH!r}",
                    f'discretisation.formulation="{formulation}"']
            run = run_scene("punch", sets, work / label.replace(" ", "_").replace("/", ""))
            rows[label] = record(run, {"punch_force_N": -final(run, "punch_fz"), "base_force_N": final(run, "base_fz"),
                                       "edge_uz_mm": final(run, "edge_uz"), **newton(run)})
    run = run_scene("blocks_incompressible", [], work / "blocks_incompressible")
    rows["blocks_incompressible"] = record(run, {"interface_force_N": abs(final(run, "interface_fz")),
                                                 "corner_uz_mm": final(run, "corner_uz"), **newton(run)})
    return rows


CASES = {"punch": case_punch, "friction": case_friction, "sphere": case_sphere, "patch": case_patch,
         "hertz": case_hertz, "ironing": case_ironing, "incompressible": case_incompressible}


# ---------------------------------------------------------------- measuring
def git(*args):
    return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True).stdout.strip()


def revision():
    """HEAD, the last commit that changed anything outside bench/, and the
    tracked files changed in the work tree (none for a clean measurement)."""
    return {"commit": git("rev-parse", "HEAD"), "code_commit": git("log", "-1", "--format=%H", "--", ".", ":!bench"),
            "dirty_files": git("status", "--porcelain", "--untracked-files=no").splitlines()}


def measure(names, label, quick):
    """Run the named cases, yielding (name, record) after each; a case that
    raises is recorded with its error."""
    for name in names:
        doc = " ".join(CASES[name].__doc__.split())
        print(f"[{name}] {doc}", flush=True)
        load0, t0 = loadavg(), time.perf_counter()
        try:
            rows, error = CASES[name](WORK / label / name, quick), None
        except Exception as err:  # report what was reached, go on with the next case
            rows, error = {}, f"{type(err).__name__}: {err}"
            print(f"  FAILED: {error}", flush=True)
        yield name, {"description": doc, "rows": rows, "error": error, **revision(),
                     "wall_s": time.perf_counter() - t0, "load_start": load0, "load_end": loadavg()}


def machine():
    model = next((line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                  if line.startswith("model name")), "")
    return {"cpus": os.cpu_count(), "cpu": model, "threads": "OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1"}


# ---------------------------------------------------------------- reporting
def fmt(v, digits=10):
    if isinstance(v, float):
        return f"{v:.{digits}g}"
    if isinstance(v, list):
        return " ".join(fmt(x, digits) for x in v)
    return "" if v is None else str(v)


def table(header, rows):
    return [f"| {' | '.join(header)} |", "|" + "---|" * len(header), *(f"| {' | '.join(r)} |" for r in rows)]


COST_COLUMNS = (("wall_process_s", "process wall (s)"), ("solve_s", "T (s)"), ("newton_total", "Newton its N"),
                ("s_per_newton", "s / Newton it"), ("contact_share", "contact share"),
                ("volume_share", "volume share"), ("linear_share", "linear share"))


def cost_rows(data, pairs):
    out = []
    for case, row in pairs:
        c = data["cases"].get(case, {}).get("rows", {}).get(row, {}).get("run", {}).get("cost")
        if c:
            out.append([f"{case}: {row}", *(fmt(c[k], 3) for k, _ in COST_COLUMNS),
                        f"{c['load_start']:.2f} → {c['load_end']:.2f}"])
    return out


def phase_table(data, pairs):
    costs = {f"{case}: {row}": data["cases"].get(case, {}).get("rows", {}).get(row, {}).get("run", {}).get("cost")
             for case, row in pairs}
    costs = {k: c for k, c in costs.items() if c}
    phases = sorted({p for c in costs.values() for p in c["time_split"]})
    return table(["run", *phases], [[k, *(fmt(c["time_split"].get(p, 0.0) / c["newton_total"], 3) for p in phases)]
                                    for k, c in costs.items()])


def report(data):
    commits = sorted({c["commit"][:10] for c in data["cases"].values()})
    code = sorted({c["code_commit"][:10] for c in data["cases"].values()})
    dirty = sorted({f for c in data["cases"].values() for f in c["dirty_files"]})
    lines = [f"# Key figures: {data['label']}{' (quick subset)' if data['quick'] else ''}", "",
             f"Generated by `bench/key_figures.py` (its docstring defines every figure) at commit(s) "
             f"{', '.join(commits)}; code (everything outside bench/) at {', '.join(code)}"
             f"{'; work tree changes: ' + ', '.join(dirty) if dirty else '; clean work tree'}. "
             f"{data['machine']['cpus']} CPUs ({data['machine']['cpu']}), shared; {data['machine']['threads']}; "
             f"last written {data['generated']}.", ""]
    for name, case in data["cases"].items():
        lines += [f"## {name}", "", case["description"], "",
                  f"Case wall time {case['wall_s']:.0f} s, load {case['load_start'][0]:.2f} → "
                  f"{case['load_end'][0]:.2f}."]
        if case["error"]:
            lines += ["", f"**Stopped: {case['error']}**"]
        groups = {}  # rows with the same figures share a table
        for label, r in case["rows"].items():
            if r["figures"]:
                groups.setdefault(tuple(r["figures"]), []).append([label, *map(fmt, r["figures"].values())])
        for keys, rows in groups.items():
            lines += ["", *table(["", *keys], rows)]
        lines += ["" if groups else "\n(nothing measured: not in this subset)\n"]
    lines += ["## Cost", "", "The three runs the issue names (N, T, s/it and shares as the docstring defines them):",
              "", *table(["run", *(h for _, h in COST_COLUMNS), "load"], cost_rows(data, COST_ROWS)), "",
              "Their time split (summary.json `time_split`), seconds per Newton iteration (phase / N):", "",
              *phase_table(data, COST_ROWS), "", "Every run:", ""]
    every = [(n, r) for n, c in data["cases"].items() for r, v in c["rows"].items() if "cost" in v.get("run", {})]
    lines += [*table(["run", *(h for _, h in COST_COLUMNS), "load"], cost_rows(data, every)), ""]
    return "\n".join(lines)


def relative(a, b):
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (a, b)):
        return "same" if a == b else "differs"
    return f"{(b - a) / abs(a):+.2e}" if a else f"{b - a:+.3g}"


def compare(before, after):
    """before → after of every figure both files have, and of the cost."""
    lines = ["# Key figures: before → after", "",
             f"Before: commit(s) {', '.join(sorted({c['commit'][:10] for c in before['cases'].values()}))}; "
             f"after: {', '.join(sorted({c['commit'][:10] for c in after['cases'].values()}))} "
             "(`bench/key_figures.py --compare`). Change: (after − before)/|before|.", ""]
    rows = []
    for name, case in before["cases"].items():
        for label, r in case["rows"].items():
            other = after["cases"].get(name, {}).get("rows", {}).get(label, {}).get("figures", {})
            for key, a in r["figures"].items():
                if key in other:
                    rows.append([name, label, key, fmt(a), fmt(other[key]), relative(a, other[key])])
    changes = [(abs(float(r[5])), r) for r in rows if r[5] not in ("same", "differs")]
    worst = max(changes, default=(0.0, None), key=lambda c: c[0])[1]
    lines += [f"Largest change of a number: {worst[5]} ({worst[0]}, {worst[1]}, {worst[2]}); lists or texts "
              f"that differ: {sum(r[5] == 'differs' for r in rows)}." if worst else "No numbers in common.", "",
              *table(["case", "row", "figure", "before", "after", "change"], rows), "", "## Cost", ""]
    rows = []
    for name, case in before["cases"].items():
        for label, r in case["rows"].items():
            a = r.get("run", {}).get("cost")
            b = after["cases"].get(name, {}).get("rows", {}).get(label, {}).get("run", {}).get("cost")
            if a and b:
                rows.append([f"{name}: {label}", fmt(a["s_per_newton"], 3), fmt(b["s_per_newton"], 3),
                             fmt(b["s_per_newton"] / a["s_per_newton"], 3), fmt(a["contact_share"], 3),
                             fmt(b["contact_share"], 3), f"{a['load_start']:.1f}/{b['load_start']:.1f}"])
    lines += table(["run", "s/it before", "s/it after", "after/before", "contact share before",
                    "contact share after", "load at start (before/after)"], rows)
    return "\n".join(lines) + "\n"


def write(data, stem):
    (RESULTS / f"{stem}.json").write_text(json.dumps(data, indent=1) + "\n")
    (RESULTS / f"{stem}.md").write_text(report(data) + "\n")
    print(f"wrote {RESULTS / stem}.json and .md", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--label", default="before", help="names the results: key_figures_<label>.{json,md}")
    ap.add_argument("--only", action="append", choices=list(CASES), default=None,
                    help="only this case (repeatable); merged into an existing results file of the label")
    ap.add_argument("--quick", action="store_true", help="a smoke subset (about a minute): key_figures_<label>_quick")
    ap.add_argument("--compare", action="store_true",
                    help="only write key_figures_compare.md from key_figures_before.json and key_figures_after.json "
                         "(with --quick: key_figures_after_quick.json → key_figures_compare_quick.md)")
    args = ap.parse_args()
    quick = "_quick" if args.quick else ""
    if args.compare:  # a quick subset repeats rows of the full run with the same settings
        before, after = (json.loads((RESULTS / name).read_text())
                         for name in ("key_figures_before.json", f"key_figures_after{quick}.json"))
        (RESULTS / f"key_figures_compare{quick}.md").write_text(compare(before, after))
        return print(f"wrote {RESULTS}/key_figures_compare{quick}.md")
    stem = f"key_figures_{args.label}{quick}"
    path = RESULTS / f"{stem}.json"
    data = json.loads(path.read_text()) if args.only and path.exists() else {"cases": {}}
    data.update(label=args.label, quick=args.quick, machine=machine())
    for name, case in measure(args.only or list(CASES), args.label, args.quick):
        data["cases"][name] = case
        data["generated"] = time.strftime("%Y-%m-%d %H:%M:%S %z")
        write(data, stem)  # after every case: a run stopped early keeps what it measured


if __name__ == "__main__":
    main()
