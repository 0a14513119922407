"""Benchmark and mesh-convergence study of the frictionless rigid punch.

    .venv/bin/python bench/punch.py [--meshes 16x4 32x8 64x16] [--out bench/results/punch]

For each quarter mesh N×N×M: punch force (whole plate) and plate-edge and
corner uplift at full indentation, number of unknowns, load steps, Newton
iterations, wall time and its split (volume assembly / contact / linear
solve / other). Writes a Markdown table and a JSON file; a benchmark
reports, it asserts nothing.
"""
import argparse
import json
import time
from pathlib import Path

from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

ROOT = Path(__file__).resolve().parents[1]


def run(n, m, out, extra):
    sc = scene.load(ROOT / "scenes" / "punch.toml",
                    [f"mesh.n={n}", f"mesh.m={m}", f"output.dir={out}/{n}x{n}x{m}", *extra])
    t0 = time.perf_counter()
    sim = Simulation(sc, MPI.COMM_WORLD, log=lambda *a: None)
    writer = sim.run()
    wall = time.perf_counter() - t0
    summary = writer.write_summary(sim.timers)
    last = writer.steps[-1]
    return {
        "mesh": f"{n}x{n}x{m}", "unknowns": 3 * sim.V.dofmap.index_map.size_global,
        "punch_force": -last["punch_fz"], "edge_uplift": last["edge_uz"], "corner_uplift": last["corner_uz"],
        "steps": len(writer.steps), "newton_total": sum(summary["newton_iterations"]),
        "newton_per_step": summary["newton_iterations"], "wall_time": wall,
        "time_split": summary["time_split"],
    }


def main():
    import logging

    logging.getLogger().setLevel(logging.WARNING)
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--meshes", nargs="+", default=["16x4", "32x8"], help="N x M of the quarter mesh")
    p.add_argument("--out", default=str(ROOT / "bench" / "results" / "punch"))
    p.add_argument("--set", dest="extra", action="append", default=[], help="scene override")
    args = p.parse_args()
    rows = []
    for mesh in args.meshes:
        n, m = (int(v) for v in mesh.split("x"))
        rows.append(run(n, m, args.out, args.extra))
        if MPI.COMM_WORLD.rank == 0:
            r = rows[-1]
            print(f"{r['mesh']:>9}: force {r['punch_force']:.4f} N, edge uplift {r['edge_uplift']:.5f} mm, "
                  f"corner {r['corner_uplift']:.5f} mm, {r['steps']} steps, {r['newton_total']} Newton its, "
                  f"{r['wall_time']:.1f} s  " + ", ".join(f"{k} {v:.1f}" for k, v in r["time_split"].items()),
                  flush=True)
    if MPI.COMM_WORLD.rank == 0:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "punch_bench.json").write_text(json.dumps(rows, indent=1))
        phases = ["volume assembly", "contact", "linear solve", "setup", "other"]
        lines = ["| quarter mesh | unknowns | punch force (N) | edge uplift (mm) | corner uplift (mm) | steps | Newton its | wall (s) | "
                 + " | ".join(phases) + " |", "|" + "---|" * (8 + len(phases))]
        for r in rows:
            split = r["time_split"]
            lines.append(f"| {r['mesh']} | {r['unknowns']} | {r['punch_force']:.4f} | {r['edge_uplift']:.5f} | "
                         f"{r['corner_uplift']:.5f} | {r['steps']} | {r['newton_total']} | {r['wall_time']:.1f} | "
                         + " | ".join(f"{split.get(k, 0.0):.1f}" for k in phases) + " |")
        (out / "punch_bench.md").write_text("\n".join(lines) + "\n")
        print("\n".join(lines))


if __name__ == "__main__":
    main()
