"""The punch ladder: the paper's punch over its whole 2 mm path at growing size
with the iterative solver (GMRES + smoothed-aggregation AMG), frictionless or
with μ1 = 0.3, serial or under mpirun. Per size: Newton iterations (and per
step), Krylov iterations per Newton iteration, time per Newton iteration and
its split (volume assembly, contact, preconditioner set-up, Krylov solves,
the rest), peak memory per unknown, the punch force.

    .venv/bin/python bench/ladder.py --sizes 16 32 64 96 112 [--mu 0.3]
    mpirun -n 2 --allow-run-as-root --oversubscribe .venv/bin/python bench/ladder.py --sizes 16 32 64
    .venv/bin/python bench/ladder.py --report

Sizes n are quarter meshes n × n × n/4 (4 335, 29 403, 215 475, 705 675 and
1 110 903 unknowns for 16, 32, 64, 96, 112). Appends one JSON line per run to
OUT/ladder.jsonl; --report writes OUT/ladder.md and OUT/ladder.png from all
lines. A benchmark reports; it asserts nothing.
"""
import argparse
import json
import resource
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def run(n, mu, out, extra):
    from mpi4py import MPI

    from hypercontact import _dolfinx as dfx
    from hypercontact import scene
    from hypercontact.simulation import Simulation

    comm = MPI.COMM_WORLD
    name = "punch.toml" if mu == 0 else "punch_mu0.3_0.toml"
    folder = out / f"n{n}_mu{mu:g}_np{comm.size}"
    sc = scene.load(ROOT / "scenes" / name, [f"mesh.n={n}", f"mesh.m={max(n // 4, 1)}", "solver.linear=iterative",
                                             "output.xdmf=false", f"output.dir={folder}", *extra])
    t0 = time.perf_counter()
    sim = Simulation(sc, comm, log=lambda *a, **k: None)
    writer = sim.run()
    wall = time.perf_counter() - t0
    summary = writer.write_summary(sim.timers)
    peak = comm.allreduce(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, op=MPI.SUM)  # MiB
    failed = summary["failed_attempts"]  # their iterations took time too: counted in the per-Newton rates
    newton = sum(summary["newton_iterations"]) + sum(attempt_iterations(f) for f in failed)
    row = {"n": n, "mu": mu, "ranks": comm.size, "unknowns": dfx.num_global_dofs(sim.V),
           "steps": len(writer.steps), "newton": newton, "newton_per_step": summary["newton_iterations"],
           "krylov": sum(summary["linear_iterations"]) + sum(f.get("linear_iterations", 0) for f in failed),
           "failed_attempts": len(failed),
           "wall_s": wall, "time_split": summary["time_split"], "linear_solver": summary["linear_solver"],
           "peak_MiB_all_ranks": peak, "force": -writer.steps[-1]["punch_fz"], "extra": list(extra)}
    if comm.rank == 0:
        with open(out / "ladder.jsonl", "a") as f:
            f.write(json.dumps(row) + "\n")
        print(json.dumps({k: v for k, v in row.items() if k != "newton_per_step"}), flush=True)


def attempt_iterations(story):
    """Newton iterations of a failed attempt, all its solves (stories written before
    attempt_newton_iterations existed count the last solve only)."""
    return story.get("attempt_newton_iterations", story.get("newton_iterations", 0))


def tangents(row):
    """Newton iterations as tangents assembled and solved (the preconditioner set-ups, one per
    tangent). SNES's own count (row["newton"]) leaves out an iteration whose update ended on a
    residual that is not a number (an inverted element), although its tangent, set-up and Krylov
    solve were done and its Krylov iterations are in row["krylov"]: the rates divide by this."""
    return max(row["linear_solver"].get("preconditioner_setups", 0), row["newton"])


