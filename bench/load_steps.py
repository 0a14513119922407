"""How the frictional punch's force depends on the load step (friction is
path dependent: the return mapping integrates the slip over each step, so a
result is converged only when it no longer moves with Δλ, as with the mesh).

    .venv/bin/python bench/load_steps.py [--meshes 16x4 32x8] [--cases punch_mu0.3_0 punch_mu0_1]
                                         [--dlams 0.1 0.05 0.025 0.0125] [--name load_steps]

Runs each case and mesh of scenes/punch_*.toml with fixed load steps Δλ
(``steps.initial = steps.max = Δλ``) and with the scene's own adaptive
steps, and writes
``bench/results/load_steps.md`` and ``load_steps.json`` (``--name``: another name): the punch force at
full indentation, its change against the smallest Δλ, load steps, Newton
iterations and wall time. With the finest Δλ's result as the reference it
also says which of the runs is within 1 %. A benchmark reports, it asserts
nothing.
"""
import argparse
import json
from pathlib import Path

from punch_friction import ROOT, run

OUT = ROOT / "bench" / "results"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--meshes", nargs="+", default=["16x4", "32x8"])
    ap.add_argument("--cases", nargs="+", default=["punch_mu0.3_0", "punch_mu0_1"])
    ap.add_argument("--dlams", nargs="+", type=float, default=[0.1, 0.05, 0.025, 0.0125])
    ap.add_argument("--work", default="/tmp/hypercontact_load_steps", help="the runs' results folders")
    ap.add_argument("--reuse", action="store_true", help="take finished runs from --work as they are")
    ap.add_argument("--name", default="load_steps", help="results file name in bench/results (without suffix)")
    args = ap.parse_args()
    work = Path(args.work)
    rows = []
    for mesh in args.meshes:
        n, m = (int(x) for x in mesh.split("x"))
        for case in args.cases:
            variants = [("adaptive", ())] + [
                (f"{d:g}", (f"steps.initial={d}", f"steps.max={d}")) for d in args.dlams]
            for label, extra in variants:
                row, _, _ = run(case, n, m, work, (*extra, "output.xdmf=false"), reuse=args.reuse)
                row["dlam"] = label
                rows.append(row)
                print(f"{case} {row['mesh']} Δλ {label}: {row['status']}, force {row['punch_force']:.3f} N, "
                      f"{row['steps']} steps, {row['newton_total']} Newton its, {row['wall_time']:.1f} s", flush=True)
    write(rows, args)


def write(rows, args):
    for r in rows:
        r.pop("curve", None)
        r.pop("orders", None)
    (OUT / f"{args.name}.json").write_text(json.dumps(rows, indent=1))
    finest = f"{min(args.dlams):g}"
    lines = [
        "# The frictional punch against the load step (bench/load_steps.py)",
        "",
        "Punch force (whole plate) at full indentation 2 mm; fixed load steps Δλ "
        "(`steps.initial = steps.max = Δλ`) and the scene's own adaptive steps "
        "(\"adaptive\": from 0.1, growing up to `steps.max`). The change is against "
        f"the smallest Δλ ({finest}) on the same mesh and case. One process, direct solver, on a "
        "machine shared with other jobs: compare times within the table. A force that keeps moving "
        "as Δλ halves has not converged in Δλ; on the sharp punch that is the edge's choice of "
        "solution, not the friction's time integration (docs/studies.md).",
        "",
        "| case | quarter mesh | Δλ | status | punch force (N) | change | steps | Newton its | wall (s) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        ref = next((q for q in rows if q["case"] == r["case"] and q["mesh"] == r["mesh"] and q["dlam"] == finest),
                   None)
        change = (f"{100 * (r['punch_force'] / ref['punch_force'] - 1):+.2f} %"
                  if ref and r["status"] == "completed" and ref["status"] == "completed" else "")
        lines.append(f"| {r['case']} | {r['mesh']} | {r['dlam']} | {r['status']} | {r['punch_force']:.2f} | "
                     f"{change} | {r['steps']} | {r['newton_total']} | {r['wall_time']:.0f} |")
    (OUT / f"{args.name}.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
