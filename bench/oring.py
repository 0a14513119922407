"""The O-ring between plates over a mesh ladder: scenes/oring_plates.toml
(mean diameter D = 24, cord d = 4, a quarter in azimuth and the upper half
of the cord, neo-Hookean μ = 1, K = 1000, mixed Taylor–Hood Q2–Q1 on
hexahedra or P2–P1 on tetrahedra, second-order curved cells, a frictionless
rigid plate moving 0.6 down in 10 load steps: 30 % squeeze at λ = 1) on the
O-grid hexahedra n = 4, 8, 12, 16 (m = n layers along the quarter circle)
and gmsh's Delaunay tetrahedra n = 4, 6, 8, 12 (size d/n), automatic penalty;
then hexahedra n = 12 and tetrahedra n = 8, 12 once more with one explicit
penalty, ε_N = 1000, so that the tetrahedra's and the hexahedra's forces
differ by their discretisation only (the automatic penalty 100 M/h depends
on the mesh's h).

    .venv/bin/python bench/oring.py            # → bench/results/oring.md, .json, .png
    .venv/bin/python bench/oring.py --quick    # n = 4, 8 of both kinds → oring_quick.*
    .venv/bin/python bench/oring.py --reuse    # the report from the runs left in --work

Each run is the CLI in a subprocess (one thread, `timeout` 25 min), its log
and results in /tmp/bench_oring/<run>/. A rung is skipped when the previous
rung of the same kind took more than 12 minutes (and a same-penalty run when
its mesh's ladder run did). Per run: unknowns (the log's first line), steps
completed and the status (a run that stops early keeps its converged steps
and the log's last lines), Newton iterations (converged steps: total and the
largest per step; failed attempts counted apart), wall time of the process
(gmsh, forms from the cache, Newton, output) and the run's own wall_time
from summary.json, the peak resident memory of the process (os.wait4). Per
step: the squeeze ε = 2 · 0.6 λ/d, the whole-ring force F = |plate_fz|
(× the scene's symmetry factor 4), Lindley's F_L = π D E d (1.25 ε^1.5 +
50 ε^6), E = 3μ, the ratio F/F_L, the contact width b = plate_area/(π D)
(the loaded nodal area of the whole ring: it grows by whole rows of nodes,
so it is resolved to one node spacing) against Hertz's line-contact width
2a, a = √(4 F' R_c/(π E*)), F' = F/(π D), R_c = d/2, E* = 4μ
(incompressible plane strain). One thread, one run at a time, on a 2-core
machine shared with other jobs: wall times are indicative. A benchmark
reports; it asserts nothing (the test is tests/verification/test_oring.py)."""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import time
import tomllib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "bench" / "results"
SCENE = ROOT / "scenes" / "oring_plates.toml"
CLI = ROOT / ".venv" / "bin" / "hypercontact"
WORK = Path("/tmp/bench_oring")

LADDER = {"hexahedra": [4, 8, 12, 16], "tetrahedra": [4, 6, 8, 12]}
QUICK = {"hexahedra": [4, 8], "tetrahedra": [4, 8]}
#: the same explicit penalty on both kinds of cells: (kind, n)
SAME_PENALTY = 1000.0
SAME_RUNS = [("hexahedra", 12), ("tetrahedra", 8), ("tetrahedra", 12)]
SKIP_AFTER_S = 12 * 60
TIMEOUT_S = 25 * 60
EPS_TABLE = [0.12, 0.18, 0.24, 0.30]

_data = tomllib.loads(SCENE.read_text())
D = _data["mesh"]["mean_diameter"]
CORD = _data["mesh"]["cord_diameter"]
MU = _data["material"]["parameters"]["mu"]
TRAVEL = abs(_data["contact"][0]["motion"][2])
E = 3.0 * MU
E_STAR = 4.0 * MU


def squeeze(lam):
    return 2.0 * TRAVEL * lam / CORD


def lindley(eps):
    return math.pi * D * E * CORD * (1.25 * eps ** 1.5 + 50.0 * eps ** 6)


def hertz_width(F):
    """2a of Hertz's line contact of a cylinder of radius d/2 under F/(π D) per unit length."""
    return 2.0 * math.sqrt(4.0 * (F / (math.pi * D)) * (CORD / 2.0) / (math.pi * E_STAR))


