"""Hertz's peak pressure and contact radius, element by element, on a block
resolved under the contact: the rigid sphere of
tests/verification/test_rigid_sphere.py (R = 1, d = 0.0025 R, E = 1,
ν = 0.3, block 40 a, quarter model, frictionless, automatic penalty, one
load step) with uniform cells over 1.5 a under the ball (``mesh.core``) and
graded t³ beyond, on Q1, Q2, P1 and P2 (contact integration "auto", and P2
with nodal weights, and P2 and Q2 with a pressure per facet).

    .venv/bin/python bench/hertz_core.py    # → bench/results/hertz_core.md, .json
    .venv/bin/python bench/hertz_core.py P2:facet Q2:facet   # those rows only, merged

Per run, against Hertz at the run's own force F (a(F) = (3FR/4E*)^(1/3),
p0(F) = 3F/(2π a(F)²)), so that the block's finite depth, which changes the
force at a given approach, does not enter: the pole's pressure p_pole (the
slave point nearest the axis, nominal), the radius a_m from the second
moment of the slave points' normal forces (Σ f r² / Σ f = (2/5) a² for
Hertz's pressure), the force against F_H(d) and against the Boussinesq
estimate of the rollers' missing compliance, whole-run wall time (forms
from the cache), Newton iterations, unknowns. One thread, one run each:
wall-time ratios are what to read. A benchmark reports; it asserts nothing
(the test is tests/verification/test_rigid_sphere.py)."""
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from mpi4py import MPI

from elements import ELEMENTS
from hypercontact import _dolfinx as dfx
from hypercontact import scene
from hypercontact.hertz import slave_points
from hypercontact.simulation import Simulation

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "bench" / "results"
sys.path[:0] = [str(ROOT / "tests" / "verification"), str(ROOT / "tests")]
from test_rigid_sphere import A_HERTZ, DEPTH, E_STAR, R, bottom_compliance, hertz_force, indentation  # noqa: E402

#: (element, contact integration) → cells per edge ("auto": nodal on hexahedra and 3-node triangles, Gauss
#: points on 6-node triangles)
LADDER = {("Q1", "auto"): [12, 16, 20, 24, 28], ("Q2", "auto"): [8, 10, 12, 14, 16], ("P1", "auto"): [16, 20, 24],
          ("P2", "auto"): [8, 10, 12], ("P2", "nodal"): [10, 12], ("P2", "facet"): [10, 12, 14, 16],
          ("Q2", "facet"): [12, 14, 16]}


def run(element, integration, n):
    cells, degree, formulation = ELEMENTS[element]
    data = indentation(f"/tmp/bench_hertz_core/{element}_{n}", n)
    data["mesh"].update(cells=cells, core=[1.5 * A_HERTZ] * 3)
    data["discretisation"] = {"degree": degree, "formulation": formulation}
    data["contact"][0]["integration"] = integration
    t = time.perf_counter()
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=lambda *a, **k: None)
    writer = sim.run(out_dir=data["output"]["dir"])
    wall = time.perf_counter() - t
    contact = sim.contacts[0]
    F = 4.0 * abs(float(contact.force(sim.u)[2]))
    _, x, gap, p = slave_points(contact, sim.u)
    g = contact.geometry
    r = np.hypot(x[:, 0], x[:, 1])
    a_F = (3.0 * F * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
    p0_F = 3.0 * F / (2.0 * math.pi * a_F ** 2)
    pole = int(np.argmin(r))
    if integration == "facet":
        # a facet's pressure is its mean: compared with Hertz's profile averaged over the same facet's
        # Gauss points, and its force spread over them for the second moment
        w = g.kernel_area.reshape(len(g.area), -1)
        rq = np.hypot(*np.moveaxis(g.coordinates(sim.u).reshape(len(g.area), -1, 3)[..., :2], -1, 0))
        hertz = np.sum(w[pole] * np.sqrt(np.clip(1.0 - (rq[pole] / a_F) ** 2, 0.0, None))) / g.area[pole]
        fq = p[:, None] * w
        second = np.sum(fq * rq ** 2) / np.sum(fq)
    else:
        hertz, f = 1.0, p * np.asarray(g.point_area)
        second = np.sum(f * r ** 2) / np.sum(f)
    return {"element": element if integration == "auto" else f"{element} {integration}", "n": n, "unknowns": dfx.num_global_dofs(sim.w.function_space),
            "force_error": F / hertz_force(DEPTH) - 1.0, "pole": float(p[pole] / (p0_F * hertz) - 1.0),
            "pole_r": float(r[pole] / a_F),
            "radius": math.sqrt(2.5 * second) / a_F - 1.0,
            "closed": int(np.sum(gap <= 0.0)), "wall_s": wall,
            "newton": sum(s["newton_iterations"] for s in writer.steps), "steps": len(writer.steps)}


def report(rows):
    est = 1.5 * bottom_compliance()
    lines = ["# Hertz's peak pressure and radius on a block resolved under the contact", "",
             "`bench/hertz_core.py` (see its text): uniform cells over 1.5 a under the ball, graded t³ beyond; "
             "p_pole and a_m against Hertz at each run's own force F; F against F_H(d), which the rollers at "
             f"depth 40 a raise by about {100 * est:.2f} % (Boussinesq). With facet integration a "
             "point is a facet: its pressure (the facet's mean) is compared with Hertz's profile averaged over "
             "the same facet, and a_m spreads its force over its Gauss points. Whole-run wall times, one thread.", "",
             "| element | n | unknowns | F/F_H − 1 | p_pole/p0(F) − 1 | a_m/a(F) − 1 | closed | Newton (steps) | wall s |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['element']} | {r['n']} | {r['unknowns']} | {100 * r['force_error']:+.2f} % | "
                     f"{100 * r['pole']:+.2f} % | {100 * r['radius']:+.2f} % | {r['closed']} | "
                     f"{r['newton']} ({r['steps']}) | {r['wall_s']:.1f} |")
    return "\n".join(lines) + "\n"


def main():
    """All rows, or (arguments such as ``P2:facet``) those element and integration rows only, merged
    into the committed hertz_core.json."""
    import logging

    logging.getLogger().setLevel(logging.WARNING)
    only = [tuple(a.split(":")) for a in sys.argv[1:]]
    rows = []
    if only:
        labels = {e if i == "auto" else f"{e} {i}" for e, i in only}
        rows = [r for r in json.loads((OUT / "hertz_core.json").read_text())["rows"] if r["element"] not in labels]
    for (element, integration), sizes in LADDER.items():
        if only and (element, integration) not in only:
            continue
        for n in sizes:
            rows.append(run(element, integration, n))
            print(rows[-1], flush=True)
    order = [e if i == "auto" else f"{e} {i}" for e, i in LADDER]
    rows.sort(key=lambda r: (order.index(r["element"]), r["n"]))
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "hertz_core.json").write_text(json.dumps({"a": A_HERTZ, "F_H": hertz_force(DEPTH),
                                                     "rollers_estimate": 1.5 * bottom_compliance(),
                                                     "rows": rows}, indent=1))
    (OUT / "hertz_core.md").write_text(report(rows))
    print(report(rows))


if __name__ == "__main__":
    main()
