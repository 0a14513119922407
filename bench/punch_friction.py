"""The paper's four friction cases of the rigid punch (docs/method.md §9.2,
the paper's Figs. 3–6).

    .venv/bin/python bench/punch_friction.py [--meshes 16x4 32x8] [--eps-t-study]

Runs scenes/punch_mu0_0, punch_mu0.3_0, punch_mu1_0 and punch_mu0_1
((μ1, μ2): μ1 between punch and plate, μ2 between plate and base) on each
quarter mesh N×N×M and writes:

- ``bench/results/punch_friction.md``: punch force (whole plate), edge and
  corner uplift at full indentation, the change against the frictionless
  case, load steps and Newton iterations per step, wall time and its split,
  and the observed order of Newton's convergence in the frictional steps
  (from the residual norm histories in each run's summary.json);
- ``bench/results/punch_friction/uz_<case>.png``: the vertical displacement on
  the deformed quarter plate at full indentation (finest mesh, one colour
  scale for the four cases), as in the paper's figures 3–6;
  ``curves.png``: punch force and uplifts against the indentation;
  ``punch_friction.json``: everything in the table, and the curves.

With ``--eps-t-study`` the three frictional cases are also run on the
coarsest mesh with other tangential penalties ε_T, to show how much the
regularisation of the stick condition moves the results. A benchmark
reports, it asserts nothing.
"""
import argparse
import json
import time
from pathlib import Path

import numpy as np
from mpi4py import MPI

from hypercontact import pictures, scene
from hypercontact.simulation import Simulation, StepFailure

ROOT = Path(__file__).resolve().parents[1]
CASES = {"punch_mu0_0": (0.0, 0.0), "punch_mu0.3_0": (0.3, 0.0), "punch_mu1_0": (1.0, 0.0),
         "punch_mu0_1": (0.0, 1.0)}
PHASES = ["setup", "volume assembly", "contact", "linear solve", "output", "other"]


def observed_orders(norms, floor, start=1e-2):
    """Orders log(e_k+1/e_k) / log(e_k/e_k-1) of a decreasing sequence (one
    Newton solve's residual or correction norms) in its asymptotic part:
    e_k-1 below ``start`` × e_0, e_k+1 above the round-off ``floor``."""
    e = np.asarray(norms, dtype=float)
    out = []
    for k in range(1, len(e) - 1):
        if e[k - 1] < start * e[0] and e[k + 1] > floor and e[k] < e[k - 1] and e[k + 1] < e[k]:
            out.append(float(np.log(e[k + 1] / e[k]) / np.log(e[k] / e[k - 1])))
    return out


def order_statistics(steps, measured):
    """Observed orders over the steps ``measured``: from the residual norms
    (floor: 10 × the smallest final residual of the run, its round-off
    level) and from the Newton corrections (floor: 1e-12 × the largest);
    all of them, and the last one of each step."""
    floor_r = 10 * min(s["residual_norms"][-1] for s in steps)
    floor_u = 1e-12 * max((max(s["update_norms"]) for s in steps if s["update_norms"]), default=1.0)
    out = {}
    for key, floor, start in (("residual", floor_r, 1e-2), ("update", floor_u, 1e-1)):
        per_step = [observed_orders(steps[i][f"{key}_norms"], floor, start) for i in measured]
        out[key] = {"all": [o for orders in per_step for o in orders],
                    "last": [orders[-1] for orders in per_step if orders], "floor": floor}
    return out


def frictional_steps(steps):
    """Indices of the steps in which a frictional contact had closed nodes."""
    names = {k[: -len("_stick_nodes")] for k in steps[0] if k.endswith("_stick_nodes")} if steps else set()
    return [i for i, s in enumerate(steps) if any(s[f"{n}_stick_nodes"] + s[f"{n}_slip_nodes"] for n in names)]


def folder(case, mesh, extra=()):
    """A run's results folder name: case, quarter mesh, overrides."""
    return f"{case}_{mesh}" + "".join(f"_{e.replace('=', '')}" for e in extra)