def tag(kind, n, eps_n):
    return f"{kind[:3]}_n{n}" + (f"_eps{eps_n:g}" if eps_n else "")


def overrides(kind, n, eps_n, out):
    sets = [f"output.dir={out}", "output.xdmf=false", f'mesh.cells="{kind}"', f"mesh.n={n}"]
    if kind == "hexahedra":
        sets.append(f"mesh.m={n}")
    if eps_n:
        sets.append(f"contact.0.eps_n={eps_n}")
    return sets


def execute(args, log_path):
    """Run args under `timeout`, stdout and stderr to log_path; (exit code, wall s, peak RSS MB)."""
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "PYTHONUNBUFFERED": "1"}
    with open(log_path, "w") as log:
        t0 = time.perf_counter()
        proc = subprocess.Popen(["timeout", "--kill-after=30", str(TIMEOUT_S)] + args, stdout=log,
                                stderr=subprocess.STDOUT, env=env, cwd=ROOT)
        _, status, usage = os.wait4(proc.pid, 0)  # this child's (and its waited children's) resources
        wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, wall, usage.ru_maxrss / 1024.0


def per_step(rows):
    steps = []
    for r in rows:
        lam = float(r["load_factor"])
        eps, F = squeeze(lam), abs(float(r["plate_fz"]))
        F_L = lindley(eps)
        b = float(r["plate_area"]) / (math.pi * D)
        steps.append({"step": int(r["step"]), "load_factor": lam, "eps": eps, "newton": int(r["newton_iterations"]),
                      "F": F, "F_L": F_L, "F_over_F_L": F / F_L, "closed_nodes": int(r["plate_closed_nodes"]),
                      "b": b, "hertz_2a": hertz_width(F)})
    return steps


def collect(kind, n, eps_n, out, code, wall, rss):
    log = (out / "log.txt").read_text(errors="replace") if (out / "log.txt").exists() else ""
    summary = json.loads((out / "summary.json").read_text()) if (out / "summary.json").exists() else {}
    rows = list(csv.DictReader(open(out / "curves.csv"))) if (out / "curves.csv").exists() else []
    steps = per_step(rows)
    unknowns = re.search(r"(\d+) unknowns on", log)
    penalty = re.search(r"ε_N = ([0-9.eE+-]+)", log)
    failed = summary.get("failed_attempts", [])
    if code == 124 or code == -9 or code == 137:
        status = f"timed out after {TIMEOUT_S / 60:.0f} min"
    elif code != 0:
        status = f"failed (exit {code})"
    else:
        status = summary.get("status", "completed")
    return {"kind": kind, "n": n, "m": n if kind == "hexahedra" else None, "eps_n": eps_n or "auto",
            "penalty": float(penalty.group(1)) if penalty else (eps_n or None),
            "unknowns": int(unknowns.group(1)) if unknowns else None, "status": status, "exit_code": code,
            "steps": len(steps), "load_factor": steps[-1]["load_factor"] if steps else 0.0,
            "newton_total": sum(s["newton"] for s in steps), "newton_max": max((s["newton"] for s in steps), default=0),
            "failed_attempts": len(failed), "failed_newton": sum(f.get("newton_iterations", 0) for f in failed),
            "wall_s": wall, "run_wall_s": summary.get("wall_time"), "peak_mb": rss,
            "peak_mb_summary": summary.get("peak_memory_mb", {}).get("max_rank"),
            "log_tail": log.strip().splitlines()[-6:] if status != "completed" else [],
            "out": str(out), "per_step": steps}


def run(kind, n, eps_n, work, reuse):
    out = work / tag(kind, n, eps_n)
    record = out / "bench_run.json"
    args = [str(CLI), "run", str(SCENE)]
    for s in overrides(kind, n, eps_n, out):
        args += ["--set", s]
    if reuse and record.exists() and json.loads(record.read_text())["args"] == args:
        code, wall, rss = (json.loads(record.read_text())[k] for k in ("code", "wall", "rss"))
    else:
        out.mkdir(parents=True, exist_ok=True)
        for f in ("curves.csv", "summary.json"):
            (out / f).unlink(missing_ok=True)
        code, wall, rss = execute(args, out / "log.txt")
        record.write_text(json.dumps({"args": args, "code": code, "wall": wall, "rss": rss}))
    return collect(kind, n, eps_n, out, code, wall, rss)


