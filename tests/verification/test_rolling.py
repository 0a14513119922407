"""A rigid cylinder rolling on a rubber slab (scenes/rolling_cylinder.toml):
pressed into the slab, then translated by Δx while turned by θ = Δx / R
about its own axis, at μ = 1.

The reference is rigid-body kinematics, independent of the code: the
cylinder's lowest line moves with v − ω R = 0, so the slab's top nodes in
contact are carried along without slipping — their accumulated slip is
zero up to the penalty's elastic play, the frictional dissipation is
nothing like the μ N Δx of sliding, and the force along x is well inside
the friction cone (sliding drives it to μ N). Without the rotation, or with
it the wrong way round, every node in contact would slip by about Δx (2 Δx)."""
import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.results import ResultsWriter
from hypercontact.simulation import Simulation


@pytest.fixture(autouse=True)
def no_pictures(monkeypatch):
    monkeypatch.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})


def test_a_rolling_cylinder_does_not_slip(scenes_dir, out_dir):
    sc = scene.load(scenes_dir / "rolling_cylinder.toml",
                    overrides=["mesh.n=12", f"output.dir={out_dir}", "output.xdmf=false"])
    roll = sc["phase"][1]["contact"]["roller"]
    dx = roll["motion"][-1][1][0]
    radius, mu = sc["contact"][0]["radius"], sc["contact"][0]["mu"]
    assert roll["rotation"][-1][1] == pytest.approx(dx / radius)  # the scene rolls: θ = Δx / R
    sim = Simulation(sc, MPI.COMM_WORLD, log=quiet)
    writer = sim.run()
    rows = [s for s in writer.steps if s["phase"] == 2]
    assert rows and rows[-1]["load_factor"] == pytest.approx(1.0)
    (roller,) = sim.contacts
    n = abs(rows[-1]["roller_fz"])
    assert n > 0
    # contact all along the roll, the nodes under the cylinder sticking
    assert all(s["roller_closed_nodes"] > 0 and s["roller_stick_nodes"] > 0 for s in rows)
    # no slip: accumulated slip ≤ 1 % of Δx at every node, dissipation ≤ 1e-3 of sliding's μ N Δx
    slip = np.asarray(roller.law.slip_accumulated)
    worst = MPI.COMM_WORLD.allreduce(float(slip.max()) if len(slip) else 0.0, op=MPI.MAX)
    assert worst <= 0.01 * dx
    assert rows[-1]["dissipation"] <= 1e-3 * mu * n * dx
    # the tangential force stays well inside the cone (sliding: |fx| → μ N)
    assert all(abs(s["roller_fx"]) <= 0.5 * mu * abs(s["roller_fz"]) for s in rows)