def previous_run(path):
    """(summary, wall time) of a finished run in ``path``, or None."""
    try:
        summary = json.loads((path / "summary.json").read_text())
    except (OSError, ValueError):
        return None
    if summary.get("status") == "running":
        return None
    try:
        wall = json.loads((path / "bench_wall.json").read_text())["wall_time"]
    except (OSError, ValueError, KeyError):
        wall = summary["wall_time"] + summary["time_split"].get("setup", 0.0)
    return summary, wall


def run(case, n, m, out, extra=(), reuse=False):
    """One run (or, with ``reuse``, the finished run already in its folder):
    (row of the table, Simulation or None, writer or None)."""
    name = folder(case, f"{n}x{n}x{m}", extra)
    comm = MPI.COMM_WORLD
    previous = comm.bcast(previous_run(out / name) if reuse and comm.rank == 0 else None, root=0)
    sim = writer = None
    if previous is not None:
        summary, wall = previous
        status = "completed" if summary["status"] == "completed" else f"failed: {summary['message']}"
    else:
        sc = scene.load(ROOT / "scenes" / f"{case}.toml",
                        [f"mesh.n={n}", f"mesh.m={m}", f"output.dir={out / name}", *extra])
        t0 = time.perf_counter()
        sim = Simulation(sc, comm, log=lambda *a: None)
        status = "completed"
        try:
            writer = sim.run()
        except StepFailure as err:
            status = f"failed: {err}"
        wall = time.perf_counter() - t0
        if comm.rank == 0:
            (out / name / "bench_wall.json").write_text(json.dumps({"wall_time": wall}))
        summary = comm.bcast(json.loads((out / name / "summary.json").read_text()) if comm.rank == 0 else None,
                             root=0)
    steps = summary["steps"]
    fric = frictional_steps(steps)
    measured = fric if any(CASES[case]) else range(len(steps))  # frictionless: all steps, for comparison
    orders = order_statistics(steps, measured) if steps else {}
    nan = float("nan")
    last = steps[-1] if steps else {}
    row = {
        "case": case, "mu1": CASES[case][0], "mu2": CASES[case][1], "mesh": f"{n}x{n}x{m}", "extra": list(extra),
        "status": status, "unknowns": 3 * (n + 1) ** 2 * (m + 1),
        "indentation": last.get("punch_displacement", nan), "punch_force": -last.get("punch_fz", nan),
        "base_force": last.get("base_fz", nan), "edge_uplift": last.get("edge_uz", nan),
        "corner_uplift": last.get("corner_uz", nan),
        "dissipation": last.get("dissipation", 0.0),
        "steps": len(steps), "newton_per_step": [s["newton_iterations"] for s in steps],
        "newton_total": sum(s["newton_iterations"] for s in steps), "frictional_steps": len(fric),
        "orders": orders,
        "order_median": float(np.median(orders["residual"]["all"])) if orders.get("residual", {}).get("all") else None,
        "wall_time": wall, "time_split": summary["time_split"],
        "curve": {k: [s.get(k) for s in steps] for k in
                  ("load_factor", "punch_displacement", "punch_fz", "base_fz", "edge_uz", "corner_uz", "dissipation")},
    }
    return row, sim, writer


def compact_png(path):
    """Rewrite a PNG with a 256-colour palette (a quarter of the size, the
    pictures are committed)."""
    from PIL import Image

    with Image.open(path) as image:
        quantized = image.convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT)
    quantized.save(path, optimize=True)


