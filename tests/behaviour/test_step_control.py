"""Load-step control after a cut-back: steps that always take more Newton
iterations than steps.grow_below (friction: 6–8 per step; here grow_below =
0 makes every step such a step) grow Δλ back once steps.grow_after steps in
a row have converged, up to the Δλ that failed; grow_after = 0 keeps the cut
Δλ to the end (the behaviour before). The cut-back is forced with
Simulation(fail_attempt=...) on a frictionless scene, so the sequence of
steps is the same whatever the BLAS kernel's rounding."""
import json

import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

from conftest import ROOT


def run_with_one_failure(tmp_path, grow_after):
    """The frictionless punch on 4 × 4 × 1 with grow_below = 0 (the
    iteration rule never grows a step) and the first attempt of step 2
    forced to fail: (load-factor increments of the converged steps, the
    hook's calls, the summary)."""
    sc = scene.load(ROOT / "scenes" / "punch.toml", [
        "mesh.n=4", "mesh.m=1", "output.xdmf=false", f"output.dir={tmp_path}", "steps.grow_below=0",
        f"steps.grow_after={grow_after}"])
    calls = []

    def fail_attempt(step, lam, dlam, attempt):
        calls.append((step, lam, dlam, attempt))
        return step == 2 and attempt == 0

    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None, fail_attempt=fail_attempt)
    steps = sim.run(out_dir=str(tmp_path)).steps
    lam = np.array([s["load_factor"] for s in steps])
    summary = json.loads((tmp_path / "summary.json").read_text())
    return np.diff(np.concatenate([[0.0], lam])), calls, summary


def test_step_regrows_after_a_forced_cut_back(tmp_path):
    dlam, calls, summary = run_with_one_failure(tmp_path / "regrow", grow_after=3)
    assert summary["steps"][-1]["load_factor"] == pytest.approx(1.0)
    # one call per attempt: step 1, step 2 twice (the forced failure, then at half the step), ...
    assert [c[0] for c in calls[:4]] == [1, 2, 2, 3] and [c[3] for c in calls[:4]] == [0, 0, 1, 0]
    assert calls[1][1:3] == pytest.approx((0.1, 0.1)) and calls[2][1:3] == pytest.approx((0.1, 0.05))
    assert len(calls) == len(summary["steps"]) + 1
    assert dlam[0] == pytest.approx(0.1) and dlam[1] == pytest.approx(0.05)  # the cut-back happened
    cut = dlam[1:-1]  # the last step may be shortened to end at λ = 1
    # three steps at the cut size, then growth by 1.5 every three steps, never beyond the Δλ that failed
    assert np.allclose(cut[:3], 0.05)
    assert cut[3] == pytest.approx(0.075)
    assert cut.max() == pytest.approx(0.1)
    assert np.all(cut <= 0.1 + 1e-12)
    assert np.all(np.diff(cut) >= -1e-12)  # no further cut-back: Δλ never falls again
    [failed] = summary["failed_attempts"]
    assert failed["step"] == 2 and failed["attempt"] == 0 and failed["outcome"] == "cut back"
    assert failed["reason"] == "FORCED_FAILURE" and failed["snes_reason"].startswith("CONVERGED")


def test_without_grow_after_the_cut_step_stays(tmp_path):
    dlam, _, _ = run_with_one_failure(tmp_path / "stay", grow_after=0)
    assert dlam[0] == pytest.approx(0.1)
    assert np.allclose(dlam[1:-1], 0.05)


def test_continuation_step_factor_holds_just_above_the_target():
    """Arc length / displacement control: √(target / its) in [0.5, 2], except that one or two iterations
    above the target keep the size (a count that does not fall with the step must not shrink it to
    nothing)."""
    from hypercontact.solve.path_following import step_factor

    assert step_factor(5, 5) == 1.0
    assert step_factor(6, 5) == step_factor(7, 5) == 1.0
    assert step_factor(8, 5) == pytest.approx((5 / 8) ** 0.5)
    assert step_factor(4, 5) == pytest.approx((5 / 4) ** 0.5)
    assert step_factor(1, 5) == 2.0 and step_factor(25, 5) == 0.5
