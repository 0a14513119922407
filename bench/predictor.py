"""What the secant predictor (steps.predictor) saves: the paper's four
friction cases of the punch with each step started from the last converged
state ("none", the default) and from the secant extrapolation of the last
two ("secant"), one after the other on one machine.

    .venv/bin/python bench/predictor.py [--meshes 16x4 32x8]

Writes ``bench/results/predictor.md`` and ``predictor.json``: per case and
mesh, the punch force at full indentation, load steps, Newton iterations
(converged steps and failed attempts), cut-backs and wall time with each
predictor, and their ratios. The scenes' own adaptive steps: with fewer
iterations per step the steps grow sooner, so the two paths need not take
the same steps (friction is path dependent: bench/load_steps.py measures how
much the force moves with the steps). A benchmark reports, it asserts
nothing.
"""
import argparse
import json
from pathlib import Path

from punch_friction import CASES, ROOT, folder, run

OUT = ROOT / "bench" / "results"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--meshes", nargs="+", default=["16x4", "32x8"])
    ap.add_argument("--cases", nargs="+", default=list(CASES))
    ap.add_argument("--work", default="/tmp/hypercontact_predictor", help="the runs' results folders")
    args = ap.parse_args()
    work = Path(args.work)
    rows = []
    for mesh in args.meshes:
        n, m = (int(x) for x in mesh.split("x"))
        for case in args.cases:
            for predictor in ("none", "secant"):
                extra = (f"steps.predictor={predictor}", "output.xdmf=false")
                row, _, _ = run(case, n, m, work, extra)
                summary = json.loads((work / folder(case, f"{n}x{n}x{m}", extra) / "summary.json").read_text())
                failed = summary.get("failed_attempts", [])
                row.update(predictor=predictor, cutbacks=len(failed),
                           failed_newton=sum(f["newton_iterations"] for f in failed))
                rows.append(row)
                print(f"{case} {row['mesh']} {predictor}: {row['status']}, force {row['punch_force']:.3f} N, "
                      f"{row['steps']} steps, {row['newton_total']} + {row['failed_newton']} Newton its, "
                      f"{row['wall_time']:.1f} s", flush=True)
    write(rows)


def write(rows):
    for r in rows:
        r.pop("curve", None)
        r.pop("orders", None)
    (OUT / "predictor.json").write_text(json.dumps(rows, indent=1))
    lines = [
        "# The secant predictor (bench/predictor.py)",
        "",
        "The punch's four friction cases, (μ1, μ2), with the scenes' own adaptive load steps; each step "
        "started from the last converged state (none) or from the secant extrapolation of the last two "
        "(secant: `steps.predictor = \"secant\"`; the default is none). Newton its: in the converged steps "
        "+ in failed attempts. One process, direct solver, the two runs of a row one after the other "
        "(compare times within a row).",
        "",
        "| (μ1, μ2) | quarter mesh | punch force none / secant (N) | steps | Newton its none | "
        "Newton its secant | ratio | wall none (s) | wall secant (s) | ratio |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for a in rows:
        if a["predictor"] != "none":
            continue
        b = next((r for r in rows if r["predictor"] == "secant" and r["case"] == a["case"] and
                  r["mesh"] == a["mesh"]), None)
        if b is None:
            continue
        na, nb = a["newton_total"] + a["failed_newton"], b["newton_total"] + b["failed_newton"]
        lines.append(
            f"| ({a['mu1']:g}, {a['mu2']:g}) | {a['mesh']} | {a['punch_force']:.2f} / {b['punch_force']:.2f} | "
            f"{a['steps']} / {b['steps']} | {a['newton_total']} + {a['failed_newton']} | "
            f"{b['newton_total']} + {b['failed_newton']} | {nb / na:.2f} | {a['wall_time']:.1f} | "
            f"{b['wall_time']:.1f} | {b['wall_time'] / a['wall_time']:.2f} |")
    (OUT / "predictor.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
