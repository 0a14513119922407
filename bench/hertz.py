"""Hertz contact (scenes/hertz.toml) at several mesh levels: contact radius,
peak pressure and approach against Hertz's solution, Newton iterations and
the time split per Newton iteration.

    .venv/bin/python bench/hertz.py --level coarse        # one level → results/hertz_<level>.json
    .venv/bin/python bench/hertz.py --report              # the JSONs → bench/results/hertz.md + .png
    .venv/bin/python bench/hertz.py --pole                # single pass against two-pass at the pole

Levels scale the cell counts of both bodies (block n × n × m, ball n, m):
coarse 8/8 + 6/6, medium 12/12 + 9/9, default 16/16 + 12/12 (the scene), fine 22/22 + 16/16
(fine: > 14 min for its first load step of 21 Newton its on the shared 2-core machine, not in the report).

Hertz (closed form and profile fit in hypercontact.hertz, which the study
command's ``reference = "hertz:…"`` uses too), two identical elastic bodies
(E, ν), sphere radius R on a plane:
E* = E / (2 (1 − ν²)), a_H = (3 F R / (4 E*))^(1/3), p0_H = 3 F / (2 π a_H²),
approach of distant points δ_H = a_H² / R. F is the whole-sphere force
(4 × the quarter model's contact force of the block on the ball).

FE contact radius, from the slave (ball) nodes' *current* radial position
r = √(x² + y²):
- ``a_gap``: on the meridian y = 0 of the ball (a line of slave nodes),
  the zero of the linearly interpolated signed gap between the outermost
  closed node and the next (open) node. The nodal pressure is p = ε_N ⟨−g⟩,
  so this is where the pressure profile extended as ε_N (−g) hits 0;
- ``a_fit``: the Hertz profile p0 √(1 − r²/a²) fitted to all closed slave
  nodes by least squares on p² = p0² − (p0²/a²) r² (linear in r²), which
  also gives a fitted peak pressure ``p0_fit``.
FE peak pressure ``p_pole``: the nodal pressure at the pole node (r = 0).
Pressures are nominal (force per reference area: the nodal area is taken on
the undeformed slave surface); at a/R ≈ 0.15 the area change of the ball's
surface under the contact is of the order of the strain there, a few %·0.1
— see the report.

h at the contact: the reference spacing of the slave nodes on the meridian
around r = a (the bracket [r_closed, r_open]) and the block's top-face cell
size at x = a.
"""
import argparse
import json
import time
from pathlib import Path

import numpy as np
from mpi4py import MPI

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "bench" / "results"

LEVELS = {"coarse": (8, 8, 6, 6), "medium": (12, 12, 9, 9), "default": (16, 16, 12, 12), "fine": (22, 22, 16, 16)}
E, NU, R = 10.0, 0.3, 10.0
E_STAR = E / (2.0 * (1.0 - NU ** 2))
DRIVE = 0.3


def hertz(F):
    """(a_H, p0_H, δ_H) for the whole-sphere force F (hypercontact.hertz)."""
    from hypercontact.hertz import closed_form

    return closed_form(F, R, E_STAR)


def overrides(nb, mb, ns, ms):
    return [f"mesh.n={nb}", f"mesh.m={mb}", f"body.0.n={ns}", f"body.0.m={ms}"]


def run(nb, mb, ns, ms, out_dir, comm=MPI.COMM_WORLD, extra=()):
    """Solve the Hertz scene at the given cell counts; returns the Simulation."""
    from hypercontact import scene
    from hypercontact.simulation import Simulation

    sc = scene.load(ROOT / "scenes" / "hertz.toml", overrides(nb, mb, ns, ms) + ["output.xdmf=false", *extra])
    sim = Simulation(sc, comm, log=lambda *a, **k: None)
    writer = sim.run(out_dir=str(out_dir))
    return sim, writer


def slave_profile(sim):
    """Gathered on every rank: reference and current coordinates, gap and
    pressure of all slave nodes, and the whole-sphere force F."""
    from hypercontact.hertz import slave_points

    c = sim.contacts[0]
    X, x, gap, p = slave_points(c, sim.u)
    F = 4.0 * float(c.force(sim.u)[2])
    return X, x, gap, p, F