def partial_rows(out, done):
    """Rows of runs stopped before the end of the path (killed: a size too big for the time
    at hand), from the summary.json each converged step rewrote; marked partial."""
    import re


    rows = []
    for folder in sorted(out.glob("n*_mu*_np*")):
        n, mu, ranks = re.fullmatch(r"n(\d+)_mu([\d.]+)_np(\d+)", folder.name).groups()
        key = (int(n), float(mu), int(ranks))
        summary = folder / "summary.json"
        if key in done or not summary.exists():
            continue
        sm = json.loads(summary.read_text())
        if not sm["steps"]:
            continue
        unknowns = 3 * (key[0] + 1) ** 2 * (max(key[0] // 4, 1) + 1)  # the box's Q1 nodes, 3 components
        failed = sm.get("failed_attempts", [])  # their iterations took time too: counted in the per-Newton rates
        rows.append({"n": key[0], "mu": key[1], "ranks": key[2], "unknowns": unknowns, "steps": len(sm["steps"]),
                     "newton": sum(sm["newton_iterations"]) + sum(attempt_iterations(f) for f in failed),
                     "krylov": sum(sm["linear_iterations"]) + sum(f.get("linear_iterations", 0) for f in failed),
                     "wall_s": sm["wall_time"], "time_split": sm["time_split"], "linear_solver": sm["linear_solver"],
                     "peak_MiB_all_ranks": sm["peak_memory_mb"]["sum_ranks"], "force": -sm["steps"][-1]["punch_fz"],
                     "partial": f"stopped after step {len(sm['steps'])}, λ = {sm['steps'][-1]['load_factor']:.2f}"
                                + (f"; Newton and Krylov counts include {len(failed)} failed attempt(s) "
                                   f"({sum(f.get('newton_iterations', 0) for f in failed)} Newton iterations)"
                                   if failed else "")})
    return rows


def speed_up(row, serial):
    """Wall time of the serial run over this run's, for the whole path; also per Newton
    iteration when the Newton counts differ. "—" for serial rows and partial runs."""
    if row["ranks"] == 1 or serial is None or "partial" in row:
        return "—"
    text = f"{serial['wall_s'] / row['wall_s']:.2f}"
    if tangents(serial) != tangents(row):
        text += f" ({serial['wall_s'] / tangents(serial) / (row['wall_s'] / tangents(row)):.2f} per Newton)"
    return text


def report(out):
    import numpy as np

    rows = [json.loads(line) for line in (out / "ladder.jsonl").read_text().splitlines() if line.strip()]
    rows += partial_rows(out, {(r["n"], r["mu"], r["ranks"]) for r in rows})
    rows.sort(key=lambda r: (r["mu"], r["ranks"], r["unknowns"]))
    lines = ["| μ1 | ranks | unknowns | steps | Newton its | Krylov / Newton | s / Newton | volume asm | contact "
             "| PC set-up | Krylov | rest | peak MiB | bytes / unknown | punch force (N) | wall (s) | speed-up |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    serial = {(r["n"], r["mu"]): r for r in rows if r["ranks"] == 1 and "partial" not in r}
    for r in rows:
        s, lin, k = r["time_split"], r["linear_solver"], tangents(r)
        its = f"{k}" + (f" ({r['newton']})" if k > r["newton"] else "")
        parts = [s.get("volume assembly", 0), s.get("contact", 0) + s.get("contact search", 0),
                 lin.get("preconditioner_setup_s", 0), lin.get("krylov_s", 0)]
        per = r["wall_s"] / k
        lines.append(f"| {r['mu']:g} | {r['ranks']} | {r['unknowns']:,} | {r['steps']} | {its} | {r['krylov'] / k:.1f} | "
                     f"{per:.2f} | " + " | ".join(f"{p / k:.2f}" for p in parts) + f" | {per - sum(parts) / k:.2f} | "
                     f"{r['peak_MiB_all_ranks']:.0f} | {r['peak_MiB_all_ranks'] * 2**20 / r['unknowns']:.0f} | "
                     f"{r['force']:.2f}{' (partial)' if 'partial' in r else ''} | {r['wall_s']:.0f} | "
                     f"{speed_up(r, serial.get((r['n'], r['mu'])))} |")
    notes = [f"- {r['unknowns']:,} unknowns, μ1 = {r['mu']:g}, {r['ranks']} rank(s): {r['partial']} "
             "(the force is that step's)" for r in rows if "partial" in r]
    text = ["# The punch ladder: the whole 2 mm path, iterative solver", "",
            "Newton its: tangents assembled and solved, every Newton iteration of the path's converged "
            "steps and failed attempts; in brackets SNES's count where it is lower (it leaves out an "
            "iteration whose update ended on a residual that is not a number, an inverted element, whose "
            "tangent, preconditioner set-up and Krylov solve were done all the same). "
            "Per Newton iteration, in seconds: volume assembly (tangent and residual), contact (and search), "
            "the AMG set-up, the Krylov solves, and the rest (line search, output, set-up of the run). "
            "Speed-up: the serial run's wall time over this run's, the whole path; a serial and a parallel "
            "run compare only when they ran one after the other in the same file.", ""] + lines
    text += (["", "Partial runs (killed before the end of the path):"] + notes) if notes else []
    special = [f"- {r['unknowns']:,} unknowns, μ1 = {r['mu']:g}, {r['ranks']} rank(s): "
               + "; ".join(([f"{r['failed_attempts']} failed attempt(s) cut back, their Newton and Krylov "
                             "iterations counted in the rates"] if r.get("failed_attempts") else [])
                           + ([f"run with {', '.join(r['extra'])}"] if r.get("extra") else []))
               for r in rows if "partial" not in r and (r.get("failed_attempts") or r.get("extra"))]
    text += (["", "Completed runs with failed attempts or non-default settings:"] + special) if special else []
    (out / "ladder.md").write_text("\n".join(text) + "\n")
    print("\n".join(text))
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for (mu, ranks) in sorted({(r["mu"], r["ranks"]) for r in rows}):
        sel = [r for r in rows if r["mu"] == mu and r["ranks"] == ranks]
        x = [r["unknowns"] for r in sel]
        label = f"μ1 = {mu:g}, {ranks} rank{'s' * (ranks > 1)}"
        ax[0].semilogx(x, [r["krylov"] / tangents(r) for r in sel], "o-", label=label)
        ax[1].loglog(x, [r["wall_s"] / tangents(r) for r in sel], "o-", label=label)
    ax[0].set(xlabel="unknowns", ylabel="Krylov iterations per Newton iteration", ylim=(0, None))
    ax[1].set(xlabel="unknowns", ylabel="seconds per Newton iteration")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
        a.legend()
    fig.tight_layout()
    fig.savefig(out / "ladder.png", dpi=100)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", type=int, nargs="+", default=[16, 32, 64])
    p.add_argument("--mu", type=float, default=0.0, help="0 (punch.toml) or 0.3 (punch_mu0.3_0.toml)")
    p.add_argument("--out", default=str(ROOT / "bench" / "results" / "ladder"))
    p.add_argument("--set", dest="extra", action="append", default=[], help="scene override KEY=VALUE")
    p.add_argument("--report", action="store_true")
    a = p.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    if a.report:
        report(out)
        return
    import logging

    logging.getLogger().setLevel(logging.WARNING)
    for n in a.sizes:
        run(n, a.mu, out, a.extra)


if __name__ == "__main__":
    main()
