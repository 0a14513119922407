"""What accuracy costs in time, element by element: the nearly incompressible
pad (K/μ = 10³) bonded to its base and pressed 10 % by a frictionless rigid
plate (the problem of tests/verification/test_locking_tetrahedra.py), and the
paper's frictionless punch, on trilinear and triquadratic hexahedra (Q1, Q2,
Q2–Q1 mixed) and linear and quadratic tetrahedra (P1, P2, P2–P1 mixed).

    .venv/bin/python bench/elements.py            # → bench/results/elements.md, elements.json, elements.png
    .venv/bin/python bench/elements.py --quick    # the pad only, two sizes

Per run: the force at the end, its error against the reference (Richardson
extrapolation of the finest two Q2–Q1 pads, or of the two finest Q2 punches
with the observed order), wall time (the whole run: mesh, forms from the
cache, every Newton step), Newton iterations, unknowns. One machine, one
thread, one run each: ratios within one run are what to read. A benchmark
reports; it asserts nothing."""
import argparse
import json
import time
import tomllib
from pathlib import Path

import numpy as np
from mpi4py import MPI

from hypercontact import scene
from hypercontact import _dolfinx as dfx
from hypercontact.simulation import Simulation

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "bench" / "results"
ELEMENTS = {  # name → (cells, degree, formulation)
    "Q1": ("hexahedra", 1, "displacement"), "Q2": ("hexahedra", 2, "displacement"),
    "Q2-Q1": ("hexahedra", 2, "mixed"), "P1": ("tetrahedra", 1, "displacement"),
    "P2": ("tetrahedra", 2, "displacement"), "P2-P1": ("tetrahedra", 2, "mixed"),
}


