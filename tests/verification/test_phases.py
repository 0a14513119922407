"""Load histories in phases ([[phase]]) against closed forms.

A rigid block (G ≫ ε h) is pressed δ into a rigid frictional plane by its
top face (so every bottom node carries the same pressure p = ε_N δ / (1 +
ε_N h / E), the block's compression taking its small share of δ, and
N = p A), slid forward by d and back by d. The reference is the 1D
Coulomb law with an elastic tangential spring ε_T (the penalty), independent
of the code: a node sticks until its spring carries μ p, i.e. for
c = μ p / ε_T of motion, then slips; at the reversal the spring goes from
+μ p to −μ p (2c of motion in stick) and the node slips back. So over the
closed cycle every node slips 2d − 3c, the dissipation is μ N (2d − 3c)
(within 1 % of 2 μ N d when 3c < 0.02 d), the tangential force is −μ N
(against the motion) while sliding forward and +μ N while sliding back, and
the block ends with its spring at +μ p: each node's tangential traction on
the body points along +x.

Also: two phases that join without a change give the one-phase run, and a
run stopped inside its second phase and resumed gives the uninterrupted run."""
import csv
import json
import re

import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.results import ResultsWriter
from hypercontact.simulation import Simulation

G = 1.0e6           # shear modulus of the (rigid) block, MPa
EPS_N, EPS_T = 10.0, 100.0
MU = 0.3
DELTA = 0.01        # the top pressed δ down: p = ε_N δ on every bottom node
D = 0.2             # slid forward by d, then back by d
E = 9 * G * G / (3 * G + G)  # Young's modulus of the block (K = G)
P = EPS_N * DELTA / (1 + EPS_N * 1.0 / E)  # δ shared by the penalty and the block's compression (h = 1)
N = P * 1.0         # the 1 × 1 bottom
C = MU * P / EPS_T  # the spring's stroke to the slip limit


@pytest.fixture(scope="module", autouse=True)
def no_pictures():
    with pytest.MonkeyPatch.context() as m:
        m.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})
        yield


def cycle_scene(out, phases=None, xdmf=False):
    """The block and its three phases: press, forward, back."""
    if phases is None:
        phases = [{"name": "press", "bc": {"lid": [0.0, 0.0, -DELTA]}, "steps": {"initial": 0.5, "max": 0.5}},
                  {"name": "forward", "bc": {"lid": [D, 0.0, -DELTA]}},
                  {"name": "back", "bc": {"lid": [0.0, 0.0, -DELTA]}}]
    return {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 2, "m": 1},
        "material": {"law": "neo_hookean", "parameters": {"mu": G, "K": G}},
        "bc": [{"name": "lid", "surface": "zmax", "fix": ["x", "y", "z"]}],
        "contact": [{"name": "base", "surface": "zmin", "obstacle": "plane", "point": [0.0, 0.0, 0.0],
                     "normal": [0.0, 0.0, 1.0], "eps_n": EPS_N, "eps_t": EPS_T, "mu": MU}],
        "steps": {"initial": 0.1, "max": 0.1},
        "solver": {"rtol": 1e-12, "atol": 1e-13, "max_it": 30},
        "output": {"dir": str(out), "xdmf": xdmf},
        "phase": phases,
    }


def rows(out):
    with open(out / "curves.csv") as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def run(data, log=quiet, resume=False):
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=log)
    return sim, sim.run(resume=resume)


