"""Hertz's closed form element by element: the rigid sphere of
tests/verification/test_rigid_sphere.py (R = 1, pressed d = 0.0025 R into a
neo-Hookean block E = 1, ν = 0.3, 40 a wide and deep, graded ∝ t³ towards
the contact, quarter model, frictionless, automatic penalty, one load step)
on trilinear and triquadratic hexahedra (Q1, Q2) and linear and quadratic
tetrahedra (P1, P2: the graded box split into six tetrahedra per cell), with
the contact integration that ``integration = "auto"`` takes (nodal, Gauss
points on 6-node triangles) and the other one where it tells something.

    .venv/bin/python bench/hertz_elements.py     # → bench/results/hertz_elements.md, .json, .png

Hertz, a rigid sphere pressed d into an elastic half-space (E* = E/(1 − ν²)):
a = √(R d), F_H = (4/3) E* √R d^{3/2} and the pressure p0 √(1 − r²/a²), whose
integral F = (2/3) π a² p0 gives p0 = 3 F_H/(2π a²) = 2 E* a/(π R) (F_H
written with d = a²/R). Per run: F/F_H − 1 (F the whole-sphere force, 4 ×
the quarter's), the contact radius from the slave points (the radius of the
outermost closed point r_closed, a lower bound; a_fit, the Hertz profile
fitted to the closed points' pressures, hypercontact.hertz.fit_profile,
where the fitted pressure falls to zero) against a, the peak pressure (the
largest slave point pressure p_max, nominal: per reference area; p0_fit)
against p0, wall time (the whole run: mesh, forms from the cache, Newton),
Newton iterations, unknowns. One thread, one run each, on a machine shared
with other jobs: wall-time ratios are what to read. A benchmark reports; it
asserts nothing (the test is tests/verification/test_rigid_sphere.py)."""
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from mpi4py import MPI

from elements import ELEMENTS, plot
from hypercontact import _dolfinx as dfx
from hypercontact import scene
from hypercontact.hertz import fit_profile, slave_points
from hypercontact.simulation import Simulation

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "bench" / "results"
sys.path[:0] = [str(ROOT / "tests" / "verification"), str(ROOT / "tests")]
from test_rigid_sphere import A_HERTZ, DEPTH, E_STAR, R, hertz_force, indentation  # noqa: E402

P0_HERTZ = 2.0 * E_STAR * A_HERTZ / (math.pi * R)
#: (element, integration) → cells per edge. Sized so that the whole ladder takes ~5 min here: Q2 at 12
#: cells (47 k unknowns) needed > 3 min (Newton failed at Δλ = 1 and 0.5, 25 iterations each, MUMPS 2 s
#: per solve), P2 at 12 cells > 5 min (stopped): not in the ladder.
LADDER = {
    ("Q1", "nodal"): [8, 12, 16, 20],
    ("Q2", "nodal"): [4, 6, 8, 10],
    ("Q2", "gauss"): [6, 8],
    ("P1", "nodal"): [8, 12, 16, 20],
    ("P2", "gauss"): [4, 6, 8],
    ("P2", "nodal"): [6, 8],
}


def run(element, integration, n):
    cells, degree, formulation = ELEMENTS[element]
    data = indentation(f"/tmp/bench_hertz_elements/{element}_{integration}_{n}", n)
    data["mesh"]["cells"] = cells
    data["discretisation"] = {"degree": degree, "formulation": formulation}
    data["contact"][0]["integration"] = integration
    t = time.perf_counter()
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=lambda *a, **k: None)
    writer = sim.run(out_dir=data["output"]["dir"])
    wall = time.perf_counter() - t
    contact = sim.contacts[0]
    F = 4.0 * abs(float(contact.force(sim.u)[2]))
    X, x, gap, p = slave_points(contact, sim.u)
    r = np.hypot(x[:, 0], x[:, 1])
    closed = gap <= 0.0
    a_fit, p0_fit = fit_profile(r, p, closed)
    return {"element": f"{element} {integration}", "n": n, "cells_across_a": n * (A_HERTZ / (40 * A_HERTZ)) ** (1 / 3),
            "unknowns": dfx.num_global_dofs(sim.w.function_space), "force": F, "error": F / hertz_force(DEPTH) - 1.0,
            "wall_s": wall, "newton": sum(s["newton_iterations"] for s in writer.steps), "steps": len(writer.steps),
            "load_factor": writer.steps[-1]["load_factor"], "closed_points": int(closed.sum()),
            "penetration": float(-gap.min() / DEPTH), "r_closed": float(r[closed].max()), "a_fit": a_fit,
            "p_max": float(p.max()), "p0_fit": p0_fit}


def report(rows):
    lines = ["# Hertz's closed form, element by element: a rigid sphere indenting a block", "",
             "`bench/hertz_elements.py`: the problem of `tests/verification/test_rigid_sphere.py` (R = 1, "
             "d = 0.0025 R, E = 1, ν = 0.3, block 40 a graded ∝ t³, quarter model, frictionless, automatic "
             "penalty, one load step; the controller cuts it when Newton fails). Hertz: a = √(R d) = "
             f"{A_HERTZ:.4g}, F_H = (4/3) E* √R d^(3/2) = {hertz_force(DEPTH):.5g}, p0 = 3 F_H/(2π a²) = "
             f"2 E* a/(π R) = {P0_HERTZ:.5g}. Slave points: nodes (nodal) or facet Gauss points (gauss). "
             "r_closed: radius of the outermost closed slave point; a_fit, p0_fit: the Hertz profile fitted to "
             "the closed points' pressures; p_max: the largest slave-point pressure (nominal). Whole-run wall "
             "times, one thread, on a 2-core machine shared with other jobs.", "",
             "| element | n | cells across a | unknowns | F/F_H − 1 | wall s | Newton (steps) | closed | "
             "r_closed/a | a_fit/a | p_max/p0 | p0_fit/p0 |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['element']} | {r['n']} | {r['cells_across_a']:.1f} | {r['unknowns']} | "
                     f"{100 * r['error']:+.2f} % | {r['wall_s']:.1f} | {r['newton']} ({r['steps']}) | "
                     f"{r['closed_points']} | {r['r_closed'] / A_HERTZ:.3f} | {r['a_fit'] / A_HERTZ:.3f} | "
                     f"{r['p_max'] / P0_HERTZ:.3f} | {r['p0_fit'] / P0_HERTZ:.3f} |")
    return "\n".join(lines) + "\n"


def main():
    import logging

    logging.getLogger().setLevel(logging.WARNING)
    rows = []
    for (element, integration), sizes in LADDER.items():
        for n in sizes:
            rows.append(run(element, integration, n))
            print({k: (round(v, 5) if isinstance(v, float) else v) for k, v in rows[-1].items()}, flush=True)
    OUT.mkdir(parents=True, exist_ok=True)
    results = {"Hertz, rigid sphere on a graded block (force error F/F_H − 1)": {"rows": rows}}
    (OUT / "hertz_elements.json").write_text(json.dumps({"a": A_HERTZ, "F_H": hertz_force(DEPTH), "p0": P0_HERTZ,
                                                         "rows": rows}, indent=1))
    (OUT / "hertz_elements.md").write_text(report(rows))
    plot(results, OUT / "hertz_elements.png")
    print(report(rows))


if __name__ == "__main__":
    main()
