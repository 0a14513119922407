"""The secant predictor (steps.predictor): a load step's first attempt starts
from the last two converged states extrapolated to its load factor, u_n +
(Δλ/Δλ_n)(u_n − u_n−1), instead of from u_n; a retry after a cut-back starts
from u_n.

References independent of the predictor's code: a rigid translation, whose
displacement is exactly linear in λ (so the extrapolated state is the
solution and Newton has nothing left to do, whatever the step lengths); and
the same scene without the predictor, whose converged states along the same
steps must be the same (the predictor changes where Newton starts, not what
it converges to)."""
import csv
import json

import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

from conftest import ROOT, quiet

TRANSLATION = """
title = "A block carried along by its two ends: u = λ d, stress-free"
[mesh]
builder = "box"
size = [1.0, 1.0, 1.0]
n = 2
m = 2
[material]
law = "mooney_rivlin"
parameters = { alpha1 = 0.2, alpha2 = 0.05, K = 5.0 }
[[bc]]
surface = "xmin"
fix = ["x", "y", "z"]
motion = [0.3, -0.2, 0.1]
[[bc]]
surface = "xmax"
fix = ["x", "y", "z"]
motion = [0.3, -0.2, 0.1]
[steps]
initial = 0.1
max = 0.4
"""


def run_translation(tmp_path, predictor, fail_step=None):
    path = tmp_path / "translation.toml"
    path.write_text(TRANSLATION)
    sc = scene.load(path, [f"output.dir={tmp_path / predictor}", "output.xdmf=false",
                           f"steps.predictor={predictor}"])
    calls = []

    def fail_attempt(step, lam, dlam, attempt):
        calls.append((step, dlam, attempt))
        return step == fail_step and attempt == 0

    Simulation(sc, MPI.COMM_SELF, log=quiet, fail_attempt=fail_attempt).run(out_dir=str(tmp_path / predictor))
    return json.loads((tmp_path / predictor / "summary.json").read_text()), calls


def test_secant_prediction_of_a_path_linear_in_load_is_the_solution(tmp_path):
    summary, calls = run_translation(tmp_path, "secant", fail_step=3)
    its = summary["newton_iterations"]
    assert summary["status"] == "completed"
    assert [c[2] for c in calls if c[0] == 3] == [0, 1]  # step 3 was cut back and retried
    # the first step has nothing to extrapolate from, and step 3's retry starts from the last
    # converged state (a retry is not predicted); every other step starts on the solution, also
    # the steps that grew (Δλ 0.1 → 0.15 → ...) and the one after the cut-back
    assert its[0] >= 1 and its[2] >= 1
    assert its[1] == 0 and its[3:] == [0] * (len(its) - 3)
    dlams = sorted({round(c[1], 12) for c in calls})
    assert len(dlams) >= 3  # unequal steps were predicted: the ratio Δλ/Δλ_n is not always 1
    # without the predictor every step starts from the last state and needs iterations
    plain, _ = run_translation(tmp_path, "none")
    assert min(plain["newton_iterations"]) >= 1


def punch(tmp_path, predictor):
    """The paper's punch with (μ1, μ2) = (0, 1) (friction that sticks the
    plate to the base) on 8 × 8 × 2, in ten equal steps of 0.1."""
    out = tmp_path / predictor
    sc = scene.load(ROOT / "scenes" / "punch_mu0_1.toml", [
        "mesh.n=8", "mesh.m=2", f"output.dir={out}", "output.xdmf=false", "steps.max=0.1",
        f"steps.predictor={predictor}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=quiet)
    sim.run(out_dir=str(out))
    rows = list(csv.DictReader(open(out / "curves.csv")))
    return sim.w.x.array.copy(), rows, json.loads((out / "summary.json").read_text())


def test_secant_predictor_same_frictional_path_fewer_iterations(tmp_path):
    w0, rows0, s0 = punch(tmp_path, "none")
    w1, rows1, s1 = punch(tmp_path, "secant")
    lam0 = [float(r["load_factor"]) for r in rows0]
    assert lam0 == pytest.approx(np.linspace(0.1, 1.0, 10), abs=1e-12)
    assert [float(r["load_factor"]) for r in rows1] == pytest.approx(lam0, abs=1e-12)
    # the same converged states (friction's history depends on the path: the same steps, the same
    # history), to the Newton tolerance
    for a, b in zip(rows0, rows1):
        assert float(b["punch_fz"]) == pytest.approx(float(a["punch_fz"]), rel=1e-7)
    assert np.abs(w1 - w0).max() <= 1e-7 * np.abs(w0).max()
    # fewer Newton iterations: the steps after the first start near their solution
    n0, n1 = sum(s0["newton_iterations"]), sum(s1["newton_iterations"])
    assert n1 <= 0.75 * n0, (s0["newton_iterations"], s1["newton_iterations"])