def test_closed_cycle_dissipates_two_mu_n_d_and_reverses_the_friction_force(out_dir):
    sim, writer = run(cycle_scene(out_dir))
    r = rows(out_dir)
    phase = np.array([row["phase"] for row in r])
    assert sorted(set(phase)) == [1, 2, 3]
    # the accumulated parameter τ runs on through the phases: 0..1, 1..2, 2..3
    assert np.all(np.diff([row["time"] for row in r]) > 0) and r[-1]["time"] == pytest.approx(3.0, abs=1e-12)
    # N is the closed form in every step after the press
    fz = np.array([row["base_fz"] for row in r])
    assert np.allclose(fz[phase > 1], N, rtol=1e-6)
    # the tangential force: −μN sliding forward, +μN sliding back (after the 2c of stick at the reversal)
    fx = np.array([row["base_fx"] for row in r])
    last_forward = np.flatnonzero(phase == 2)[-1]
    assert fx[last_forward] == pytest.approx(-MU * N, rel=1e-6)
    assert fx[-1] == pytest.approx(+MU * N, rel=1e-6)
    # the dissipation of the closed cycle
    dissipation = r[-1]["dissipation"]
    assert dissipation == pytest.approx(2 * MU * N * D, rel=0.01)
    assert dissipation == pytest.approx(MU * N * (2 * D - 3 * C), rel=1e-5)
    # where the block ends: each node has slipped 2d − 3c, and its spring holds +μ p (traction on the body +x)
    (base,) = sim.contacts
    slip = base.law.slip_accumulated
    assert len(slip) == 0 or np.allclose(slip, 2 * D - 3 * C, rtol=1e-5)
    traction, pressure = -base.state.traction, base.state.pressure  # on the body
    assert len(slip) == 0 or np.allclose(pressure, P, rtol=1e-5)  # a rigid block: to ε_N h / E ≈ 4e-6
    assert len(slip) == 0 or np.allclose(traction[:, 0], MU * pressure, rtol=1e-9)  # on the cone, along +x
    assert np.all(np.abs(traction[:, 1:]) <= 1e-9 * MU * P)
    summary = json.loads((out_dir / "summary.json").read_text()) if MPI.COMM_WORLD.rank == 0 else None
    if summary is not None:
        assert [p["name"] for p in summary["phases"]] == ["press", "forward", "back"]
        assert all(p["status"] == "completed" for p in summary["phases"])
        assert summary["phases"][1]["first_step"] == summary["phases"][0]["last_step"] + 1


def test_two_phases_that_join_without_a_change_equal_one_phase(out_dir):
    one = cycle_scene(out_dir / "one", [
        {"name": "press", "bc": {"lid": [0.0, 0.0, -DELTA]}, "steps": {"initial": 0.5, "max": 0.5}},
        {"name": "forward", "bc": {"lid": [D, 0.0, -DELTA]}, "steps": {"initial": 0.1, "max": 0.1}}])
    two = cycle_scene(out_dir / "two", [
        {"name": "press", "bc": {"lid": [0.0, 0.0, -DELTA]}, "steps": {"initial": 0.5, "max": 0.5}},
        {"name": "forward 1", "bc": {"lid": [D / 2, 0.0, -DELTA]}, "steps": {"initial": 0.2, "max": 0.2}},
        {"name": "forward 2", "bc": {"lid": [D, 0.0, -DELTA]}, "steps": {"initial": 0.2, "max": 0.2}}])
    sim1, _ = run(one)
    sim2, _ = run(two)
    r1, r2 = rows(out_dir / "one"), rows(out_dir / "two")
    assert len(r1) == len(r2) == 12
    for a, b in zip(r1, r2):
        for key in ("base_fx", "base_fz", "dissipation", "base_stick_nodes", "base_slip_nodes"):
            assert a[key] == pytest.approx(b[key], rel=1e-10, abs=1e-14), key
    diff = np.abs(sim1.w.x.array - sim2.w.x.array).max()
    assert MPI.COMM_WORLD.allreduce(diff, op=MPI.MAX) <= 1e-10 * D


class Stop(Exception):
    pass