def pad(n, element):
    cells, degree, formulation = ELEMENTS[element]
    return {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 0.5], "n": n, "m": max(1, n // 2), "cells": cells},
        "material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 1000.0}},
        "discretisation": {"degree": degree, "formulation": formulation,
                           "quadrature_degree": 4 if degree == 2 else 2},
        "bc": [{"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]},
               {"surface": "zmin", "fix": ["x", "y", "z"]}],
        "contact": [{"name": "plate", "surface": "zmax", "obstacle": "plane", "point": [0, 0, 0.5],
                     "normal": [0, 0, -1], "motion": [0, 0, -0.05]}],
        "steps": {"initial": 0.5, "max": 1.0},
        "output": {"dir": "/tmp/bench_elements", "xdmf": False, "symmetry_factor": 4.0},
    }, "plate_fz", -1.0


def punch(n, element):
    data = tomllib.loads((ROOT / "scenes" / "punch.toml").read_text())
    cells, degree, formulation = ELEMENTS[element]
    data["mesh"].update(n=n, m=max(1, n // 4), cells=cells)
    data["discretisation"].update(degree=degree, formulation=formulation,
                                  quadrature_degree=4 if degree == 2 else 2)
    data["output"].update(dir="/tmp/bench_elements", xdmf=False)
    return data, "punch_fz", -1.0


def sphere_plane(n, element):
    """The inflated Mooney sphere against the rigid plane (scenes/sphere_plane.toml): its limit pressure,
    the vertex of the parabola through the largest pressure and its two neighbours against the pole's
    displacement (as docs/verification.md §6 reads it). The octant shell is built of hexahedra only, so only the hexahedral elements run it."""
    data = tomllib.loads((ROOT / "scenes" / "sphere_plane.toml").read_text())
    cells, degree, formulation = ELEMENTS[element]
    if cells != "hexahedra":
        raise ValueError(f"sphere_plane: the shell builder makes hexahedra only, not {element}")
    data["mesh"].update(n=n, m=max(1, n // 4))
    data["discretisation"].update(degree=degree, formulation=formulation,
                                  quadrature_degree=4 if degree == 2 else 2)
    data["output"].update(dir="/tmp/bench_elements", xdmf=False)
    return data, "limit:pressure_inner:pole_uz", 1.0


def limit(steps, column, against):
    """The largest value of a column on the converged path: the vertex of the parabola through its largest
    step value and the two neighbours, against another column (the step's value if the largest is an end)."""
    y = np.array([x[column] for x in steps])
    x = np.array([x[against] for x in steps])
    k = int(np.argmax(y))
    if k == 0 or k == len(y) - 1:
        return float(y[k])
    a, b, c = np.polyfit(x[k - 1:k + 2], y[k - 1:k + 2], 2)
    return float(c - b * b / (4 * a)) if a < 0 else float(y[k])


def run(problem, n, element):
    data, key, sign = problem(n, element)
    t = time.perf_counter()
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=lambda *a, **k: None)
    writer = sim.run()
    wall = time.perf_counter() - t
    s = writer.steps[-1]
    value = limit(writer.steps, *key.split(":")[1:]) if key.startswith("limit:") else s[key]
    return {"n": n, "element": element, "force": sign * value, "wall_s": wall,
            "newton": sum(x["newton_iterations"] for x in writer.steps),
            "unknowns": dfx.num_global_dofs(sim.w.function_space), "load_factor": s["load_factor"]}


def richardson(coarse, fine, ratio, order):
    return fine + (fine - coarse) / (ratio**order - 1)


def study(name, problem, plan, reference_element, quick):
    rows = []
    for element, sizes in plan.items():
        for n in sizes:
            rows.append(run(problem, n, element))
            print(name, rows[-1], flush=True)
    ref = [r for r in rows if r["element"] == reference_element]
    a, b, c = [r["force"] for r in ref[-3:]] if len(ref) >= 3 else (None, ref[-2]["force"], ref[-1]["force"])
    ratio = ref[-1]["n"] / ref[-2]["n"]
    if a is not None and (b - a) * (c - b) > 0:
        order = np.log(abs((b - a) / (c - b))) / np.log(ratio)
    else:
        order = 2.0
    reference = richardson(b, c, ratio, order)
    for r in rows:
        r["error"] = (r["force"] - reference) / reference
    return {"rows": rows, "reference": reference, "order": order, "reference_element": reference_element}


def report(results):
    lines = ["# What accuracy costs: element by element", "",
             "`bench/elements.py` (one thread; whole-run wall times). Error: against the Richardson "
             "extrapolation of the finest reference-element runs (its order observed from the last three).", ""]
    for name, res in results.items():
        lines += [f"## {name}", "", f"reference {res['reference']:.6g} ({res['reference_element']}, observed "
                  f"order {res['order']:.2f})", "",
                  "| element | n | unknowns | force | error | wall s | Newton |", "|---|---|---|---|---|---|---|"]
        for r in res["rows"]:
            lines.append(f"| {r['element']} | {r['n']} | {r['unknowns']} | {r['force']:.6g} | {100 * r['error']:+.2f} % "
                         f"| {r['wall_s']:.1f} | {r['newton']} |")
        lines.append("")
    return "\n".join(lines)


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(results), figsize=(6 * len(results), 4.5), squeeze=False)
    for ax, (name, res) in zip(axes[0], results.items()):
        for element in dict.fromkeys(r["element"] for r in res["rows"]):
            rs = [r for r in res["rows"] if r["element"] == element]
            ax.loglog([r["wall_s"] for r in rs], [max(abs(r["error"]), 1e-6) for r in rs], "o-", label=element)
        ax.set_xlabel("wall time, s")
        ax.set_ylabel("|force error|")
        ax.set_title(name)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true")
    p.add_argument("--sphere", action="store_true", help="the sphere against a plane only (results in "
                                                         "elements_sphere.*)")
    args = p.parse_args()
    results = {}
    if not args.sphere:
        pad_plan = {"Q2-Q1": [4, 8], "P2-P1": [4, 8]} if args.quick else {
            "Q1": [4, 8, 16], "Q2": [4, 8], "Q2-Q1": [4, 8, 12, 16], "P1": [4, 8, 16], "P2": [4, 8],
            "P2-P1": [4, 8, 12, 16]}
        results["pad, K/μ = 1e3, bonded, pressed 10 % (force)"] = study("pad", pad, pad_plan, "Q2-Q1", args.quick)
    if not (args.quick or args.sphere):
        punch_plan = {"Q1": [8, 16, 32], "Q2": [4, 8, 16], "Q2-Q1": [4, 8], "P2": [4, 8], "P2-P1": [4, 8]}
        results["paper punch, frictionless (punch force, N)"] = study("punch", punch, punch_plan, "Q2", False)
    if not args.quick:
        sphere_plan = {"Q1": [8, 16, 32], "Q2": [4, 8, 16]}
        results["sphere against a rigid plane (limit pressure, MPa)"] = study("sphere_plane", sphere_plane,
                                                                           sphere_plan, "Q2", False)
    OUT.mkdir(parents=True, exist_ok=True)
    suffix = "_quick" if args.quick else "_sphere" if args.sphere else ""
    (OUT / f"elements{suffix}.json").write_text(json.dumps(results, indent=1))
    (OUT / f"elements{suffix}.md").write_text(report(results))
    plot(results, OUT / f"elements{suffix}.png")
    print(report(results))


if __name__ == "__main__":
    main()
