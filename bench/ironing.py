"""Ironing benchmark (Puso & Laursen 2004, 3D) with Coulomb friction, the die
deformable (faceted, node-to-surface) or a smooth rigid cylinder.

    .venv/bin/python bench/ironing.py --die rigid --eps-t 5      # bench/results/ironing_rigid.md
    .venv/bin/python bench/ironing.py [--n 18 --m 6 --die-n 16] [--press-steps 10 --slide-steps 40]
                                      [--eps-n 50 --eps-t 50] [--steady-from 1.5]
                                      [--max-it-slide 12 --stall-tol 0.2] [--linesearch-slide basic]
    .venv/bin/python bench/ironing.py --analyse bench/results/ironing.json   # re-report a (partial) run

scenes/ironing.toml holds the slab, the die (as a box body), the contact
(slave: slab top, master: die outer surface, μ = 0.3) and the bcs. This
driver maps the die box onto a half-cylindrical shell (outer radius 3, wall
0.2, width 5.2, axis along y at x = 2.5, z = 6) and runs two phases through
the Python API (hypercontact.phases): press the die's inner surface 1.4 down,
then slide it 4 along x. Writes bench/results/ironing.md, ironing.json and
ironing.png (reaction forces on the die along the path); the rows so far are
rewritten to ironing.json after every converged step (a run stopped early
can be reported with --analyse). Progress (steps, Newton iterations,
cut-backs) goes to stdout. Reports, asserts nothing.
"""
import argparse
import json
import re
import time
import tomllib
from pathlib import Path

import numpy as np
from mpi4py import MPI

from hypercontact import _dolfinx as dfx
from hypercontact import scene
from hypercontact.phases import run_phase
from hypercontact.simulation import Simulation
from hypercontact.solve.newton_solver import NewtonSolver

ROOT = Path(__file__).resolve().parents[1]
RADIUS, WALL, AXIS_X, AXIS_Z = 3.0, 0.2, 2.5, 6.0
PRESS, SLIDE, MU = 1.4, 4.0, 0.3


def bend_die(body):
    """The scene's die box mapped onto the half-cylindrical shell."""
    x = body.mesh.geometry.x
    die = x[:, 2] > 5.0  # the die box sits at z in [10, 10.2]; the slab below z = 3
    a = x[die, 0]  # 0 … 1 around the half circle
    r = RADIUS - WALL + (x[die, 2] - 10.0)  # box z = 10 inner, 10.2 outer
    theta = 2.0 * np.pi - np.pi * a  # 2π → π: the lower half, orientation kept
    x[die, 0] = AXIS_X + r * np.cos(theta)
    x[die, 2] = AXIS_Z + r * np.sin(theta)