@pytest.mark.mpi
def test_restart_inside_the_second_phase_equals_the_uninterrupted_run(out_dir):
    sim_full, full = run(cycle_scene(out_dir / "full"))
    steps = []

    def stop_inside_forward(message):
        if message.startswith("step"):
            steps.append(message)
            if len(steps) == 6:  # press: 2 steps; the 4th step of "forward"
                assert "'forward'" in message
                raise Stop

    with pytest.raises(Stop):
        run(cycle_scene(out_dir / "cut", xdmf=True), log=stop_inside_forward)
    sim_res, resumed = run(cycle_scene(out_dir / "cut", xdmf=True), resume=True)
    assert len(resumed.steps) == len(full.steps)
    for a, b in zip(full.steps, resumed.steps):
        assert (a["phase"], a["load_factor"]) == (b["phase"], pytest.approx(b["load_factor"], rel=1e-12))
        for key in ("base_fx", "base_fz", "dissipation"):
            assert a[key] == pytest.approx(b[key], rel=1e-10, abs=1e-14), key
    diff = np.abs(sim_full.w.x.array - sim_res.w.x.array).max()
    assert MPI.COMM_WORLD.allreduce(diff, op=MPI.MAX) <= 1e-10 * D
    (c_full,), (c_res,) = sim_full.contacts, sim_res.contacts
    assert np.allclose(c_full.law.slip_accumulated, c_res.law.slip_accumulated, rtol=1e-10, atol=1e-14)
    if MPI.COMM_WORLD.rank == 0:
        summary = json.loads((out_dir / "cut" / "summary.json").read_text())
        assert summary["status"] == "completed"
        assert [p["status"] for p in summary["phases"]] == ["completed"] * 3
        # fields.xdmf: one time per step, the accumulated τ (λ restarts in each phase), across the resume
        text = (out_dir / "cut" / "fields.xdmf").read_text()
        times = sorted({float(t) for t in re.findall(r'<Time Value="([^"]+)"', text)})
        assert times == pytest.approx([s["time"] for s in full.steps], abs=1e-12)


@pytest.mark.mpi
def test_a_contact_switched_off_and_on_starts_its_friction_afresh(out_dir):
    """Press, slide forward by d, switch the base off, switch it on (its
    penalty ramps in over the phase: the block stands still, so no traction
    builds) and slide back by d. Switched off, the base carries nothing
    (the stiff block hangs from its lid); switched on, every node starts
    open with no anchor, so on the way back it sticks for c (from 0 to
    μ p), not 2c (from −μ p to +μ p) as in the closed cycle: it slips
    2 (d − c) in all and the base dissipates 2 μ N (d − c) — μ N c more
    than the closed cycle's μ N (2d − 3c), far beyond the 1e-5 asserted."""
    phases = [{"name": "press", "bc": {"lid": [0.0, 0.0, -DELTA]}, "steps": {"initial": 0.5, "max": 0.5}},
              {"name": "forward", "bc": {"lid": [D, 0.0, -DELTA]}},
              {"name": "off", "contact": {"base": {"active": False}}, "steps": {"initial": 0.5, "max": 0.5}},
              {"name": "on", "contact": {"base": {"active": True}}, "steps": {"initial": 0.25, "max": 0.25}},
              {"name": "back", "bc": {"lid": [0.0, 0.0, -DELTA]}}]
    data = cycle_scene(out_dir, phases)
    data["solver"]["atol"] = 1e-9  # the hanging stiff block's residual stalls at its round-off (~1e-10)
    lines = []
    sim, writer = run(data, log=lines.append)
    assert any("phase 3 'off'" in m and "contact 'base' switched off" in m for m in lines)
    assert any("phase 4 'on'" in m and "contact 'base' switched on" in m for m in lines)
    r = rows(out_dir)
    off = [row for row in r if row["phase"] == 3]
    forward_end = [row for row in r if row["phase"] == 2][-1]
    assert len(off) == 2
    for row in off:  # nothing carried, nothing dissipated while off
        assert row["base_fx"] == row["base_fz"] == row["base_closed_nodes"] == 0.0
        assert row["dissipation"] == forward_end["dissipation"]
    on = [row for row in r if row["phase"] == 4]
    for row in on:  # the penalty ramps in: p = s ε_N δ / (1 + s ε_N h / E), no traction, no dissipation
        s = row["load_factor"]
        assert row["base_fz"] == pytest.approx(s * EPS_N * DELTA / (1 + s * EPS_N * 1.0 / E), rel=1e-6)
        assert abs(row["base_fx"]) <= 1e-6 * MU * N
    back = [row for row in r if row["phase"] == 5]
    assert all(row["base_fz"] == pytest.approx(N, rel=1e-6) for row in back)
    assert back[-1]["base_fx"] == pytest.approx(+MU * N, rel=1e-6)
    assert r[-1]["dissipation"] == pytest.approx(2 * MU * N * (D - C), rel=1e-5)
    (base,) = sim.contacts
    slip = base.law.slip_accumulated
    assert len(slip) == 0 or np.allclose(slip, 2 * (D - C), rtol=1e-5)


