"""Load-step control after a cut-back: steps that always take more Newton
iterations than steps.grow_below (friction: 6–8 per step) grow Δλ back once
steps.grow_after steps in a row have converged, up to the Δλ that failed;
grow_after = 0 keeps the cut Δλ to the end (the behaviour before)."""
import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

from conftest import ROOT


def run_with_one_failure(tmp_path, grow_after):
    """The base-friction punch on 4 × 4 × 1 (every step needs more than
    grow_below = 5 iterations), with the first attempt of step 2 made to
    fail: (load-factor increments of the converged steps, Newton iterations,
    the converged rows)."""
    sc = scene.load(ROOT / "scenes" / "punch_mu0_1.toml", [
        "mesh.n=4", "mesh.m=1", "output.xdmf=false", f"output.dir={tmp_path}", f"steps.grow_after={grow_after}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    solve, calls = sim.solve_step, []

    def solve_step():
        calls.append(sim._lam)
        if len(calls) == 2:  # the first attempt from λ = 0.1: reported as not converged, state untouched
            return False, 25, [1.0], "FORCED_FAILURE"
        return solve()

    sim.solve_step = solve_step
    steps = sim.run(out_dir=str(tmp_path)).steps
    lam = np.array([s["load_factor"] for s in steps])
    return np.diff(np.concatenate([[0.0], lam])), [s["newton_iterations"] for s in steps], steps


def test_step_regrows_after_a_forced_cut_back(tmp_path):
    dlam, its, steps = run_with_one_failure(tmp_path / "regrow", grow_after=3)
    assert steps[-1]["load_factor"] == pytest.approx(1.0)
    assert min(its) > 5  # the iteration rule alone never grows these steps
    assert dlam[0] == pytest.approx(0.1) and dlam[1] == pytest.approx(0.05)  # the cut-back happened
    cut = dlam[1:-1]  # the last step may be shortened to end at λ = 1
    # three steps at the cut size, then growth by 1.5 every three steps, never beyond the Δλ that failed
    assert np.allclose(cut[:3], 0.05)
    assert cut[3] == pytest.approx(0.075)
    assert cut.max() == pytest.approx(0.1)
    assert np.all(cut <= 0.1 + 1e-12)
    assert np.all(np.diff(cut) >= -1e-12)  # no further cut-back: Δλ never falls again


def test_without_grow_after_the_cut_step_stays(tmp_path):
    dlam, its, _ = run_with_one_failure(tmp_path / "stay", grow_after=0)
    assert np.allclose(dlam[1:-1], 0.05)
