"""What halving a Newton correction that would invert an element
(``solver.damp_inversion``, docs/performance.md §2) does to the punch's path:
each run with and without it, one after the other, at load steps large
enough for the first correction of a step to shear the cells at the punch
edge through themselves.

    .venv/bin/python bench/inversion_damping.py [--meshes 32x8] [--steps 0.1:0.25 0.25:0.5 0.5:1 1:1]
                                                [--cases punch punch_mu0.3_0] [--add]

``--steps initial:max`` are the scene's steps.initial and steps.max. Each
run is ``hypercontact run CASE --set …`` in a subprocess with one thread;
the figures come from its summary.json: converged steps, Newton iterations
(converged steps + failed attempts), failed attempts, damped corrections,
the punch force at full indentation and the wall time. Writes
``bench/results/inversion_damping.{md,json}``. A benchmark reports; it
asserts nothing. On the sharp-edged punch the force depends on the path
(README, docs/studies.md): runs that take different steps may end on
different solutions.
"""
import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "bench" / "results"
ENV = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}


def run(case, n, m, initial, largest, damp, work):
    folder = work / f"{case}_{n}x{m}_{initial:g}_{largest:g}_{'damped' if damp else 'plain'}"
    sets = [f"mesh.n={n}", f"mesh.m={m}", f"steps.initial={initial}", f"steps.max={largest}",
            f"solver.damp_inversion={'true' if damp else 'false'}", "output.xdmf=false"]
    command = [str(Path(sys.executable).parent / "hypercontact"), "run", case, "--out", str(folder)]
    for s in sets:
        command += ["--set", s]
    done = subprocess.run(command, env=ENV, capture_output=True, text=True)
    summary = json.loads((folder / "summary.json").read_text())
    failed = summary["failed_attempts"]
    steps = summary["steps"]
    return {"case": case, "mesh": f"{n}x{n}x{m}", "steps_setting": f"{initial:g} / {largest:g}", "damp": damp,
            "status": summary["status"], "returncode": done.returncode, "steps": len(steps),
            "newton": sum(summary["newton_iterations"]) + sum(f.get("attempt_newton_iterations",
                                                                    f["newton_iterations"]) for f in failed),
            "failed_attempts": len(failed),
            "failed_reasons": [[s["reason"] for s in f.get("solves", [])] for f in failed],
            "damped_corrections": summary["linear_solver"].get("damped_corrections"),
            "load_factor": steps[-1]["load_factor"] if steps else 0.0,
            "force": -steps[-1]["punch_fz"] if steps else None, "wall_s": summary["wall_time"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--meshes", nargs="+", default=["32x8"])
    ap.add_argument("--steps", nargs="+", default=["0.1:0.25", "0.25:0.5", "0.5:1", "1:1"])
    ap.add_argument("--cases", nargs="+", default=["punch", "punch_mu0.3_0"])
    ap.add_argument("--work", default="/tmp/hypercontact_inversion_damping")
    ap.add_argument("--add", action="store_true", help="add the rows to those already in the results file")
    args = ap.parse_args()
    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    rows = []
    for mesh in args.meshes:
        n, m = (int(v) for v in mesh.split("x"))
        for case in args.cases:
            for setting in args.steps:
                initial, largest = (float(v) for v in setting.split(":"))
                for damp in (False, True):
                    row = run(case, n, m, initial, largest, damp, work)
                    rows.append(row)
                    print(json.dumps(row), flush=True)
    if args.add:
        key = lambda r: (r["case"], r["mesh"], r["steps_setting"], r["damp"])  # noqa: E731
        new = {key(r) for r in rows}
        old = json.loads((OUT / "inversion_damping.json").read_text())
        rows = [r for r in old if key(r) not in new] + rows
    write(rows)


def write(rows):
    (OUT / "inversion_damping.json").write_text(json.dumps(rows, indent=1))
    lines = [
        "# Halving Newton corrections that would invert an element (bench/inversion_damping.py)",
        "",
        "The punch pressed 2 mm, each row's runs one after the other, one process, direct solver. "
        "steps: the scene's steps.initial / steps.max; Newton its: in converged steps + in failed attempts "
        "(each failed attempt's reasons: its full-step solve, then its fallback); damped: corrections halved "
        "so that no element inverts. The force is the whole plate's at the last converged step.",
        "",
        "| case | mesh | steps | damp_inversion | status | load steps | Newton its | failed attempts (reasons) "
        "| damped | punch force (N) | wall (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        reasons = "; ".join(" → ".join(f) for f in r["failed_reasons"]) or "—"
        force = f"{r['force']:.2f}" if r["force"] is not None else "—"
        status = r["status"] if r["load_factor"] >= 1.0 - 1e-12 else f"{r['status']} at λ = {r['load_factor']:.3f}"
        lines.append(f"| {r['case']} | {r['mesh']} | {r['steps_setting']} | {str(r['damp']).lower()} | {status} "
                     f"| {r['steps']} | {r['newton']} | {r['failed_attempts']} ({reasons}) "
                     f"| {r['damped_corrections']} | {force} | {r['wall_s']:.1f} |")
    (OUT / "inversion_damping.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