def draw_uz(sims, rows, folder):
    """uz on the deformed quarter plate, one PNG per case, one colour scale."""
    lo = min(float(MPI.COMM_WORLD.allreduce(sim.u.x.array.reshape(-1, 3)[:, 2].min(initial=np.inf), op=MPI.MIN))
             for sim in sims)
    hi = max(float(MPI.COMM_WORLD.allreduce(sim.u.x.array.reshape(-1, 3)[:, 2].max(initial=-np.inf), op=MPI.MAX))
             for sim in sims)
    paths = []
    for sim, r in zip(sims, rows):
        path = folder / f"uz_{r['case']}.png"
        title = (f"(μ1, μ2) = ({r['mu1']:g}, {r['mu2']:g}): vertical displacement uz (mm), indentation 2 mm\n"
                 f"quarter plate {r['mesh']}, punch force {r['punch_force']:.1f} N, "
                 f"uplift edge {r['edge_uplift']:.3f} mm, corner {r['corner_uplift']:.3f} mm")
        pictures.deformed_shape(sim.V.mesh, sim.u, "uz", path, title=title, label="uz (mm)",
                                view=(30.0, -125.0), cmap="coolwarm", limits=(lo, hi))
        if MPI.COMM_WORLD.rank == 0:
            compact_png(path)
        paths.append(path)
    return paths


