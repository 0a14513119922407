"""The inflated sphere (paper Fig. 2) and what its accuracy costs in time.

    .venv/bin/python bench/sphere.py [--figure] [--study] [--out bench/results/sphere]

--figure: pressure against the inner radial displacement for K = 1, 5, 200
  (16 × 16 × 4 octant, plain displacement formulation, arc length to 85 mm)
  with the spherically symmetric 1D oracle; PNG, CSV and a table of limit
  points.
--study: for K = 200, the error of the limit pressure and of the
  displacement at it against the oracle, and the wall time, for meshes
  8 × 8 × 2 … 32 × 32 × 8, the plain formulation (quadrature degrees 2 and
  3), selective reduced integration and the mixed u–p formulation
  (Taylor–Hood, 4 × 4 × 1 … 16 × 16 × 4); a table and a plot of error
  against time. A benchmark reports; it asserts nothing.
"""
import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from hypercontact.sphere1d import PAPER, limit_point, pressure_curve  # noqa: E402


def run(out, overrides):
    sc = scene.load(ROOT / "scenes" / "sphere.toml", [f"output.dir={out}", "output.xdmf=false", *overrides])
    t0 = time.perf_counter()
    sim = Simulation(sc, MPI.COMM_WORLD, log=lambda *a: None)
    writer = sim.run()
    wall = time.perf_counter() - t0
    u = np.array([s["equator_ux"] for s in writer.steps])
    p = np.array([s["pressure_inner"] for s in writer.steps])
    summary = writer.write_summary(sim.timers)
    return u, p, wall, summary


def vertex(u, p):
    """The parabola through the highest computed point and its neighbours (how
    the limit point was read before continuation located it)."""
    k = int(np.argmax(p))
    a, b, c = np.polyfit(u[k - 1:k + 2], p[k - 1:k + 2], 2)
    return -b / (2 * a), c - b * b / (4 * a)


def located(summary):
    """(u, p) of the limit point continuation located (summary.json limit_points)."""
    limit = summary["limit_points"][0]
    if not limit["located"]:
        return float("nan"), float("nan")
    scale = summary["scene"]["pressure"][0]["value"]
    return limit["probes"]["equator"][0], scale * limit["load_factor"]