def accept_stalled(stall_tol):
    """NewtonSolver.solve, plus a fallback: node-to-surface against the
    faceted die has force jumps where a penetrated slave node crosses a die
    facet edge (the normal turns by the facet angle), so Newton can stall at
    |R| of the order p_N·w·Δθ without reaching the tolerance; such an iterate
    is accepted when |R| ≤ stall_tol and reported ("ACCEPTED_STALLED" with
    its |R| in the step log)."""
    solve = NewtonSolver.solve

    def solve_accepting_stalled(self):
        ok, its, norms, reason = solve(self)
        last = float(norms[-1]) if len(norms) else np.inf
        model = self.model
        if (not ok and reason in ("DIVERGED_MAX_IT", "DIVERGED_LINE_SEARCH") and np.isfinite(last)
                and last <= stall_tol
                and model.comm.allreduce(int(np.all(np.isfinite(model.problem.x.array))), op=MPI.MIN)):
            model.problem.x.copy(model.w.vector)
            dfx.update_ghosts(model.w)
            model.sync_displacement()
            return True, its, norms, "ACCEPTED_STALLED"
        return ok, its, norms, reason

    NewtonSolver.solve = solve_accepting_stalled


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--die", choices=("deformable", "smooth", "rigid"), default="deformable",
                    help="deformable: the faceted stiff shell of the scene (node-to-surface); smooth: the same "
                         "shell as a smooth master (master_surface = \"smooth\"); rigid: a smooth rigid "
                         "cylinder of the same outer radius (obstacle = \"cylinder\")")
    ap.add_argument("--n", type=int, default=18, help="slab cells along x and y")
    ap.add_argument("--m", type=int, default=6, help="slab cells through the thickness")
    ap.add_argument("--die-n", type=int, default=16, help="die cells around the half circle and across")
    ap.add_argument("--press-steps", type=int, default=10)
    ap.add_argument("--slide-steps", type=int, default=40)
    ap.add_argument("--eps-n", type=float, default=50.0, help="normal penalty")
    ap.add_argument("--eps-t", type=float, default=50.0, help="tangential penalty")
    ap.add_argument("--steady-from", type=float, default=1.5, help="slide distance where steady sliding is taken to start")
    ap.add_argument("--linesearch-press", default="auto", help="SNES line search of the press phase (auto: bt)")
    ap.add_argument("--linesearch-slide", default="auto", help="SNES line search of the slide phase (auto: bt)")
    ap.add_argument("--max-it", type=int, default=25, help="Newton iterations per step before a cut-back (press)")
    ap.add_argument("--max-it-slide", type=int, default=25, help="the same in the slide phase")
    ap.add_argument("--rtol", type=float, default=1e-10, help="Newton: |R| ≤ rtol × |R| of the step's first iterate")
    ap.add_argument("--atol", type=float, default=1e-10, help="Newton: or |R| ≤ atol")
    ap.add_argument("--stall-tol", type=float, default=None,
                    help="accept a Newton solve that stalls (max_it reached) with |R| ≤ this; reported per step")
    ap.add_argument("--verbose-failures", action="store_true",
                    help="print the residual norms and active sets of failed Newton solves")
    ap.add_argument("--analyse", default=None, help="only re-report this ironing.json (no run)")
    ap.add_argument("--out", default=str(ROOT / "bench" / "results"))
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.analyse:
        summary = json.loads(Path(args.analyse).read_text())
        report(summary, out, args.steady_from)
        return
    rigid = args.die == "rigid"
    if rigid:
        sc = scene.load(rigid_die_scene(), overrides=[f"mesh.n={args.n}", f"mesh.m={args.m}",
                                                      f"contact.0.eps_n={args.eps_n}", f"contact.0.eps_t={args.eps_t}"])
    else:
        sc = scene.load(ROOT / "scenes" / "ironing.toml",
                        overrides=[f"mesh.n={args.n}", f"mesh.m={args.m}", f"body.0.n={args.die_n}",
                                   f"contact.0.eps_n={args.eps_n}", f"contact.0.eps_t={args.eps_t}",
                                   f"contact.0.master_surface={'smooth' if args.die == 'smooth' else 'faceted'}"])
    comm = MPI.COMM_WORLD
    rows = []
    t0 = time.perf_counter()
    pending_cuts = [0]

    def log(msg="", *a, **k):
        # the step log: Newton iterations and cut-backs go into the rows (record() runs before the step line)
        m = re.match(r"step\s+\d+\s+λ = \S+\s+Newton\s+(\d+)\s+\|R\| = (\S+)\s+\((\w+)\)", str(msg))
        if m and rows:
            rows[-1]["newton"] = int(m.group(1))
            rows[-1]["residual"] = float(m.group(2))
            rows[-1]["reason"] = m.group(3)
            rows[-1]["cutbacks"] = pending_cuts[0]
            rows[-1]["wall"] = time.perf_counter() - t0
            pending_cuts[0] = 0
            dump()
        elif "cut back" in str(msg):
            pending_cuts[0] += 1
            if args.verbose_failures and comm.rank == 0:
                norms = sim.snes.getConvergenceHistory()[0]
                print("   residual norms:", " ".join(f"{v:.2e}" for v in norms[:sim.snes.getIterationNumber() + 1]))
                print("   active sets (closed, Σ(closed idx + facet), slipping):",
                      [a[0] for a in sim.newton.history.active_sets[-8:]], flush=True)
        if comm.rank == 0:
            print(f"[{time.perf_counter() - t0:7.1f} s] {msg}", flush=True)

    sim = Simulation(sc, comm, log=log, map_mesh=None if rigid else bend_die)
    if args.stall_tol is not None:
        accept_stalled(args.stall_tol)
    c = sim.contacts[0]
    work = Path("/tmp") / f"ironing_{args.die}_{args.n}x{args.m}"
    die = "rigid cylinder (smooth)" if rigid else f"die {args.die_n}x{args.die_n}x1"
    meta = {"die": args.die, "mesh": f"slab {args.n}x{args.n}x{args.m} hexahedra, {die}",
            "n": args.n, "m": args.m, "die_n": args.die_n, "press_steps": args.press_steps,
            "slide_steps": args.slide_steps, "linesearch": [args.linesearch_press, args.linesearch_slide],
            "max_it": [args.max_it, args.max_it_slide], "rtol": args.rtol, "atol": args.atol, "stall_tol": args.stall_tol, "eps_n": args.eps_n, "eps_t": args.eps_t, "ranks": comm.size}

    def dump(status="running"):
        if comm.rank == 0:
            summary = dict(meta, status=status, wall_s=time.perf_counter() - t0, rows=rows)
            (out / f"{stem_of(args.die)}.json").write_text(json.dumps(summary, indent=1))

    def record(phase, s):
        st = c.law.committed
        F = -comm.allreduce(np.asarray(st.force), op=MPI.SUM)  # on the die = −(on the slab)
        Fn = -comm.allreduce(np.asarray(st.normal_force), op=MPI.SUM)  # its normal-pressure part
        p, area = np.asarray(st.pressure), c.geometry.point_area
        N = comm.allreduce(float(np.sum(area * p)), op=MPI.SUM)
        state = np.asarray(st.state)
        slip = state == 2
        t_abs = np.linalg.norm(np.asarray(st.traction), axis=1)
        wt = comm.allreduce(float(np.sum((area * t_abs)[slip])), op=MPI.SUM)
        wp = comm.allreduce(float(np.sum((area * p)[slip])), op=MPI.SUM)
        rows.append({"phase": phase, "s": s, "Fx": F[0], "Fy": F[1], "Fz": F[2], "N": N,
                     "stick": int(comm.allreduce(np.count_nonzero(state == 1), op=MPI.SUM)),
                     "slip": int(comm.allreduce(np.count_nonzero(slip), op=MPI.SUM)),
                     "slip_t": wt, "slip_pN": wp, "dissipation": c.law.dissipation,
                     "Fx_normal": Fn[0], "Fz_normal": Fn[2], "Fx_friction": F[0] - Fn[0], "Fz_friction": F[2] - Fn[2]})

    def phase(name, motion, steps, s0, s1, linesearch, max_it):
        # fixed step 1/steps; after a cut-back the step grows back (×2 per converged step) to 1/steps
        sim.scene["steps"].update(initial=1.0 / steps, max=1.0 / steps, growth=2.0,
                                  grow_below=sim.scene["solver"]["max_it"])
        sim.scene["solver"].update(linesearch=linesearch, max_it=max_it, rtol=args.rtol, atol=args.atol)  # read by each run's SNES
        orig = c.commit

        def commit():
            orig()
            record(name, s0 + c.geometry.load_factor * (s1 - s0))

        c.commit = commit
        try:
            if rigid:  # the obstacle moves by this phase's increment
                run_phase(sim, {}, work / name, obstacle_motions={0: np.asarray(motion) - moved[0]})
                moved[0] = np.asarray(motion, dtype=float)
            else:
                run_phase(sim, {1: motion}, work / name)
        finally:
            del c.commit

    moved = [np.zeros(3)]  # rigid die: its displacement at the end of the last phase
    status = "completed"
    try:
        phase("press", [0.0, 0.0, -PRESS], args.press_steps, 0.0, PRESS, args.linesearch_press, args.max_it)
        phase("slide", [SLIDE, 0.0, -PRESS], args.slide_steps, 0.0, SLIDE, args.linesearch_slide, args.max_it_slide)
    except Exception as e:  # a step that does not converge: report what was reached
        status = f"stopped: {type(e).__name__}: {e}"
        log(status)
    dump(status)
    if comm.rank:
        return
    report(json.loads((out / f"{stem_of(args.die)}.json").read_text()), out, args.steady_from)