def test_a_contact_that_starts_switched_off_acts_from_the_phase_that_switches_it_on(out_dir):
    data = cycle_scene(out_dir, [
        {"name": "press", "bc": {"lid": [0.0, 0.0, -DELTA]}, "steps": {"initial": 0.5, "max": 0.5}},
        {"name": "touch", "contact": {"base": {"active": True}}, "steps": {"initial": 0.5, "max": 0.5}}])
    data["contact"][0]["active"] = False
    data["solver"]["atol"] = 1e-9  # the displaced stiff block's residual stalls at its round-off (~1e-10)
    run(data)
    r = rows(out_dir)
    assert [row["base_fz"] for row in r if row["phase"] == 1] == [0.0, 0.0]
    touch = [row for row in r if row["phase"] == 2]
    assert [row["load_factor"] for row in touch] == [0.5, 1.0]
    for row in touch:  # the overclosure δ taken up as the penalty ramps in
        s = row["load_factor"]
        assert row["base_fz"] == pytest.approx(s * EPS_N * DELTA / (1 + s * EPS_N * 1.0 / E), rel=1e-6)
    assert touch[-1]["base_fz"] == pytest.approx(N, rel=1e-6)


def test_lift_off_releases_the_friction_spring_by_the_backward_euler_return_map(out_dir):
    """Press, slide forward by d (each node's spring at μ p), then lift the
    lid from −δ to +δ in 10 steps: the penetration falls by δ/5 per step to
    0 at the 5th and the block lifts off (no force, no closed node). The
    shrinking cone μ p_i makes each spring slip back to it; by the
    return map (backward Euler, the 1D oracle worked by hand) step i
    dissipates μ p_i (μ p_{i−1} − μ p_i) / ε_T per unit area with
    p_i = P (1 − i/5): in all μ² P² / ε_T × Σ_i (1 − i/5)/5 = 0.4 μ N c."""
    data = cycle_scene(out_dir, [
        {"name": "press", "bc": {"lid": [0.0, 0.0, -DELTA]}, "steps": {"initial": 0.5, "max": 0.5}},
        {"name": "forward", "bc": {"lid": [D, 0.0, -DELTA]}},
        {"name": "lift", "bc": {"lid": [D, 0.0, +DELTA]}}])
    data["solver"]["atol"] = 1e-9  # the lifted stiff block's residual stalls at its round-off (~1e-10)
    data["contact"][0]["smoothing"] = 0.0  # the 5th step lands on g = 0: the sharp law's p = 0 there
    sim, _ = run(data)
    r = rows(out_dir)
    lift = [row for row in r if row["phase"] == 3]
    forward_end = [row for row in r if row["phase"] == 2][-1]
    assert len(lift) == 10
    for i, row in enumerate(lift[:5], start=1):  # still touching: p_i = P (1 − i/5), on the cone
        assert row["base_fz"] == pytest.approx(N * (1 - i / 5), rel=1e-5, abs=1e-9 * N)
        assert row["base_fx"] == pytest.approx(-MU * row["base_fz"], rel=1e-5, abs=1e-9 * N)
    for row in lift[5:]:  # lifted off
        assert row["base_fz"] == row["base_fx"] == row["base_closed_nodes"] == 0.0
    released = lift[-1]["dissipation"] - forward_end["dissipation"]
    # to the block's shear compliance: its bottom follows the spring by ε_T h / G = 1e-4 of the slip
    assert released == pytest.approx(0.4 * MU * N * C, rel=1e-3)
    assert released != pytest.approx(0.5 * MU * N * C, rel=0.1)  # not the continuous ∫ μ p dp μ/ε_T
    (base,) = sim.contacts
    assert np.all(base.state.traction == 0.0)
