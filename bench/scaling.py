"""Time per Newton iteration and peak memory of the frictionless punch from
~10^4 to ~10^6 unknowns, with the iterative solver (GMRES + GAMG with the
rigid-body near-nullspace), serial or under mpirun. One load step of a 0.5 mm
indentation (Δλ = 1), so that every size does the same few Newton
iterations; the per-phase split says where the time goes.

    .venv/bin/python bench/scaling.py --sizes 16 32 64 112 --out bench/results/scaling
    mpirun -n 2 --allow-run-as-root --oversubscribe .venv/bin/python bench/scaling.py --sizes 16 32 64 96 ...

Appends one JSON line per size to OUT/scaling_np{N}.jsonl; --report writes
OUT/scaling.md from all the lines. --max-it K times K Newton iterations of
the step without converging it (for the largest sizes; rows marked capped).
"""
import argparse
import json
import resource
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def run(n, out, linear, max_it=None):
    from mpi4py import MPI

    from hypercontact import scene
    from hypercontact import _dolfinx as dfx
    from hypercontact.simulation import Simulation, StepFailure

    comm = MPI.COMM_WORLD
    data = tomllib.loads((ROOT / "scenes" / "punch.toml").read_text())
    data["mesh"].update(n=n, m=max(n // 4, 1))
    data["contact"][0]["motion"] = [0.0, 0.0, -0.5]
    data["steps"].update(initial=1.0, max=1.0)
    data["solver"]["linear"] = linear
    if max_it:  # time a fixed number of Newton iterations (the step is not converged: no cut-back)
        data["solver"]["max_it"] = max_it
        data["steps"]["max_cutbacks"] = 0
    data["output"].update(xdmf=False)
    sc = scene.load(data, [f"output.dir={out}"])
    t0 = time.perf_counter()
    sim = Simulation(sc, comm, log=lambda *a, **k: None)
    setup = time.perf_counter() - t0
    try:
        writer = sim.run(out_dir=str(out / f"n{n}"))
        converged, its_capped = True, 0
    except StepFailure:
        if not max_it:
            raise
        writer, converged = None, False
        its_capped = sim.snes.getIterationNumber()
    wall = time.perf_counter() - t0 - setup
    its = sum(s["newton_iterations"] for s in writer.steps) if writer else its_capped
    peak = comm.allreduce(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, op=MPI.SUM)  # MiB
    seconds = {k: comm.allreduce(v, op=MPI.MAX) for k, v in sim.timers.seconds.items()}
    row = {"n": n, "ranks": comm.size, "unknowns": dfx.num_global_dofs(sim.V), "linear": linear,
           "newton": its, "krylov": int(sum(sim.linear_iterations)), "wall_s": wall, "setup_s": setup,
           "per_newton_s": wall / its, "peak_MiB_all_ranks": peak, "seconds": seconds,
           "force": writer.steps[-1]["punch_fz"] if writer else None, "converged": converged}
    if comm.rank == 0:
        with open(out / f"scaling_np{comm.size}.jsonl", "a") as f:
            f.write(json.dumps(row) + "\n")
        print(json.dumps(row), flush=True)


def report(out):
    rows = []
    for path in sorted(out.glob("scaling_np*.jsonl")):
        rows += [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
    rows.sort(key=lambda r: (r["ranks"], r["unknowns"]))
    lines = ["| ranks | unknowns | Newton its | Krylov its / Newton | s / Newton it | volume asm | contact | linear solve "
             "| peak memory (MiB, all ranks) | bytes / unknown |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        s = r["seconds"]
        capped = "" if r.get("converged", True) else " (capped)"
        lines.append(f"| {r['ranks']} | {r['unknowns']} | {r['newton']}{capped} | {r['krylov'] / r['newton']:.1f} | "
                     f"{r['per_newton_s']:.2f} | {s.get('volume assembly', 0) / r['newton']:.2f} | "
                     f"{s.get('contact', 0) / r['newton']:.3f} | {s.get('linear solve', 0) / r['newton']:.2f} | "
                     f"{r['peak_MiB_all_ranks']:.0f} | {r['peak_MiB_all_ranks'] * 2**20 / r['unknowns']:.0f} |")
    import numpy as np

    for ranks in sorted({r["ranks"] for r in rows}):
        sel = [r for r in rows if r["ranks"] == ranks and r.get("converged", True)]  # capped rows: not a full step
        if len(sel) >= 2:
            x = np.log([r["unknowns"] for r in sel])
            y = np.log([r["per_newton_s"] for r in sel])
            lines.append(f"\n{ranks} rank(s): time per Newton iteration grows like unknowns^{np.polyfit(x, y, 1)[0]:.2f}"
                         " (converged steps only)")
    if any(not r.get("converged", True) for r in rows):
        lines.append("\n(capped): only the first Newton iteration(s) of the step were timed (--max-it); the first "
                     "iteration also sets up GAMG and takes more Krylov iterations than the step's average, so its "
                     "time is not comparable to the converged rows' mean; its memory is.")
    (out / "scaling.md").write_text("# Punch scaling, iterative solver\n\n" + "\n".join(lines) + "\n")
    print("\n".join(lines))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--sizes", type=int, nargs="+", default=[16, 32, 64])
    p.add_argument("--out", default="bench/results/scaling")
    p.add_argument("--linear", default="iterative")
    p.add_argument("--report", action="store_true")
    p.add_argument("--max-it", type=int, default=None,
                   help="time this many Newton iterations only (the largest sizes; marked 'capped')")
    a = p.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    if a.report:
        report(out)
        return
    import logging

    logging.getLogger().setLevel(logging.WARNING)
    for n in a.sizes:
        run(n, out, a.linear, a.max_it)


if __name__ == "__main__":
    main()