def stem_of(die):
    """The results' file stem of a die kind."""
    return {"rigid": "ironing_rigid", "smooth": "ironing_smooth"}.get(die, "ironing")


def rigid_die_scene():
    """scenes/ironing.toml with the die replaced by a rigid cylinder of the
    die's outer radius, axis along y through (2.5, ·, 6), touching the slab's
    top along x = 2.5 (the slab is the only body; no die bc)."""
    data = tomllib.loads((ROOT / "scenes" / "ironing.toml").read_text())
    del data["body"]
    data["bc"] = [bc for bc in data["bc"] if not bc["surface"].startswith("die.")]
    contact = data["contact"][0]
    del contact["master"]
    contact.update(obstacle="cylinder", point=[AXIS_X, 0.0, AXIS_Z], axis=[0.0, 1.0, 0.0], radius=RADIUS,
                   motion=[0.0, 0.0, 0.0])
    data["title"] = "Ironing with a rigid cylindrical die (bench/ironing.py --die rigid)"
    return data


def _dominant_period(s, y):
    """Wavelength (in s) of the largest Fourier component of y(s) (resampled uniformly)."""
    if len(s) < 8:
        return float("nan")
    su = np.linspace(s[0], s[-1], len(s))
    yu = np.interp(su, s, y)
    spec = np.abs(np.fft.rfft(yu - yu.mean()))
    freq = np.fft.rfftfreq(len(su), su[1] - su[0])
    k = 1 + int(np.argmax(spec[1:]))
    return float(1.0 / freq[k])