def skipped(kind, n, eps_n, why):
    return {"kind": kind, "n": n, "m": n if kind == "hexahedra" else None, "eps_n": eps_n or "auto",
            "status": f"skipped: {why}", "steps": 0, "per_step": []}


def at(r, eps, key):
    """key at squeeze eps: the step's value, or linear between the two steps around it (cut-backs); nan beyond."""
    s = r["per_step"]
    if not s or eps > s[-1]["eps"] + 1e-9:
        return float("nan")
    return float(np.interp(eps, [0.0] + [x["eps"] for x in s], [0.0] + [x[key] for x in s]))


def fmt(v, spec):
    return "—" if v is None or (isinstance(v, float) and not math.isfinite(v)) else format(v, spec)


def done(r):
    return not r["status"].startswith("skipped")


def ladder_table(rows, kind):
    head = ("| n | m | unknowns | wall s (run) | peak MB | steps | Newton (max/step) | "
            + " | ".join(f"F at ε = {e:.2f} (F/F_L)" for e in EPS_TABLE) + " | b at 0.12 | 2a Hertz at 0.12 | status |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        if not done(r):
            lines.append(f"| {r['n']} | {r['m'] or '—'} | — | — | — | — | — | " + " | ".join("—" for _ in EPS_TABLE)
                         + f" | — | — | {r['status']} |")
            continue
        Fs = " | ".join(f"{fmt(at(r, e, 'F'), '.1f')} ({fmt(at(r, e, 'F_over_F_L'), '.3f')})" for e in EPS_TABLE)
        newton = f"{r['newton_total']} ({r['newton_max']})" + (f" + {r['failed_newton']} in {r['failed_attempts']} "
                                                                 f"failed" if r["failed_attempts"] else "")
        lines.append(f"| {r['n']} | {r['m'] or '—'} | {fmt(r['unknowns'], 'd')} | {r['wall_s']:.1f} "
                     f"({fmt(r['run_wall_s'], '.1f')}) | {r['peak_mb']:.0f} | {r['steps']} | {newton} | {Fs} | "
                     f"{fmt(at(r, 0.12, 'b'), '.2f')} | {fmt(at(r, 0.12, 'hertz_2a'), '.2f')} | {r['status']} |")
    lines.append("| Lindley F_L | | | | | | | " + " | ".join(f"{lindley(e):.1f}" for e in EPS_TABLE) + " | | | |")
    return lines


def same_penalty(rows):
    """The same-penalty runs' forces at each step's ε and the tetrahedra's over the hexahedra's."""
    sp = [r for r in rows if r["eps_n"] != "auto" and done(r) and r["per_step"]]
    hexes = [r for r in sp if r["kind"] == "hexahedra"]
    tets = [r for r in sp if r["kind"] == "tetrahedra"]
    if not hexes:
        return None
    h = hexes[-1]
    table = []
    for s in h["per_step"]:
        e = s["eps"]
        row = {"eps": e, "F_hex": s["F"], "F_L": s["F_L"]}
        for t in tets:
            row[f"F_tet{t['n']}"] = at(t, e, "F")
            row[f"tet{t['n']}_over_hex"] = at(t, e, "F") / s["F"]
        table.append(row)
    return {"hex": h["n"], "tets": [t["n"] for t in tets], "eps_n": SAME_PENALTY, "rows": table}


def finest(rows, kind):
    full = [r for r in rows if r["kind"] == kind and r["eps_n"] == "auto" and done(r) and r["per_step"]]
    complete = [r for r in full if r["status"] == "completed"]
    return (complete or full or [None])[-1]


def intervals(steps, test):
    """The runs of consecutive steps that pass test, as (first ε, last ε)."""
    out, start, last = [], None, None
    for s in steps:
        if test(s):
            start, last = (s["eps"] if start is None else start), s["eps"]
        elif start is not None:
            out.append((start, last))
            start = None
    return out + ([(start, last)] if start is not None else [])


def findings(rows, comparison):
    out = []
    for kind in LADDER:
        rs = [r for r in rows if r["kind"] == kind and r["eps_n"] == "auto" and done(r) and r["status"] == "completed"]
        if len(rs) >= 2:
            changes = ", ".join(f"{100 * (at(b, e, 'F') / at(a, e, 'F') - 1):+.1f} %" for e in EPS_TABLE[::3]
                                for a, b in [(rs[-2], rs[-1])])
            seq = " → ".join(f"{at(r, 0.30, 'F'):.1f}" for r in rs)
            out.append(f"{kind.capitalize()}: F at 30 % squeeze over n = {', '.join(str(r['n']) for r in rs)} is "
                       f"{seq} N; from n = {rs[-2]['n']} to {rs[-1]['n']} F changes by {changes} "
                       f"(at ε = 0.12, 0.30).")
    h, t = finest(rows, "hexahedra"), finest(rows, "tetrahedra")
    if h and t:
        diffs = ", ".join(f"{100 * (at(t, e, 'F') / at(h, e, 'F') - 1):+.1f} %" for e in EPS_TABLE)
        out.append(f"The finest tetrahedra (n = {t['n']}, automatic ε_N = {fmt(t['penalty'], '.0f')}) against the "
                   f"finest hexahedra (n = {h['n']}, ε_N = {fmt(h['penalty'], '.0f')}): F_tet/F_hex − 1 = {diffs} "
                   f"at ε = {', '.join(f'{e:.2f}' for e in EPS_TABLE)}.")
    if comparison and comparison["tets"]:
        n = comparison["tets"][-1]
        ratios = [r[f"tet{n}_over_hex"] for r in comparison["rows"] if math.isfinite(r[f"tet{n}_over_hex"])]
        if ratios:
            out.append(f"With the same ε_N = {comparison['eps_n']:g} the tetrahedra n = {n} give "
                       f"{min(ratios):.3f}–{max(ratios):.3f} × the hexahedra n = {comparison['hex']}'s force over "
                       f"the ten steps.")
    for r in (h, t):
        if r:
            span = ", ".join(f"ε = {a:.2f} … {b:.2f}" if b > a else f"ε = {a:.2f}" for a, b in
                             intervals(r["per_step"], lambda s: abs(s["F_over_F_L"] - 1.0) <= 0.10)) or "at no step"
            lo = min(r["per_step"], key=lambda s: s["F_over_F_L"])
            hi = max(r["per_step"], key=lambda s: s["F_over_F_L"])
            out.append(f"Lindley within ±10 % ({r['kind']} n = {r['n']}): {span}; over all steps F/F_L runs from "
                       f"{lo['F_over_F_L']:.3f} (ε = {lo['eps']:.2f}) to {hi['F_over_F_L']:.3f} "
                       f"(ε = {hi['eps']:.2f}).")
    return out


def report(rows, comparison, quick):
    lines = ["# O-ring between two rigid plates: mesh ladder against Lindley and Hertz", "",
             "`bench/oring.py` (regenerate: `.venv/bin/python bench/oring.py`; `--quick` for n = 4, 8 only). "
             f"`scenes/oring_plates.toml`: D = {D:g}, d = {CORD:g}, neo-Hookean μ = {MU:g}, K = 1000, mixed "
             "Q2–Q1 (hexahedra, O-grid, m = n layers along the quarter circle) or P2–P1 (tetrahedra, gmsh "
             "Delaunay at size d/n), second-order curved cells, frictionless plate 0.6 down in 10 steps "
             "(ε = 2·0.6 λ/d, 30 % at λ = 1). F: whole-ring force |plate_fz| (× 4); F_L = π D E d (1.25 ε^1.5 + "
             "50 ε^6), E = 3μ; b = plate_area/(π D), the loaded nodal area (resolved to one node spacing); "
             "2a: Hertz's line contact, a = √(4 F' R_c/(π E*)), F' = F/(π D), R_c = d/2, E* = 4μ. Wall time: "
             "the CLI process (in brackets the run's own, summary.json); Newton: total over the converged steps "
             "(largest per step). One thread, one run at a time, on a 2-core machine shared with other jobs. "
             f"Rungs are skipped when the previous rung of the kind took more than {SKIP_AFTER_S // 60} min; "
             f"each run is limited to {TIMEOUT_S // 60} min.", ""]
    for kind in LADDER:
        rs = [r for r in rows if r["kind"] == kind and r["eps_n"] == "auto"]
        if rs:
            lines += [f"## {kind.capitalize()} ({'Q2–Q1' if kind == 'hexahedra' else 'P2–P1'}), automatic penalty",
                      ""] + ladder_table(rs, kind) + [""]
            pens = ", ".join(f"n = {r['n']}: {fmt(r.get('penalty'), '.0f')}" for r in rs if done(r))
            lines += [f"Automatic penalty ε_N: {pens}.", ""]
    sp = [r for r in rows if r["eps_n"] != "auto"]
    if sp:
        lines += [f"## Same penalty ε_N = {SAME_PENALTY:g}: tetrahedra against hexahedra", ""]
        lines += ladder_table(sp, None)[:-1] + [""]
        if comparison:
            tets = comparison["tets"]
            head = (f"| ε | F hex n = {comparison['hex']} | " + " | ".join(f"F tet n = {n}" for n in tets)
                    + " | " + " | ".join(f"tet {n} / hex" for n in tets) + " | F_L |")
            lines += [head, "|" + "---|" * (head.count("|") - 1)]
            for r in comparison["rows"]:
                lines.append(f"| {r['eps']:.2f} | {r['F_hex']:.2f} | "
                             + " | ".join(fmt(r[f'F_tet{n}'], '.2f') for n in tets) + " | "
                             + " | ".join(fmt(r[f'tet{n}_over_hex'], '.4f') for n in tets) + f" | {r['F_L']:.1f} |")
            lines.append("")
    failed = [r for r in rows if done(r) and r["status"] != "completed"]
    for r in failed:
        lines += [f"{r['kind']} n = {r['n']} (ε_N {r['eps_n']}): {r['status']} after {r['steps']} steps "
                  f"(λ = {r['load_factor']:.3g}); the log's last lines:", "", "```"] + r["log_tail"] + ["```", ""]
    lines += ["## Findings", ""] + [" ".join(findings(rows, comparison))] + [""]
    return "\n".join(lines)


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(17, 5))
    eps = np.linspace(0.0, squeeze(1.0), 200)
    for r in rows:
        if not done(r) or not r["per_step"]:
            continue
        e = [s["eps"] for s in r["per_step"]]
        style = ("o-" if r["kind"] == "hexahedra" else "s--") if r["eps_n"] == "auto" else ("^:" if r["kind"] ==
                                                                                              "hexahedra" else "v:")
        label = f"{'hex' if r['kind'] == 'hexahedra' else 'tet'} n = {r['n']}" + (
            f", ε_N = {r['eps_n']:g}" if r["eps_n"] != "auto" else "")
        axes[0].plot(e, [s["F_over_F_L"] for s in r["per_step"]], style, ms=4, label=label)
        axes[1].plot(e, [s["F"] for s in r["per_step"]], style, ms=4, label=label)
        if r["eps_n"] == "auto":
            axes[2].plot(e, [s["b"] for s in r["per_step"]], style, ms=4, label=label)
    axes[0].axhspan(0.9, 1.1, color="0.9", label="Lindley ± 10 %")
    axes[0].set_ylabel("F / F_Lindley")
    axes[1].plot(eps, [lindley(x) for x in eps], "k-", lw=2, label="Lindley")
    axes[1].set_ylabel("whole-ring force F, N")
    fin = [r for r in rows if r["eps_n"] == "auto" and done(r) and r["per_step"]]
    if fin:
        ref = max(fin, key=lambda r: (r["kind"] == "hexahedra", r["n"]))
        axes[2].plot([s["eps"] for s in ref["per_step"]], [s["hertz_2a"] for s in ref["per_step"]], "k-", lw=2,
                     label=f"Hertz 2a (F of hex n = {ref['n']})" if ref["kind"] == "hexahedra" else "Hertz 2a")
    axes[2].set_ylabel("contact width b = A/(πD), mm")
    for ax, title in zip(axes, ["force over Lindley's formula", "force", "contact width (nodal area)"]):
        ax.set_xlabel("squeeze ε")
        ax.set_title(title)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("O-ring between plates (D = 24, d = 4, μ = 1, K/μ = 10³), mesh ladder")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="n = 4, 8 of both kinds, no same-penalty runs")
    p.add_argument("--kinds", nargs="+", choices=list(LADDER), default=list(LADDER))
    p.add_argument("--no-same-penalty", action="store_true", help="the ladder only")
    p.add_argument("--reuse", action="store_true", help="take a run's results from --work if it was made with "
                                                        "the same arguments (regenerate the report)")
    p.add_argument("--work", type=Path, default=WORK, help="the runs' folders (default /tmp/bench_oring)")
    p.add_argument("--out", type=Path, default=OUT)
    p.add_argument("--from-json", type=Path, help="rewrite the report and plot from a results JSON, running "
                                                   "nothing")
    p.add_argument("--merge", type=Path, help="keep the runs of the kinds not run now from this results JSON")
    args = p.parse_args()
    if args.from_json:
        data = json.loads(args.from_json.read_text())
        write(args, data["runs"], data["constants"], args.from_json.stem.endswith("_quick"))
        return
    ladder = {k: v for k, v in (QUICK if args.quick else LADDER).items() if k in args.kinds}
    rows = []
    if args.merge:
        rows = [r for r in json.loads(args.merge.read_text())["runs"] if r["kind"] not in args.kinds]
    ladder_wall = {}
    for kind, sizes in ladder.items():
        slow = None
        for n in sizes:
            if slow is not None:
                rows.append(skipped(kind, n, None, f"n = {slow['n']} took {slow['wall_s'] / 60:.1f} min "
                                                   f"(> {SKIP_AFTER_S // 60})"))
            else:
                rows.append(run(kind, n, None, args.work, args.reuse))
                ladder_wall[kind, n] = rows[-1]["wall_s"]
                if rows[-1]["wall_s"] > SKIP_AFTER_S:
                    slow = rows[-1]
            print({k: v for k, v in rows[-1].items() if k not in ("per_step", "log_tail")}, flush=True)
    if not (args.quick or args.no_same_penalty):
        for kind, n in SAME_RUNS:
            if kind not in args.kinds:
                continue
            if (kind, n) not in ladder_wall:
                rows.append(skipped(kind, n, SAME_PENALTY, f"its ladder run (n = {n}) was skipped"))
            elif ladder_wall[kind, n] > SKIP_AFTER_S:
                rows.append(skipped(kind, n, SAME_PENALTY, f"its ladder run took {ladder_wall[kind, n] / 60:.1f} min "
                                                           f"(> {SKIP_AFTER_S // 60})"))
            else:
                rows.append(run(kind, n, SAME_PENALTY, args.work, args.reuse))
            print({k: v for k, v in rows[-1].items() if k not in ("per_step", "log_tail")}, flush=True)
    constants = {"D": D, "d": CORD, "mu": MU, "E": E, "E_star": E_STAR, "travel": TRAVEL,
                 "lindley": "F_L = pi D E d (1.25 eps^1.5 + 50 eps^6)",
                 "hertz": "2a, a = sqrt(4 F' R_c/(pi E*)), F' = F/(pi D), R_c = d/2",
                 "width": "b = plate_area/(pi D)", "skip_after_s": SKIP_AFTER_S, "timeout_s": TIMEOUT_S}
    write(args, rows, constants, args.quick)


def write(args, rows, constants, quick):
    """The JSON, the Markdown report and the plot of a set of runs."""
    comparison = same_penalty(rows)
    args.out.mkdir(parents=True, exist_ok=True)
    suffix = "_quick" if quick else ""
    (args.out / f"oring{suffix}.json").write_text(json.dumps(
        {"constants": constants, "runs": rows, "same_penalty": comparison,
         "findings": findings(rows, comparison)}, indent=1, ensure_ascii=False))
    text = report(rows, comparison, quick)
    (args.out / f"oring{suffix}.md").write_text(text)
    plot(rows, args.out / f"oring{suffix}.png")
    print(text)


if __name__ == "__main__":
    main()