def figure(out, i2="usual"):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    rows = []
    suffix = "" if i2 == "usual" else f"_{i2}"
    for K, color in [(1.0, "tab:blue"), (5.0, "tab:orange"), (200.0, "tab:green")]:
        params = dict(PAPER, K=K, i2=i2)
        u, p, wall, summary = run(out / f"K{K:g}_{i2}", [f"material.parameters.K={K}", f"material.parameters.i2={i2}",
                                                         "steps.max=0.15"])
        uu = np.linspace(0.0, u.max(), 200)
        ax.plot(uu, 1e3 * pressure_curve("mooney_rivlin", params, uu), "-", color=color, lw=1,
                label=f"K = {K:g}: 1D oracle")
        ax.plot(u, 1e3 * p, "o", color=color, ms=3, label=f"K = {K:g}: FE 16×16×4")
        u_ref, p_ref = limit_point("mooney_rivlin", params)
        u_max, p_max = located(summary)
        u_par, _ = vertex(u, p)
        err = np.max(np.abs(p / pressure_curve("mooney_rivlin", params, u) - 1))
        rows.append(dict(K=K, u_ref=u_ref, p_ref=p_ref, u_fe=u_max, p_fe=p_max, u_parabola=u_par, curve_error=err,
                         steps=len(u), newton=int(sum(summary["newton_iterations"])), wall=wall))
        np.savetxt(out / f"curve_K{K:g}{suffix}.csv", np.c_[u, p], delimiter=",", header="u_inner_mm,p_MPa", comments="")
    ax.set_xlabel("radial displacement of the inner surface (mm)")
    ax.set_ylabel("internal pressure (kPa)")
    ax.set_title(f"Inflated Mooney sphere (α1 = 0.1863, α2 = 0.0098), {i2} I2")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / f"sphere_fig2{suffix}.png", dpi=120)
    lines = ["| K | oracle u_max (mm) | FE u_max located | (parabola) | oracle p_max (kPa) | FE p_max located | "
             "max curve error | steps | Newton its | wall (s) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['K']:g} | {r['u_ref']:.3f} | {r['u_fe']:.3f} | {r['u_parabola']:.3f} | {1e3 * r['p_ref']:.4f} | "
                     f"{1e3 * r['p_fe']:.4f} | {100 * r['curve_error']:.2f} % | {r['steps']} | {r['newton']} | {r['wall']:.0f} |")
    (out / f"sphere_fig2{suffix}.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines), flush=True)


def study(out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    K = 200.0
    params = dict(PAPER, K=K, i2="usual")
    u_ref, p_ref = limit_point("mooney_rivlin", params)
    rows = []
    cases = [(n, m, "displacement", q) for n, m in [(8, 2), (16, 4), (32, 8)] for q in (2, 3)]
    cases += [(n, m, "sri", 2) for n, m in [(8, 2), (16, 4), (32, 8)]]
    cases += [(n, m, "mixed", 4) for n, m in [(4, 1), (8, 2), (16, 4)]]
    for n, m, formulation, q in cases:
        u, p, wall, summary = run(out / f"study_{n}x{m}_{formulation}_q{q}", [
            f"mesh.n={n}", f"mesh.m={m}", f"material.parameters.K={K}",
            f"discretisation.formulation={formulation}", f"discretisation.quadrature_degree={q}",
            "steps.max=0.15", f"steps.stop_value={1.25 * u_ref}"])
        u_max, p_max = located(summary)
        u_par, _ = vertex(u, p)
        rows.append(dict(mesh=f"{n}x{n}x{m}", formulation=formulation, quadrature=q,
                         u_error_parabola=abs(u_par / u_ref - 1), locating_its=summary["limit_points"][0].get(
                             "newton_iterations", 0),
                         p_error=abs(p_max / p_ref - 1), u_error=abs(u_max / u_ref - 1), wall=wall,
                         newton=int(sum(summary["newton_iterations"])), steps=len(u)))
        r = rows[-1]
        print(f"{r['mesh']:>8} {formulation:>12} q{q}: p error {100 * r['p_error']:.3f} %, "
              f"u error {100 * r['u_error']:.3f} %, {r['steps']} steps, {r['newton']} Newton, "
              f"{wall:.1f} s", flush=True)
    (out / "study_K200.json").write_text(json.dumps(rows, indent=1))
    lines = ["| mesh | formulation | quadrature | limit pressure error | displacement error | (parabola) | steps | "
             "Newton its (locating) | wall (s) |",
             "|---|---|---|---|---|---|---|---|---|"]
    lines += [f"| {r['mesh']} | {r['formulation']} | {r['quadrature']} | {100 * r['p_error']:.3f} % | "
              f"{100 * r['u_error']:.3f} % | {100 * r['u_error_parabola']:.3f} % | {r['steps']} | "
              f"{r['newton']} ({r['locating_its']}) | {r['wall']:.1f} |" for r in rows]
    (out / "study_K200.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for formulation, q, marker, fill in [("displacement", 2, "o", "full"), ("displacement", 3, "o", "none"),
                                         ("sri", 2, "s", "full"), ("mixed", 4, "^", "full")]:
        sel = [r for r in rows if r["formulation"] == formulation and r["quadrature"] == q]
        ax.loglog([r["wall"] for r in sel], [max(r["p_error"], 1e-6) for r in sel], marker=marker,
                  fillstyle=fill, label=f"{formulation}, quadrature {q}")
        for r in sel:
            ax.annotate(r["mesh"], (r["wall"], max(r["p_error"], 1e-6)), fontsize=7)
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("relative error of the limit pressure")
    ax.set_title("Sphere, K = 200: accuracy against time")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "study_K200.png", dpi=120)


def main():
    import logging

    logging.getLogger().setLevel(logging.WARNING)
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--figure", action="store_true")
    p.add_argument("--study", action="store_true")
    p.add_argument("--i2", choices=["usual", "paper"], default="usual", help="definition of I2 for --figure")
    p.add_argument("--out", default=str(ROOT / "bench" / "results" / "sphere"))
    args = p.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.figure or not args.study:
        figure(out, args.i2)
    if args.study or not args.figure:
        study(out)


if __name__ == "__main__":
    main()
