"""Where the iterative solver overtakes the direct one: the paper's punch over
its whole 2 mm path at growing size, each size run with MUMPS (LDLᵀ where the
tangent is symmetric, frictionless; LU with friction) and right after with
GMRES + smoothed-aggregation AMG (with the inexact Newton tolerance), one
process. Per run: Newton iterations, wall time, its split (volume assembly,
linear solve), the punch force; per size the iterative run's wall time over
the direct one's. `solver.linear = "auto"` takes the direct solver up to
`solver.direct_max_unknowns`: this is the measurement that number comes from.

    .venv/bin/python bench/crossover.py --sizes 8 12 16 20 24 32 40 [--mu 0.3] --out bench/results/crossover
    .venv/bin/python bench/crossover.py --report --out bench/results/crossover

Sizes n are quarter meshes n × n × n/4. Appends one JSON line per run to
OUT/crossover.jsonl; --report writes OUT/crossover.md. A benchmark reports; it
asserts nothing. Run it alone on the machine: the ratios of one size compare
two runs made one after the other.
"""
import argparse
import json
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def run(n, mu, linear, out):
    from mpi4py import MPI

    from hypercontact import _dolfinx as dfx
    from hypercontact import scene
    from hypercontact.simulation import Simulation

    comm = MPI.COMM_WORLD
    name = "punch.toml" if mu == 0 else "punch_mu0.3_0.toml"
    folder = out / f"n{n}_mu{mu:g}_{linear}"
    sc = scene.load(ROOT / "scenes" / name, [f"mesh.n={n}", f"mesh.m={max(n // 4, 1)}", f"solver.linear={linear}",
                                             "output.xdmf=false", f"output.dir={folder}"])
    t0 = time.perf_counter()
    sim = Simulation(sc, comm, log=lambda *a, **k: None)
    writer = sim.run()
    wall = time.perf_counter() - t0
    summary = writer.write_summary(sim.timers)
    row = {"n": n, "mu": mu, "linear": linear, "unknowns": dfx.num_global_dofs(sim.V), "steps": len(writer.steps),
           "newton": sum(summary["newton_iterations"]), "failed_attempts": len(summary["failed_attempts"]),
           "krylov": sum(k or 0 for k in summary["linear_iterations"]), "wall_s": wall, "time_split": summary["time_split"],
           "force": -writer.steps[-1]["punch_fz"]}
    if comm.rank == 0:
        with open(out / "crossover.jsonl", "a") as f:
            f.write(json.dumps(row) + "\n")
        print(json.dumps(row), flush=True)


def report(out):
    rows = [json.loads(line) for line in (out / "crossover.jsonl").read_text().splitlines() if line.strip()]
    by_key = {(r["n"], r["mu"], r["linear"]): r for r in rows}  # the last run of each
    text = ["# Direct against iterative: the crossover", "",
            "The punch over its whole 2 mm path, one process; each size with MUMPS (LDLᵀ frictionless, "
            "LU with friction) and right after with GMRES + GAMG. Seconds of the whole path; "
            "ratio: the iterative run's wall time over the direct one's (below 1: the iterative "
            "solver is faster). The first size of each process carries the process's start-up "
            "(forms loaded from the cache, PETSc initialised), in its direct run most: compare from "
            "the second size on.", "",
            "| μ1 | quarter mesh | unknowns | solver | steps | Newton its | Krylov its | wall (s) | "
            "volume assembly | linear solve | punch force (N) | iterative / direct |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (n, mu, linear) in sorted(by_key, key=lambda k: (k[1], k[0], k[2])):
        r = by_key[(n, mu, linear)]
        d = by_key.get((n, mu, "direct"))
        ratio = f"{r['wall_s'] / d['wall_s']:.2f}" if linear == "iterative" and d else ""
        s = r["time_split"]
        text.append(f"| {mu:g} | {n} × {n} × {max(n // 4, 1)} | {r['unknowns']:,} | {linear} | {r['steps']} | "
                    f"{r['newton']} | {r['krylov'] if linear == 'iterative' else '—'} | {r['wall_s']:.1f} | "
                    f"{s['volume assembly']:.1f} | {s['linear solve']:.1f} | {r['force']:.4f} | {ratio} |")
    (out / "crossover.md").write_text("\n".join(text) + "\n")
    print("\n".join(text))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", type=int, nargs="+", default=[8, 12, 16, 20, 24, 32, 40])
    p.add_argument("--mu", type=float, default=0.0, help="0 (punch.toml) or 0.3 (punch_mu0.3_0.toml)")
    p.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "crossover")
    p.add_argument("--report", action="store_true")
    args = p.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    if args.report:
        return report(args.out)
    import logging

    logging.getLogger().setLevel(logging.WARNING)
    for n in args.sizes:
        for linear in ("direct", "iterative"):
            run(n, args.mu, linear, args.out)


if __name__ == "__main__":
    main()
