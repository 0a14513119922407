"""Facet integration's blind spot (docs/verification.md §9): a facet's one
pressure sees the mean gap over its Gauss points, not each point's. On the
Taylor–Hood pad of bench/pad_sphere.py pressed 0.2 deep by a rigid sphere
(radius ½, K/μ = 10³, 8 × 8 × 4), run with integration = "facet" on Q2–Q1
hexahedra (it stops where its equilibrium turns unstable) and P2–P1
tetrahedra, and with Gauss points on Q2–Q1 to the facet run's depth: at the
last converged state, the smallest facet mean gap and the gaps of the facets'
own Gauss points against the sphere (an independent distance |x − c| − R).

    .venv/bin/python bench/facet_penetration.py   # one JSON line per run (committed: bench/results/facet_penetration.jsonl)

A benchmark reports; it asserts nothing."""
import json
import sys
import tempfile
from pathlib import Path

import numpy as np
from mpi4py import MPI

sys.path.insert(0, str(Path(__file__).resolve().parent))
from pad_sphere import pad  # noqa: E402

from hypercontact import scene  # noqa: E402
from hypercontact.simulation import Simulation, StepFailure  # noqa: E402


def run(cells, integration, press, work):
    data = pad(cells, 8, 1e3, "sphere", press, Path(work) / f"{cells}{integration}")
    data["contact"][0]["integration"] = integration
    sim = Simulation(scene.load(data), MPI.COMM_SELF, log=lambda m: None)
    try:
        sim.run()
        completed = True
    except StepFailure:
        completed = False
    lam = json.loads((Path(data["output"]["dir"]) / "summary.json").read_text())["steps"][-1]["load_factor"]
    depth = press * lam
    ball = sim.contacts[0]
    state = ball.evaluate(sim.u)
    points = np.asarray(ball.geometry.coordinates(sim.u)).reshape(-1, 3)  # the kernel's Gauss points
    gaps = np.linalg.norm(points - np.array([0.0, 0.0, 1.0 - depth]), axis=1) - 0.5
    return {"cells": cells, "integration": integration, "completed": completed, "load_factor": lam,
            "depth": depth, "closed": int(np.count_nonzero(np.asarray(state.pressure) > 0)),
            "smallest_kernel_gap": float(np.min(state.gap)), "deepest_gauss_point": float(gaps.min()),
            "gauss_points_deeper_than_1e-3": int(np.count_nonzero(gaps < -1e-3))}


def main():
    with tempfile.TemporaryDirectory() as work:
        q2 = run("hexahedra", "facet", 0.2, work)
        print(json.dumps(q2), flush=True)
        print(json.dumps(run("hexahedra", "gauss", q2["depth"], work)), flush=True)
        print(json.dumps(run("tetrahedra", "facet", 0.2, work)), flush=True)


if __name__ == "__main__":
    main()