def draw_curves(rows, path):
    import matplotlib.pyplot as plt

    meshes = sorted({r["mesh"] for r in rows if not r["extra"]}, key=lambda s: int(s.split("x")[0]))
    fig, axes = plt.subplots(1, 3, figsize=(15.0, 4.6), dpi=100)
    colours = dict(zip(CASES, ["0.2", "tab:blue", "tab:red", "tab:green"]))
    for r in rows:
        if r["extra"] or not r["steps"]:
            continue
        c = r["curve"]
        style = "-" if r["mesh"] == meshes[-1] else "--"
        label = f"({r['mu1']:g}, {r['mu2']:g}) {r['mesh']}"
        d = [0.0] + c["punch_displacement"]
        axes[0].plot(d, [0.0] + [-f for f in c["punch_fz"]], style, color=colours[r["case"]], marker="o",
                     markersize=2.5, label=label)
        axes[1].plot(d, [0.0] + c["edge_uz"], style, color=colours[r["case"]], marker="o", markersize=2.5, label=label)
        axes[2].plot(d, [0.0] + c["corner_uz"], style, color=colours[r["case"]], marker="o", markersize=2.5,
                     label=label)
    for ax, what in zip(axes, ["punch force (N, whole plate)", "edge uplift uz(40, 0, 0) (mm)",
                               "corner uplift uz(40, 40, 0) (mm)"]):
        ax.set_xlabel("indentation (mm)")
        ax.set_ylabel(what)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7, title="(μ1, μ2) mesh", title_fontsize=7)
    fig.suptitle("Rigid punch on a Mooney plate: friction under the punch (μ1) and on the base (μ2)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    compact_png(path)


def mm(v):
    """A displacement in mm: 3 decimals, or one significant digit when it is tiny."""
    return f"{v:.3f}" if abs(v) >= 0.005 else f"{v:.1g}"


def markdown(rows, out):
    ref = {r["mesh"]: r for r in rows if r["case"] == "punch_mu0_0" and not r["extra"]}

    def change(r, key):
        base = ref.get(r["mesh"], {}).get(key)
        if r["case"] == "punch_mu0_0" or base in (None, 0) or r[key] is None:
            return ""
        return f" ({100 * (r[key] / base - 1):+.1f} %)"

    lines = ["| (μ1, μ2) | quarter mesh | punch force (N) | edge uplift (mm) | corner uplift (mm) | dissipation (N mm) "
             "| steps | Newton its per step | wall (s) | " + " | ".join(PHASES) + " |",
             "|" + "---|" * (9 + len(PHASES))]
    for r in rows:
        if r["extra"]:
            continue
        split = r["time_split"]
        lines.append(
            f"| ({r['mu1']:g}, {r['mu2']:g}) | {r['mesh']} | {r['punch_force']:.2f}{change(r, 'punch_force')} | "
            f"{mm(r['edge_uplift'])}{change(r, 'edge_uplift')} | {mm(r['corner_uplift'])}{change(r, 'corner_uplift')} | "
            f"{r['dissipation']:.1f} | {r['steps']} | {' '.join(map(str, r['newton_per_step']))} "
            f"(Σ {r['newton_total']}) | {r['wall_time']:.0f} | "
            + " | ".join(f"{split.get(k, 0.0):.1f}" for k in PHASES) + " |")
    lines += ["", "Observed order of Newton's convergence q = log(e_k+1/e_k) / log(e_k/e_k-1), in the steps with "
              "friction (the frictionless case: all its steps, for comparison). From the residual norms r_k of "
              "summary.json: over the iterations with r_k-1 < 1 % of r_0 and r_k+1 above the round-off level (10 × "
              "the smallest final residual of the run, about 2e-11 N); from the Newton corrections |Δu_k| "
              "(summary.json's update_norms; as tests/verification/test_punch.py measures it): with |Δu_k-1| < 10 % of the "
              "first. Medians over all such iterations, and over the last one of each step (the asymptotic rate):",
              "", "| (μ1, μ2) | quarter mesh | frictional steps | residuals: median (iterations) | residuals: last of "
              "each step | corrections: median | corrections: last of each step |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["extra"]:
            continue
        steps = json.loads((out / folder(r["case"], r["mesh"]) / "summary.json").read_text())["steps"]
        measured = frictional_steps(steps) if any(CASES[r["case"]]) else range(len(steps))
        st = order_statistics(steps, measured)

        def med(values):
            return f"{np.median(values):.2f}" if values else "–"

        cells = []
        for key in ("residual", "update"):
            a, last = st[key]["all"], st[key]["last"]
            cells.append(f"{med(a)} ({len(a)})" if key == "residual" else med(a))
            cells.append(f"{med(last)} ({sum(o >= 1.5 for o in last)} of {len(last)} ≥ 1.5)")
        lines.append(f"| ({r['mu1']:g}, {r['mu2']:g}) | {r['mesh']} | {len(frictional_steps(steps))} | "
                     + " | ".join(cells) + " |")
    finest = max((r["mesh"] for r in rows), key=lambda s: int(s.split("x")[0]))
    lines += ["", f"Residual norms (N) of the step with the most Newton iterations, {finest}:", ""]
    for r in rows:
        if r["extra"] or r["mesh"] != finest:
            continue
        steps = json.loads((out / folder(r["case"], r["mesh"]) / "summary.json").read_text())["steps"]
        k = max(range(len(steps)), key=lambda i: len(steps[i]["residual_norms"]))
        norms = " → ".join(f"{v:.1e}" for v in steps[k]["residual_norms"])
        lines.append(f"- ({r['mu1']:g}, {r['mu2']:g}), step {k + 1} (λ = {steps[k]['load_factor']:.3g}): {norms}")
    study = [r for r in rows if r["extra"]]
    if study:
        lines += ["", "Tangential penalty ε_T (N/mm³) against the scenes' ε_T = 10, coarsest mesh:", "",
                  "| (μ1, μ2) | ε_T | status | punch force (N) | edge uplift (mm) | corner uplift (mm) | steps "
                  "| Newton its |", "|---|---|---|---|---|---|---|---|"]
        for r in study:
            eps = r["extra"][0].split("=")[1]
            base = next(b for b in rows if b["case"] == r["case"] and not b["extra"] and b["mesh"] == r["mesh"])
            if r["status"] != "completed":
                lines.append(f"| ({r['mu1']:g}, {r['mu2']:g}) | {eps} | {r['status'][:60]}… | | | | {r['steps']} | "
                             f"{r['newton_total']} |")
                continue

            def rel(key):
                return f"{mm(r[key]) if 'uplift' in key else f'{r[key]:.2f}'} ({100 * (r[key] / base[key] - 1):+.2f} %)"

            lines.append(f"| ({r['mu1']:g}, {r['mu2']:g}) | {eps} | completed | {rel('punch_force')} | "
                         f"{rel('edge_uplift')} | {rel('corner_uplift')} | {r['steps']} | {r['newton_total']} |")
    return "\n".join(lines) + "\n"


def main():
    import logging

    logging.getLogger().setLevel(logging.WARNING)
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--meshes", nargs="+", default=["16x4", "32x8"], help="N x M of the quarter mesh")
    p.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    p.add_argument("--eps-t-study", action="store_true", help="also other ε_T on the coarsest mesh")
    p.add_argument("--out", default=str(ROOT / "bench" / "results" / "punch_friction"))
    p.add_argument("--reuse", action="store_true",
                   help="take the runs already finished in --out from their summary.json instead of running them")
    p.add_argument("--report", action="store_true",
                   help="only rewrite the table and curves.png from the runs already in --out")
    args = p.parse_args()
    out = Path(args.out)
    if args.report:
        rows = json.loads((out / "punch_friction.json").read_text())
        write_report(rows, out)
        return
    rank0 = MPI.COMM_WORLD.rank == 0
    rows = []
    meshes = [tuple(int(v) for v in mesh.split("x")) for mesh in args.meshes]
    for n, m in meshes:
        sims = []
        for case in args.cases:
            row, sim, writer = run(case, n, m, out, reuse=args.reuse)
            rows.append(row)
            sims.append(sim)
            if rank0:
                print(f"{case:>14} {row['mesh']:>8}: {row['status']}, force {row['punch_force']:.2f} N, "
                      f"edge {row['edge_uplift']:.4f} mm, corner {row['corner_uplift']:.4f} mm, "
                      f"{row['steps']} steps, its {row['newton_per_step']}, order {row['order_median']}, "
                      f"{row['wall_time']:.0f} s", flush=True)
        if (n, m) == meshes[-1] and all(r["status"] == "completed" for r in rows[-len(sims):]):
            if all(sim is not None for sim in sims):
                draw_uz(sims, rows[-len(sims):], out)
            elif rank0:
                print("uz pictures kept as they are (runs reused)")
        del sims
    if args.eps_t_study:
        n, m = meshes[0]
        for case, eps in [("punch_mu0.3_0", 100), ("punch_mu1_0", 100), ("punch_mu0_1", 30), ("punch_mu0_1", 100)]:
            contact = 0 if CASES[case][0] > 0 else 1
            # steps.min: a case that converges only with tiny steps is reported as failed, not crawled through
            row, _, _ = run(case, n, m, out, [f"contact.{contact}.eps_t={eps}", "steps.min=0.005"], reuse=args.reuse)
            rows.append(row)
            if rank0:
                print(f"{case:>14} ε_T = {eps}: {row['status'][:80]}, force {row['punch_force']:.2f} N, "
                      f"{row['steps']} steps, {row['newton_total']} its", flush=True)
    if rank0:
        write_report(rows, out)


def write_report(rows, out):
    """punch_friction.md beside the results folder, curves.png and
    punch_friction.json (with the order statistics) in it."""
    for r in rows:
        steps = json.loads((out / folder(r["case"], r["mesh"], r["extra"]) / "summary.json").read_text())["steps"]
        if steps:
            r["orders"] = order_statistics(steps, frictional_steps(steps) if any(CASES[r["case"]]) else range(len(steps)))
            r["order_median"] = float(np.median(r["orders"]["residual"]["all"])) if r["orders"]["residual"]["all"] else None
    (out / "punch_friction.json").write_text(json.dumps(rows, indent=1))
    draw_curves(rows, out / "curves.png")
    md = markdown(rows, out)
    rel = out.name
    pictures_md = "\n".join(f"![uz {c}]({rel}/uz_{c}.png)" for c in CASES if (out / f"uz_{c}.png").is_file())
    (out.parent / "punch_friction.md").write_text(
        "# The punch with friction (bench/punch_friction.py)\n\n"
        "Full indentation 2 mm; forces for the whole plate; uplift = uz at the bottom of the plate at "
        "(40, 0, 0) (edge) and (40, 40, 0) (corner); in brackets the change against (0, 0) on the same mesh. "
        "ε_T = 10 N/mm³, ε_N = 100 N/mm³, full Newton steps (the scenes' settings). Time in seconds, one "
        "process, on a machine shared with other jobs (compare times within a table, not to the second).\n\n"
        + md + f"\n![curves]({rel}/curves.png)\n\n" + pictures_md + "\n")
    print(md)


if __name__ == "__main__":
    main()
