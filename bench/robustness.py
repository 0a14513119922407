"""The same answer on every machine: the built-in scenes under several
OpenBLAS kernels, with the solver settings of today (default) and as they
were before the contact law was smoothed ("before": smoothing = 0 and the
line search the scene used to name).

    /usr/bin/python3 bench/robustness.py [--quick] [--out bench/results]

Each case runs the CLI in a subprocess with OPENBLAS_CORETYPE set (the kernel
is chosen when OpenBLAS loads) and one thread. Writes robustness.json and
robustness.md: per scene and kernel the status, load steps, cut-backs, Newton
iterations per step (mean, max), the final force and the wall time, and per
scene the largest relative spread of the force over the kernels that finished.
A benchmark reports; tests/behaviour/test_robustness.py asserts.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PY = ROOT / ".venv" / "bin" / "python"
KERNELS = ["Sandybridge", "Haswell", "SkylakeX"]
PUNCH = ["punch_mu0_0", "punch_mu0.3_0", "punch_mu1_0", "punch_mu0_1", "punch_mu0.3_1"]
#: the line search each punch scene named before (main at ff7346d)
BEFORE_LINESEARCH = {"punch_mu0.3_1": "l2"}
#: scene and extra --set overrides
CASES = [(name, []) for name in PUNCH] + [
    ("punch_mu0_1", ["contact.0.eps_t=0", "contact.1.eps_t=0"]),  # the default ε_T = ε_N
    ("chatter", []),
    ("hertz", []),
    ("sphere_plane", []),
    ("sphere_plane", ["contact.0.mu=0.3"]),
    ("blocks_incompressible", []),
]


def kernels_here():
    flags = Path("/proc/cpuinfo").read_text()
    need = {"Sandybridge": " avx ", "Haswell": " avx2 ", "SkylakeX": " avx512f "}
    return [k for k in KERNELS if need[k] in flags.replace("\n", " ")]


def force_column(rows):
    """The force component of largest magnitude at the last step (the contact's push)."""
    columns = [c for c in rows[0] if c[-3:] in ("_fx", "_fy", "_fz")]
    if not columns:
        return None, float("nan")
    column = max(columns, key=lambda c: (round(abs(float(rows[-1][c])), 6), c))  # ties: the same column
    return column, abs(float(rows[-1][column]))


def run(scene, overrides, kernel, out, before):
    sets = list(overrides)
    if before:
        sets += [f"contact.{i}.smoothing=0" for i in range(count_contacts(scene))]
        sets += [f'solver.linesearch="{BEFORE_LINESEARCH.get(scene, "basic")}"'] if scene in PUNCH else []
    args = [str(PY), "-m", "hypercontact.cli", "run", scene, "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    env = {**os.environ, "OPENBLAS_CORETYPE": kernel, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    t0 = time.perf_counter()
    done = subprocess.run(args, env=env, capture_output=True, text=True, timeout=3600, cwd=ROOT)
    wall = time.perf_counter() - t0
    rows = list(csv.DictReader(open(out / "curves.csv"))) if (out / "curves.csv").exists() else []
    its = [int(r["newton_iterations"]) for r in rows]
    column, force = force_column(rows) if rows else (None, float("nan"))
    return {"scene": scene, "overrides": overrides, "kernel": kernel, "before": before,
            "status": "completed" if done.returncode == 0 else f"exit {done.returncode}",
            "steps": len(rows), "cutbacks": done.stdout.count("cut back to"),
            "newton_mean": sum(its) / len(its) if its else 0.0, "newton_max": max(its) if its else 0,
            "force_column": column, "force": force, "wall_s": wall,
            "limit_lambda": max((float(r["load_factor"]) for r in rows), default=float("nan")),
            "last_line": (done.stdout.strip().splitlines() or [""])[-1][:160]}


def count_contacts(scene):
    import tomllib

    path = ROOT / "scenes" / f"{scene}.toml"
    return len(tomllib.loads(path.read_text()).get("contact", []))


def spread(values):
    """(max − min) / |first| of a list, NaN for fewer than two values."""
    return (max(values) - min(values)) / abs(values[0]) if len(values) > 1 and values[0] else float("nan")


def report(records, out):
    lines = ["# The same answer on every machine: scenes under OpenBLAS kernels", "",
             "Produced by `bench/robustness.py`; one thread per run; wall times on a shared 2-core machine.",
             "*before*: smoothing = 0 (the paper's sharp ⟨−g⟩) and the line search the scene named before",
             "(main at ff7346d) for the punch cases; the other scenes' *before* runs take today's solver with the",
             "sharp law. *after*: today's defaults. The force is the largest force component at the last step; for",
             "the arc-length scenes (sphere_plane) the last step's position depends on the step sizes, which follow",
             "the Newton iteration counts, so compare their limit load factors (`limit_lambda`) and the steps before",
             "the first difference in iterations.", "",
             "| scene | overrides | law | kernel | status | steps | cut-backs | Newton mean / max | |force| (N) | wall s |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in records:
        lines.append(f"| {r['scene']} | {' '.join(r['overrides'])} | {'before' if r['before'] else 'after'} | "
                     f"{r['kernel']} | {r['status']} | {r['steps']} | {r['cutbacks']} | "
                     f"{r['newton_mean']:.1f} / {r['newton_max']} | {r['force']:.10g} | {r['wall_s']:.1f} |")
    lines += ["", "Largest relative spread over the kernels (completed runs only) of the final force and of the",
              "largest load factor reached:", ""]
    groups = {}
    for r in records:
        groups.setdefault((r["scene"], " ".join(r["overrides"]), r["before"]), []).append(r)
    for (scene, ov, before), rs in groups.items():
        done = [r for r in rs if r["status"] == "completed"]
        lines.append(f"- {scene} {ov} ({'before' if before else 'after'}): {len(done)}/{len(rs)} completed, "
                     f"force spread {spread([r['force'] for r in done]):.2e}, "
                     f"largest-λ spread {spread([r.get('limit_lambda', float('nan')) for r in done]):.2e}")
    (out / "robustness.md").write_text("\n".join(lines) + "\n")
    (out / "robustness.json").write_text(json.dumps(records, indent=1))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(ROOT / "bench" / "results"))
    ap.add_argument("--quick", action="store_true", help="the punch cases only")
    ap.add_argument("--no-before", action="store_true", help="today's defaults only")
    ap.add_argument("--only", nargs="*", default=None, help="these scenes only (appended to robustness.json)")
    ap.add_argument("--kernels", nargs="*", default=None, help="these OpenBLAS kernels only")
    ap.add_argument("--report", action="store_true", help="only rewrite robustness.md from robustness.json")
    args = ap.parse_args()
    out = Path(args.out)
    if args.report:
        records = json.loads((out / "robustness.json").read_text())
        for r in records:
            r["force"] = abs(r["force"])
        return report(records, out)
    work = out / "robustness_runs"
    records = []
    cases = CASES[:len(PUNCH)] if args.quick else CASES
    if args.only is not None:
        records = json.loads((out / "robustness.json").read_text()) if (out / "robustness.json").exists() else []
        cases = [c for c in cases if c[0] in args.only]
    for scene, overrides in cases:
        for before in ((False,) if args.no_before or overrides else (True, False)):
            for kernel in args.kernels or kernels_here():
                tag = f"{scene}_{'_'.join(overrides)}_{'before' if before else 'after'}_{kernel}".replace("=", "")
                records.append(run(scene, overrides, kernel, work / tag, before))
                r = records[-1]
                print(f"{scene:22s} {' '.join(overrides):30s} {'before' if before else 'after ':6s} {kernel:11s} "
                      f"{r['status']:10s} steps {r['steps']:3d} cuts {r['cutbacks']:2d} "
                      f"Newton {r['newton_mean']:.1f}/{r['newton_max']} F {r['force']:.10g} {r['wall_s']:.0f} s",
                      flush=True)
                report(records, out)


if __name__ == "__main__":
    sys.exit(main())
