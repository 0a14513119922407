"""Continuation inside a phase: the inflated sphere (scenes/sphere.toml)
pressed to 0.004 MPa under load control, then followed by arc length (or
displacement control of the equator) through its limit point, against the spherically symmetric 1D oracle
(hypercontact.sphere1d), independent of the phase code: the limit pressure
and the displacement at it within 1 % (the tolerance of the one-phase
arc-length test, tests/verification/test_sphere.py), every point of both
phases on the oracle's curve within 1 %, and the second phase's pressure
linear in its parameter from where the first left it."""
import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.results import ResultsWriter
from hypercontact.simulation import Simulation
from hypercontact.sphere1d import PAPER, limit_point, pressure_curve

SCENE = ROOT / "scenes" / "sphere.toml"
P1, P2 = 0.004, 0.01  # MPa: the end of the load-control phase; the arc-length phase's value at s = 1


@pytest.fixture(autouse=True)
def no_pictures(monkeypatch):
    monkeypatch.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})


def two_phases(out, u_ref, control="arclength"):
    data = scene.load(SCENE, [f"output.dir={out}", "output.xdmf=false"])
    data["pressure"][0].update(name="inflate", value=None)
    data["phase"] = [
        {"name": "pre-inflate", "steps": {"control": "load", "initial": 0.25, "max": 0.25},
         "pressure": {"inflate": P1}},
        # arc lengths are measured with the tangent where the phase starts (0.004 MPa: softer than at 0),
        # so the same Δu per step as the one-phase run's max = 0.15 takes a smaller max here;
        # displacement control: steps of 0.02 to 0.05 × stop_value of the equator's displacement
        {"name": "through the limit point",
         "steps": {"control": control, "initial": 0.02, "max": 0.05, "stop_value": 1.3 * u_ref},
         "pressure": {"inflate": P2}}]
    return scene.load(data)


@pytest.mark.slow
@pytest.mark.parametrize("control", ["arclength", "displacement"])
def test_continuation_in_a_second_phase_passes_the_limit_point_on_the_oracle(control, out_dir):
    params = dict(PAPER, K=5.0, i2="usual")
    u_ref, p_ref = limit_point("mooney_rivlin", params)
    data = two_phases(out_dir, u_ref, control)
    lines = []
    sim = Simulation(data, MPI.COMM_WORLD, log=lines.append)
    writer = sim.run()
    steps = writer.steps
    first = [s for s in steps if s["phase"] == 1]
    second = [s for s in steps if s["phase"] == 2]
    assert [s["load_factor"] for s in first] == pytest.approx([0.25, 0.5, 0.75, 1.0])
    assert first[-1]["pressure_inner"] == pytest.approx(P1, rel=1e-14)
    # the second phase: p = P1 + s (P2 − P1), s its own parameter; τ runs on from 1
    for s in second:
        assert s["pressure_inner"] == pytest.approx(P1 + s["load_factor"] * (P2 - P1), rel=1e-12)
        assert s["time"] == pytest.approx(1.0 + s["load_factor"], rel=1e-12)
    assert len(writer.limit_points) == 1 and writer.limit_points[0]["after_step"] > len(first)
    u = np.array([s["equator_ux"] for s in steps])
    p = np.array([s["pressure_inner"] for s in steps])
    k = int(np.argmax(p))
    assert 0 < k < len(p) - 1
    a, b, c = np.polyfit(u[k - 1:k + 2], p[k - 1:k + 2], 2)
    assert c - b * b / (4 * a) == pytest.approx(p_ref, rel=0.01)
    assert -b / (2 * a) == pytest.approx(u_ref, rel=0.01)
    assert np.max(np.abs(p / pressure_curve("mooney_rivlin", params, u) - 1)) < 0.01
    assert u[-1] >= 1.3 * u_ref * (1 - 1e-9) and p[-1] < p.max()
    assert writer.phases[1]["status"] == "completed" and writer.phases[1]["steps"]["control"] == control
    assert {"arclength": "load control, then arc-length continuation",
            "displacement": "load control, then displacement control"}[control] in sim.effects


class Stop(Exception):
    pass


@pytest.mark.slow
@pytest.mark.mpi
def test_restart_inside_the_arc_length_phase_equals_the_uninterrupted_run(out_dir):
    u_ref, _ = limit_point("mooney_rivlin", dict(PAPER, K=5.0, i2="usual"))
    full = Simulation(two_phases(out_dir / "full", u_ref), MPI.COMM_WORLD, log=quiet).run()
    seen = []

    def stop_in_the_second_phase(message):
        if message.startswith("step"):
            seen.append(message)
            if len(seen) == 7:  # 4 load steps, then the 3rd arc-length step
                assert "'through the limit point'" in message
                raise Stop

    with pytest.raises(Stop):
        Simulation(two_phases(out_dir / "cut", u_ref), MPI.COMM_WORLD, log=stop_in_the_second_phase).run()
    resumed = Simulation(two_phases(out_dir / "cut", u_ref), MPI.COMM_WORLD, log=quiet).run(resume=True)
    assert len(resumed.steps) == len(full.steps)
    for a, b in zip(full.steps, resumed.steps):
        assert a["phase"] == b["phase"]
        for key in ("load_factor", "pressure_inner", "equator_ux", "pole_uz"):
            assert a[key] == pytest.approx(b[key], rel=1e-10, abs=1e-12), key
    assert [p["after_step"] for p in resumed.limit_points] == [p["after_step"] for p in full.limit_points]
    assert [p["load_factor"] for p in resumed.limit_points] == \
        pytest.approx([p["load_factor"] for p in full.limit_points], rel=1e-10)