def contact_radius(X, x, gap, p):
    """(a_gap, bracket, h_slave, a_fit, p0_fit, p_pole) — see the module text."""
    r = np.hypot(x[:, 0], x[:, 1])
    R0 = np.hypot(X[:, 0], X[:, 1])
    line = np.flatnonzero(np.abs(X[:, 1]) < 1e-9 * R)  # meridian y = 0
    line = line[np.argsort(R0[line])]
    closed = np.flatnonzero(gap[line] < 0.0)
    k = closed.max()  # outermost closed node on the line (the pole is closed)
    i, j = line[k], line[k + 1]
    a_gap = r[i] + (r[j] - r[i]) * (-gap[i]) / (gap[j] - gap[i])
    h_slave = R0[j] - R0[i]
    from hypercontact.hertz import fit_profile

    cl = np.flatnonzero(gap < 0.0)
    a_fit, p0_fit = fit_profile(r, p, cl)
    pole = np.argmin(R0)
    return dict(a_gap=float(a_gap), bracket=[float(r[i]), float(r[j])], h_slave=float(h_slave),
                a_fit=float(a_fit), p0_fit=float(p0_fit), p_pole=float(p[pole]), pole_r=float(R0[pole]),
                n_closed=int(len(cl)))


def fit_off_planes(row):
    """(a, p0) of the Hertz profile fitted to the closed slave nodes off the
    symmetry planes (from the saved profile; closed ⇔ p > 0)."""
    rr, pp, y0 = (np.asarray(row["profile"][k]) for k in ("r", "p", "y0"))
    if "on_plane" not in row["profile"]:
        return float("nan"), float("nan")
    on = np.asarray(row["profile"]["on_plane"])
    from hypercontact.hertz import fit_profile

    return fit_profile(rr, pp, (pp > 0.0) & ~on)


def master_h(nb, a):
    """The block's top-face cell size at x = a (graded box, grading 2 towards 0)."""
    t = np.linspace(0.0, 1.0, nb + 1) ** 2.0 * 10.0
    k = np.searchsorted(t, a)
    return float(t[k] - t[k - 1])


def bench_level(name):
    nb, mb, ns, ms = LEVELS[name]
    comm = MPI.COMM_WORLD
    t0 = time.perf_counter()
    sim, writer = run(nb, mb, ns, ms, RESULTS / "hertz_runs" / name, comm)
    wall = time.perf_counter() - t0
    summary = writer.write_summary(sim.timers)
    X, x, gap, p, F = slave_profile(sim)
    aH, p0H, dH = hertz(F)
    geo = contact_radius(X, x, gap, p)
    its = summary["newton_iterations"]
    row = dict(level=name, cells=[nb, mb, ns, ms], unknowns=3 * sim.V.dofmap.index_map.size_global,
               ranks=comm.size, F=F, a_H=aH, p0_H=p0H, delta_H=dH, delta=DRIVE, **geo,
               h_master=master_h(nb, aH), steps=len(its), newton=its, newton_total=int(sum(its)),
               wall=wall, split=summary["time_split"], calls=summary.get("calls", {}),
               profile=dict(r=np.hypot(x[:, 0], x[:, 1]).tolist(), p=p.tolist(), y0=(np.abs(X[:, 1]) < 1e-9).tolist(),
                                                                               on_plane=(np.abs(X[:, :2]).min(axis=1) < 1e-9).tolist()))
    if comm.rank == 0:
        RESULTS.mkdir(parents=True, exist_ok=True)
        (RESULTS / f"hertz_{name}.json").write_text(json.dumps(row))
        print(f"{name}: F = {F:.4f} N  a_H = {aH:.4f}  a_gap = {geo['a_gap']:.4f}  a_fit = {geo['a_fit']:.4f}  "
              f"p0_H = {p0H:.4f}  p_pole = {geo['p_pole']:.4f}  p0_fit = {geo['p0_fit']:.4f}  "
              f"h = {geo['h_slave']:.3f}/{row['h_master']:.3f}  its {its}  wall {wall:.0f} s", flush=True)
    return row