def report(summary, out, steady_from):
    rigid = summary.get("die") == "rigid"
    stem = stem_of(summary.get("die"))
    rows = summary["rows"]
    press = [r for r in rows if r["phase"] == "press"]
    slide = [r for r in rows if r["phase"] == "slide"]
    s = np.array([r["s"] for r in slide])
    Fx, Fz = np.array([r["Fx"] for r in slide]), np.array([r["Fz"] for r in slide])
    ratio = np.abs(Fx) / np.abs(Fz)
    steady = s >= steady_from
    res = {}
    if steady.sum() >= 4:
        ss = s[steady]
        res["ratio_mean"] = float(ratio[steady].mean())
        res["ratio_min"], res["ratio_max"] = float(ratio[steady].min()), float(ratio[steady].max())
        wt = sum(r["slip_t"] for r, k in zip(slide, steady) if k)
        wp = sum(r["slip_pN"] for r, k in zip(slide, steady) if k)
        res["local_ratio"] = wt / wp if wp > 0 else float("nan")
        if "Fx_normal" in slide[0]:
            for key in ("Fx_normal", "Fx_friction", "Fz_normal", "Fz_friction", "N"):
                res[f"{key}_mean"] = float(np.mean([r[key] for r, k in zip(slide, steady) if k]))
        for name, y in (("Fx", np.abs(Fx[steady])), ("Fz", np.abs(Fz[steady])), ("ratio", ratio[steady])):
            trend = np.polyval(np.polyfit(ss, y, 1), ss)
            d = y - trend
            res[f"{name}_mean"] = float(y.mean())
            res[f"{name}_slope"] = float(np.polyfit(ss, y, 1)[0])
            res[f"{name}_p2p"] = float(d.max() - d.min())
            res[f"{name}_p2p_rel"] = float((d.max() - d.min()) / y.mean())
            res[f"{name}_period"] = _dominant_period(ss, d)
            d2 = y - np.polyval(np.polyfit(ss, y, 2), ss)  # also without the slow arc of the whole window
            res[f"{name}_p2p2_rel"] = float((d2.max() - d2.min()) / y.mean())
            res[f"{name}_period2"] = _dominant_period(ss, d2)
    summary["analysis"] = res
    n, die_n = summary["n"], summary["die_n"]
    h_slab = 9.0 / n
    h_die = np.pi * RADIUS / die_n if die_n else float("nan")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(10, 3.6))
        ax[0].plot(s, Fz, "s-", ms=3, label="Fz")
        ax[0].plot(s, Fx, "^-", ms=3, label="Fx")
        ax[0].set_xlabel("slide distance s")
        ax[0].set_ylabel("reaction force on the die")
        ax[0].axvline(steady_from, color="0.6", ls=":")
        ax[0].legend(fontsize=8)
        ax[1].plot(s, ratio, "o-", ms=3, label="|Fx| / |Fz|")
        bad = np.array([r.get("reason") == "ACCEPTED_STALLED" for r in slide], bool)
        if bad.any():
            ax[0].plot(s[bad], Fx[bad], "rx", ms=6)
            ax[0].plot(s[bad], Fz[bad], "rx", ms=6, label="stalled Newton (accepted)")
            ax[1].plot(s[bad], ratio[bad], "rx", ms=6, label="stalled Newton (accepted)")
        ax[1].axhline(MU, color="k", ls="--", label="μ = 0.3")
        ax[1].axvline(steady_from, color="0.6", ls=":")
        ax[1].set_xlabel("slide distance s")
        ax[1].legend()
        fig.suptitle(f"Ironing, {summary['mesh']}, ε_N = {summary['eps_n']:g}, ε_T = {summary['eps_t']:g}",
                     fontsize=9)
        fig.tight_layout()
        fig.savefig(out / f"{stem}.png", dpi=80)
    except ImportError:
        pass
    stalled = [r for r in rows if r.get("reason") == "ACCEPTED_STALLED"]
    its_p = [r.get("newton") for r in press]
    its_s = [r.get("newton") for r in slide]
    cuts = sum(r.get("cutbacks", 0) for r in rows)
    lines = [
        "# Ironing benchmark (Puso & Laursen 2004, 3D)", "",
        "Generated by `bench/ironing.py" + ("" if summary.get("die", "deformable") == "deformable" else f" --die {summary['die']}") + "` (scene `scenes/ironing.toml`).", "",
        f"- Slab 9 × 4 × 3, neo-Hookean E = 1, ν = 0.3, bottom fixed; mesh {summary['mesh']}.",
        *(["- Die: rigid circular cylinder, radius 3 (the shell's outer surface), axis along y, moved as a whole.",
            "- Contact: node to rigid surface, slave = slab top (nodal areas),"] if rigid else [
            "- Die: half-cylindrical shell, outer radius 3, wall 0.2, width 5.2 (box body mapped by the",
            "  driver), neo-Hookean E = 1000, ν = 0.3, driven through its inner surface.",
            "- Contact: single pass node-to-surface, slave = slab top, master = die outer surface,"]),
        f"  ε_N = {summary['eps_n']:g}, ε_T = {summary['eps_t']:g}, μ = {MU}; Newton (MUMPS LU; settings below).",
        f"- Path: press {PRESS} in {summary['press_steps']} steps, then slide {SLIDE} in {summary['slide_steps']} steps.",
        f"- Status: **{summary['status']}**; slide reached s = {s[-1] if len(s) else 0:.3f}; "
        f"wall time {summary['wall_s']:.0f} s on {summary['ranks']} rank(s); {cuts} cut-back(s).",
        f"- Newton: SNES line search (press, slide) = {summary.get('linesearch')}, max_it {summary.get('max_it')}, "
        f"rtol {summary.get('rtol')}, atol {summary.get('atol')}; stalled solves accepted at |R| ≤ "
        f"{summary.get('stall_tol')}: {len(stalled)} step(s)"
        + (", |R| = " + ", ".join(f"{r['residual']:.2g}" for r in stalled) + " (at s = "
           + ", ".join(f"{r['s']:.3f}" for r in stalled) + ")." if stalled else "."), ""]
    if res:
        lines += [
            "## Steady sliding", "",
            f"- Window s ≥ {steady_from} ({int(steady.sum())} steps, s = {s[steady][0]:.3f} … {s[steady][-1]:.3f}).",
            f"- Global |Fx|/|Fz| = {res['ratio_mean']:.4f} (min {res['ratio_min']:.4f}, max {res['ratio_max']:.4f}), "
            f"μ = {MU}: difference {res['ratio_mean'] - MU:+.4f} ({100 * (res['ratio_mean'] - MU) / MU:+.1f} %).",
            f"- Local check over slipping points, Σ w|t| / Σ w p_N = {res['local_ratio']:.6f}.",
            f"- |Fx| = {res['Fx_mean']:.4g} (trend {res['Fx_slope']:+.3g} per unit s), detrended peak-to-peak "
            f"{res['Fx_p2p']:.3g} = {100 * res['Fx_p2p_rel']:.2f} % of the mean, dominant period {res['Fx_period']:.3g}.",
            f"- |Fz| = {res['Fz_mean']:.4g} (trend {res['Fz_slope']:+.3g} per unit s), detrended peak-to-peak "
            f"{res['Fz_p2p']:.3g} = {100 * res['Fz_p2p_rel']:.2f} % of the mean, dominant period {res['Fz_period']:.3g}.",
            f"- Ratio: detrended peak-to-peak {res['ratio_p2p']:.3g} = {100 * res['ratio_p2p_rel']:.2f} % of the mean.",
            f"- With a quadratic trend removed instead (the slow arc of the window): peak-to-peak Fx "
            f"{100 * res['Fx_p2p2_rel']:.2f} %, Fz {100 * res['Fz_p2p2_rel']:.2f} %, ratio {100 * res['ratio_p2p2_rel']:.2f} % "
            f"of the mean; dominant periods {res['Fx_period2']:.3g}, {res['Fz_period2']:.3g}, {res['ratio_period2']:.3g}.",
            f"- Length scales: slab element along x 9/{n} = {h_slab:.3f}"
            + ("." if rigid else f"; die facet arc length π·3/{die_n} = {h_die:.3f}."),
            ""]
        if "Fx_normal_mean" in res:
            lines[-1:-1] = [
                f"- Split of the mean force on the die in the window: Fx = {res['Fx_normal_mean']:.4g} (normal pressure) "
                f"{res['Fx_friction_mean']:+.4g} (friction); Fz = {res['Fz_normal_mean']:.4g} (normal) "
                f"{res['Fz_friction_mean']:+.4g} (friction); Σ w p_N = {res['N_mean']:.4g}; "
                f"|Fx friction| / Σ w p_N = {abs(res['Fx_friction_mean']) / res['N_mean']:.4f}."]
    lines += [
        f"- Newton iterations per step: press {its_p}, slide {its_s}"
        + (f" (mean {np.mean([i for i in its_s if i is not None]):.1f})." if any(i is not None for i in its_s) else "."),
        "", f"![reaction forces]({stem}.png)", "",
        "| phase | s | Fx | Fy | Fz | abs(Fx/Fz) | Σ w p_N | stick | slip | Newton | final abs(R) | cuts | dissipation |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    lines += [f"| {r['phase']} | {r['s']:.3f} | {r['Fx']:.5g} | {r['Fy']:.3g} | {r['Fz']:.5g} | "
              f"{abs(r['Fx'] / r['Fz']) if r['Fz'] else 0:.4f} | {r['N']:.5g} | "
              f"{r['stick']} | {r['slip']} | {r.get('newton', '')} | "
              f"{r.get('residual', float('nan')):.1e}{' (stalled)' if r.get('reason') == 'ACCEPTED_STALLED' else ''} | "
              f"{r.get('cutbacks', '')} | {r['dissipation']:.4g} |"
              for r in rows]
    lines[lines.index(f"![reaction forces]({stem}.png)"):lines.index(f"![reaction forces]({stem}.png)")] = [
        "## Notes", "",
        "- Why the global ratio is not μ: the die's Fx and Fz are sums over the whole contact zone of the",
        "  normal pressure *and* the friction traction, and the die surface is inclined (a cylinder): on its",
        "  leading side the normal pressure has an x-component that resists the motion (ploughing the",
        "  bow wave of the soft slab), and the friction traction on an inclined facet has a z-component.",
        "  So |Fx/Fz| differs from μ even when every closed node slides with |t| = μ p_N; the local check",
        "  (Σ w|t| / Σ w p_N over slipping points) is μ by construction of the return mapping. The",
        "  'friction' part of Fx divided by Σ w p_N (above) is below μ where not every closed point slips",
        "  and because the tractions follow the inclined die surface (not all along x). A finite ε_T only delays the onset of sliding at a point by",
        "  a tangential elastic slip μ p_N / ε_T (here p_N ≲ 1, so ≲ 0.006): the slow rise of the ratio over",
        "  the first ~1 of slide is the shear compliance of the slab (E = 1), not the penalty.",
        "- Oscillations: with node-to-surface contact the forces jump when slab (slave) nodes cross the die's",
        "  facet edges (the normal turns by π/die_n) and when slab nodes enter or leave the contact zone",
        "  (period = slab element length along x). Their amplitude is the detrended peak-to-peak above; the",
        "  sampling (one point per slide step) cannot resolve periods below ~2 steps.",
        "- Newton: at some positions a penetrated slab node sits at a die facet edge, where the node-to-surface",
        "  force is discontinuous; the backtracking line search then stalls at a residual of the order",
        "  p_N·w·Δθ (~1e-2 … 1e-1 here) with the active-set signature unchanged, for any step size (cut back to",
        "  Δλ = 6.5e-5 without success), and with full Newton steps the pairing ping-pongs between two facets.",
        "  The driver accepts such stalled iterates up to |R| ≤ stall_tol and lists them (column 'final abs(R)');",
        "  those steps are not converged equilibria: treat the force at those s with an error of ~|R|.", ""]
    if rigid:  # the notes above are about the faceted die
        k = lines.index("## Notes")
        lines[k:lines.index(f"![reaction forces]({stem}.png)")] = [
            "## Notes", "",
            "- The die is a rigid circular cylinder (obstacle = \"cylinder\"): a smooth master, so no normal jumps",
            "  at facet edges. What oscillation remains comes from slab (slave) nodes entering and leaving the",
            "  contact zone one row at a time: period = slab element length along x.",
            "- Why the global ratio is not μ: the die's Fx and Fz sum the normal pressure on an inclined (curved)",
            "  surface and the friction traction; the pressure's x-component on the leading side resists the",
            "  motion. The local check Σ w|t| / Σ w p_N over slipping points is μ by construction.", ""]
    (out / f"{stem}.md").write_text("\n".join(lines) + "\n")
    (out / f"{stem}.json").write_text(json.dumps(summary, indent=1))
    print("\n".join(lines[:26]))


if __name__ == "__main__":
    main()
