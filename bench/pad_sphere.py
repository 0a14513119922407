"""The nearly incompressible pad of docs/verification.md §12 (neo-Hooke, μ = 1,
1 × 1 × ½ quarter model bonded to its base) on the two Taylor–Hood elements,
Q2–Q1 hexahedra and P2–P1 tetrahedra, with the scene defaults (automatic
steps and penalty, integration "auto"):

- pressed by a rigid sphere of radius ½ over the quarter's axis, 0.2 deep (40 %
  of the height), K/μ = 10³, n × n × n/2 cells for n = 4 and 8: load steps,
  Newton iterations, failed attempts, force, wall time;
- pressed 10 % by a flat rigid plate, n = 8, at K/μ = 10³, 10⁴, 10⁵: the force
  (the incompressible limit F∞ + a/K).

    .venv/bin/python bench/pad_sphere.py   # → bench/results/pad_sphere.md, .jsonl

One process, one thread. A benchmark reports; the assertions are in
tests/verification/test_locking_tetrahedra.py."""
import json
import tempfile
import time
from pathlib import Path

from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation, StepFailure

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "bench" / "results"


def pad(cells, n, k_over_mu, obstacle, press, out):
    if obstacle == "plane":
        contact = {"name": "tool", "surface": "zmax", "obstacle": "plane", "point": [0, 0, 0.5],
                   "normal": [0, 0, -1], "motion": [0, 0, -press]}
    else:
        contact = {"name": "tool", "surface": "zmax", "obstacle": "sphere", "center": [0.0, 0.0, 1.0],
                   "radius": 0.5, "motion": [0, 0, -press]}
    return {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 0.5], "n": n, "m": n // 2, "cells": cells},
        "material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": k_over_mu}},
        "discretisation": {"degree": 2, "formulation": "mixed", "quadrature_degree": 4},
        "bc": [{"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]},
               {"surface": "zmin", "fix": ["x", "y", "z"]}],
        "contact": [contact],
        "output": {"dir": str(out), "xdmf": False, "symmetry_factor": 4.0},
    }


def run(cells, n, k_over_mu, obstacle, press, work):
    out = Path(work) / f"{cells}{n}{obstacle}{k_over_mu:g}"
    t = time.perf_counter()
    sim = Simulation(scene.load(pad(cells, n, k_over_mu, obstacle, press, out)), MPI.COMM_SELF,
                     log=lambda m: None)
    try:
        sim.run()
        completed = True
    except StepFailure:
        completed = False
    summary = json.loads((out / "summary.json").read_text())
    steps = summary["steps"]
    return {"cells": cells, "n": n, "K_over_mu": k_over_mu, "obstacle": obstacle, "press": press,
            "completed": completed, "steps": len(steps), "newton_its": summary["newton_iterations"],
            "failed_attempts": len(summary["failed_attempts"]),
            "force": -steps[-1]["tool_fz"] if steps else None, "wall_s": round(time.perf_counter() - t, 1)}


def main():
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for n in (4, 8):
            for cells in ("hexahedra", "tetrahedra"):
                rows.append(run(cells, n, 1e3, "sphere", 0.2, work))
                print(json.dumps(rows[-1]), flush=True)
        for k in (1e3, 1e4, 1e5):
            for cells in ("hexahedra", "tetrahedra"):
                rows.append(run(cells, 8, k, "plane", 0.05, work))
                print(json.dumps(rows[-1]), flush=True)
    (OUT / "pad_sphere.jsonl").write_text("".join(json.dumps(r) + "\n" for r in rows))
    name = {"hexahedra": "Q2–Q1", "tetrahedra": "P2–P1"}
    lines = ["# The Taylor–Hood pad: a rigid sphere pressed 40 % deep, and K/μ to 10⁵", "",
             "`bench/pad_sphere.py`, one process, scene defaults.", "",
             "| element | n × n × n/2 | load steps | Newton its (sum) | failed attempts | force (whole pad) | wall (s) |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["obstacle"] == "sphere":
            lines.append(f"| {name[r['cells']]} | {r['n']} | {r['steps']}{'' if r['completed'] else ' (stopped)'} | "
                         f"{sum(r['newton_its'])} | {r['failed_attempts']} | {r['force']:.4f} | {r['wall_s']} |")
    lines += ["", "The flat plate, 10 % of the height, 8 × 8 × 4:", "",
              "| element | K/μ | force (whole pad) | Newton its | wall (s) |", "|---|---|---|---|---|"]
    for r in rows:
        if r["obstacle"] == "plane":
            lines.append(f"| {name[r['cells']]} | {r['K_over_mu']:.0e} | {r['force']:.5f} | "
                         f"{sum(r['newton_its'])} | {r['wall_s']} |")
    (OUT / "pad_sphere.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