def report():
    rows = [json.loads((RESULTS / f"hertz_{n}.json").read_text()) for n in LEVELS
            if (RESULTS / f"hertz_{n}.json").exists()]
    L = ["# Hertz contact: elastic hemisphere on an elastic block (scenes/hertz.toml)", "",
         "Both bodies neo-Hookean, E = 10 MPa, ν = 0.3 (E* = E/(2(1−ν²)) = %.4f MPa), R = 10 mm, "
         "the ball's flat top driven down %.1f mm; quarter model, F = 4 × the contact force of the block on "
         "the ball. Hertz: a_H = (3FR/4E*)^(1/3), p0_H = 3F/(2π a_H²), δ_H = a_H²/R. "
         "Generated by `bench/hertz.py` (serial, 2-core machine shared with other jobs: wall times are indicative)."
         % (E_STAR, DRIVE), "",
         "FE contact radius: `a_gap` = zero of the linearly interpolated signed gap between the outermost closed "
         "and the next (open) slave node on the meridian y = 0 (p = ε_N⟨−g⟩, so this is where the pressure "
         "profile extended as ε_N(−g) hits 0); `a_fit` = least-squares fit of p² = p0² (1 − r²/a²) to all "
         "closed slave nodes (r = current radial position). FE peak pressure: `p_pole` = nodal pressure at the "
         "pole, `p0_fit` from the fit. h_s = reference spacing of the slave nodes bracketing a on the meridian, "
         "h_m = the block's top cell size at x = a_H. Errors are relative to the Hertz values at the FE force.",
         "", "| level | cells block n/m, ball n/m | unknowns | F (N) | a_H (mm) | a_gap | err | a_fit | err | "
         "bracket [r_c, r_o] | h_s | h_m | p0_H (MPa) | p_pole | err | p0_fit | err | closed nodes |",
         "|" + "---|" * 18]
    off = []
    for r in rows:
        L.append(f"| {r['level']} | {r['cells'][0]}/{r['cells'][1]}, {r['cells'][2]}/{r['cells'][3]} | "
                 f"{r['unknowns']} | {r['F']:.3f} | {r['a_H']:.4f} | {r['a_gap']:.4f} | "
                 f"{100 * (r['a_gap'] / r['a_H'] - 1):+.1f} % | {r['a_fit']:.4f} | "
                 f"{100 * (r['a_fit'] / r['a_H'] - 1):+.1f} % | [{r['bracket'][0]:.3f}, {r['bracket'][1]:.3f}] | "
                 f"{r['h_slave']:.3f} | {r['h_master']:.3f} | {r['p0_H']:.4f} | {r['p_pole']:.4f} | "
                 f"{100 * (r['p_pole'] / r['p0_H'] - 1):+.1f} % | {r['p0_fit']:.4f} | "
                 f"{100 * (r['p0_fit'] / r['p0_H'] - 1):+.1f} % | {r['n_closed']} |")
        a_o, p_o = fit_off_planes(r)
        off.append(f"| {r['level']} | {a_o:.4f} | {100 * (a_o / r['a_H'] - 1):+.1f} % | {p_o:.4f} | "
                   f"{100 * (p_o / r['p0_H'] - 1):+.1f} % |")
    L += ["", "The same fit restricted to the closed slave nodes *off* the symmetry planes x = 0, y = 0 "
          "(see the remark on the symmetry-plane nodes below):", "",
          "| level | a_fit off planes | err | p0_fit off planes | err |", "|---|---|---|---|---|", *off]
    L += ["", "Approach: the drive is %.1f mm between the ball's flat top and the block's fixed base; Hertz's "
          "δ_H = a_H²/R is the approach of *distant points of two half-spaces*. δ_H comes out ~7 %% *larger* than "
          "the drive: the finite bodies are held at ~R from the contact (the fixed base 10 mm below, the driven "
          "flat top 10 mm above), which removes the far-field part of the half-spaces' compliance (their "
          "displacement decays only like 1/distance), so a given force needs less approach. This is a geometry "
          "effect of the model, not a contact error; a(F) and p(F) are what the comparison tests." % DRIVE, "",
          "| level | δ drive (mm) | δ_H = a_H²/R (mm) | a_gap²/R (mm) | δ_H / δ |", "|---|---|---|---|---|"]
    for r in rows:
        L.append(f"| {r['level']} | {r['delta']:.3f} | {r['delta_H']:.4f} | {r['a_gap'] ** 2 / R:.4f} | "
                 f"{r['delta_H'] / r['delta']:.3f} |")
    L += ["", "## Newton iterations and time split", "",
          "Per Newton iteration = the phase's total time / the total number of Newton iterations (line-search "
          "residual evaluations are included in the phase totals). 'contact' is the contact residual + tangent "
          "assembly, 'contact search' the broad/narrow phase pairing.", "",
          "| level | steps | Newton its per step | total its | wall (s) | volume assembly (s/it) | contact (s/it) | "
          "contact search (s/it) | linear solve (s/it) | contact / volume |", "|" + "---|" * 10]
    for r in rows:
        s, n = r["split"], max(r["newton_total"], 1)
        va, ca, cs, ls = (s.get(k, 0.0) / n for k in ("volume assembly", "contact", "contact search", "linear solve"))
        L.append(f"| {r['level']} | {r['steps']} | {r['newton']} | {r['newton_total']} | {r['wall']:.0f} | "
                 f"{va:.3f} | {ca:.3f} | {cs:.4f} | {ls:.3f} | {ca / va if va else float('nan'):.2f} |")
    L += ["", "## Remarks", "",
          "- **Nominal pressure.** The nodal pressure is p = ε_N⟨−g⟩ and the nodal force p·A_i with A_i the "
          "*reference* nodal area, so p is force per undeformed area. Hertz's surface strains at the centre are "
          "ε_rr = ε_θθ ≈ −(1−2ν)(1+ν) p0/(2E) ≈ −1.6 %, so the current area under the contact is ≈ 3 % smaller "
          "and the true (Cauchy) pressure ≈ 3 % above the nominal one at the centre, less towards the edge — "
          "small next to the discretisation errors below, and of the order of the finite-strain effects "
          "(a/R ≈ 0.18) that Hertz's linear theory ignores anyway.",
          "- **Slave nodes on the symmetry planes carry less pressure.** At the default mesh the nodes on "
          "x = 0 or y = 0 sit ~5–10 % below the off-plane nodes at the same radius (r ≈ 0.19: 0.525 vs 0.553 MPa; "
          "r ≈ 0.77: 0.494 vs 0.520; r ≈ 1.21: 0.421 vs 0.441), and the pole node, on both planes, 24–27 % below "
          "p0_H at *every* level — it does not converge with h (the cells at the pole are already 0.05 mm). "
          "The nodal areas there are right (checked: the pole node has exactly ¼ of its quarter cell, the "
          "plane nodes half of a full node's), so the pressure deficit is in the gap, i.e. the displacement "
          "field. Off-plane nodes follow Hertz within ~1 % for r ≥ 1 mm and ~7 % near the centre. Possible "
          "causes to investigate (not settled here): the slave meridian nodes project exactly onto the master's "
          "rim (the master block's boundary edges y = 0, x = 0 and its corner at the pole; 'rim continued by "
          "5 %' in surface_contact.py), where the projection is classified edge/vertex; or the cube-to-ball "
          "mesh of the hemisphere, whose cells along the symmetry planes differ from those on the diagonal. "
          "Hence `p_pole` is reported but not used as the FE peak pressure in the test; `p0_fit` is.",
          "- **a_gap vs a_fit.** a_gap interpolates the gap linearly between the last closed and first open "
          "meridian node; outside the contact the gap grows like (r − a)^{3/2}, so it lands near the closed "
          "node whenever the open node is far (medium: bracket [1.377, 2.167], a_gap −23 % but within one "
          "node spacing). a_fit uses every closed node and is within 1.4–5.3 % at all levels.",
          "- **Tolerance of tests/verification/test_hertz.py** (coarse mesh, block 8/8, ball 6/6): |a − a_H| ≤ h_s (the "
          "slave node spacing at the contact edge, 1.375 mm there) for a_gap and a_fit; |p0_fit/p0_H − 1| ≤ 20 % "
          "(the measured error at that mesh is −15.6 %, falling to −14.2 % and −10.5 % on the finer meshes).",
          "- **Fine level.** 22/22 + 16/16 (≈ 50 k unknowns) was started but needed > 14 min for its first load "
          "step (21 Newton iterations, MUMPS LU dominating) on the shared machine and was stopped; the "
          "refinement here is coarse → medium → default (h at the contact edge 1.375 → 0.786 → 0.638 mm)."]
    (RESULTS / "hertz.md").write_text("\n".join(L) + "\n")
    print("\n".join(L))
    plot(rows)


def plot(rows):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4), dpi=110)
    for r, col in zip(rows, ("C0", "C1", "C2")):
        rr, pp, y0 = (np.asarray(r["profile"][k]) for k in ("r", "p", "y0"))
        ax.plot(rr, pp, ".", color=col, ms=2, alpha=0.35)
        o = np.argsort(rr[y0])
        ax.plot(rr[y0][o], pp[y0][o], "o-", color=col, ms=3, lw=1, label=f"FE {r['level']} (meridian y=0)")
        s = np.linspace(0.0, r["a_H"], 200)
        ax.plot(s, r["p0_H"] * np.sqrt(1 - (s / r["a_H"]) ** 2), "--", color=col, lw=1,
                label=f"Hertz at F = {r['F']:.1f} N")
    ax.set_xlim(0, 1.6 * max(r["a_H"] for r in rows))
    ax.set_xlabel("current radial position r (mm)")
    ax.set_ylabel("nodal contact pressure (MPa, nominal)")
    ax.legend(fontsize=7)
    ax.set_title("Hertz: pressure profile, FE vs analytic")
    fig.tight_layout()
    fig.savefig(RESULTS / "hertz.png")


def pole_study():
    """The pole's pressure on the default mesh, single pass against two-pass (the traction of
    all passes at the ball's slave nodes, hypercontact.hertz.vertical_tractions), and in the
    single-pass solution the block's surface nodes that lie inside the ball (the second
    pass's gaps evaluated there without applying them) → bench/results/hertz_pole.md."""
    from hypercontact import scene
    from hypercontact.hertz import fit_profile, vertical_tractions
    from hypercontact.simulation import Simulation

    import tempfile

    work = Path(tempfile.mkdtemp(prefix="hertz_pole_"))
    rows, single = [], None
    for passes in (1, 2):
        t0 = time.perf_counter()
        sim, writer = run(*LEVELS["default"], work / f"p{passes}", MPI.COMM_SELF, extra=[f"contact.0.passes={passes}"])
        wall = time.perf_counter() - t0
        X, x, t = vertical_tractions(sim, "hertz")
        # the block's force on the ball: the first pass's, less the second pass's (the ball on the block)
        F = 4.0 * sum(float(c.force(sim.u)[2]) * (1 if c.name == "hertz" else -1) for c in sim.contacts)
        r, R0 = np.hypot(x[:, 0], x[:, 1]), np.hypot(X[:, 0], X[:, 1])
        pole = int(np.argmin(R0))
        closed = np.isfinite(t) & (t > 0)
        a_fit, p0_fit = fit_profile(r, t, closed)
        a_H, p0_H, _ = hertz(abs(F))
        rows.append(dict(passes=passes, F=F, p0_H=p0_H, pole=float(t[pole]), p0_fit=p0_fit, a_fit=a_fit, a_H=a_H,
                         closed=int(closed.sum()), newton=sum(s["newton_iterations"] for s in writer.steps),
                         steps=len(writer.steps), wall=wall))
        if passes == 1:
            single = sim
    # the single-pass solution seen by a second pass: block nodes inside the ball's facets
    sc = scene.load(ROOT / "scenes" / "hertz.toml", overrides(*LEVELS["default"]) +
                    ["output.xdmf=false", "contact.0.passes=2", f"output.dir={work / 'probe'}"])
    probe = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    probe.u.x.array[:] = single.u.x.array
    probe.model.update_pairing(True)
    second = probe.contacts[1]
    gap = np.asarray(second.evaluate(probe.u).gap)
    Xb = second.geometry.X[second.geometry.point_nodes[:, 0]]
    inside = gap < 0
    ball_gap = np.asarray(single.contacts[0].evaluate(single.u).gap)
    lines = ["| passes | F (N) | p0_H (MPa) | pole traction | err | p0_fit | err | a_fit (mm) | err | closed ball nodes | "
             "steps | Newton its | wall (s) |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for q in rows:
        lines.append(f"| {q['passes']} | {q['F']:.4f} | {q['p0_H']:.4f} | {q['pole']:.4f} | "
                     f"{100 * (q['pole'] / q['p0_H'] - 1):+.1f} % | {q['p0_fit']:.4f} | "
                     f"{100 * (q['p0_fit'] / q['p0_H'] - 1):+.1f} % | {q['a_fit']:.4f} | "
                     f"{100 * (q['a_fit'] / q['a_H'] - 1):+.1f} % | {q['closed']} | {q['steps']} | {q['newton']} | "
                     f"{q['wall']:.0f} |")
    lines += ["", f"Single pass, the block's top-surface nodes inside the ball's facets: {int(inside.sum())} "
              f"(all within r = {np.hypot(Xb[inside, 0], Xb[inside, 1]).max():.3f} mm of the pole), the deepest "
              f"{-gap.min():.2e} mm; the ball's nodes' deepest penetration into the block {-ball_gap.min():.2e} mm. "
              "Slave (ball) node spacing at the pole "
              f"{np.sort(np.hypot(*single.contacts[0].geometry.X[single.contacts[0].geometry.point_nodes[:, 0]][:, :2].T))[1]:.3f} mm, "
              f"master (block) {np.sort(np.unique(np.round(np.hypot(Xb[:, 0], Xb[:, 1]), 6)))[1]:.3f} mm."]
    (RESULTS / "hertz_pole.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


def main():
    import logging

    logging.getLogger().setLevel(logging.WARNING)
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--level", choices=list(LEVELS), action="append", default=[])
    p.add_argument("--report", action="store_true")
    p.add_argument("--pole", action="store_true", help="the pole's pressure, single pass against two-pass "
                                                       "→ bench/results/hertz_pole.md")
    args = p.parse_args()
    if args.pole:
        pole_study()
    for name in args.level:
        bench_level(name)
    if args.report and MPI.COMM_WORLD.rank == 0:
        report()


if __name__ == "__main__":
    main()
