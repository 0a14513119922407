"""Hard cases converge or stop with a diagnosis, and their results are
checked (issue: hard cases stay numerically stable). Coarse meshes: each
case runs in seconds."""
import tomllib

import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

from conftest import ROOT


def punch(**steps):
    data = tomllib.loads((ROOT / "scenes" / "punch.toml").read_text())
    data["mesh"].update(n=8, m=2)
    data["output"]["xdmf"] = False
    data["steps"].update(steps)
    return data


def run(data, out, overrides=()):
    sc = scene.load(data, [f"output.dir={out}", *overrides])
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    return sim, sim.run(out_dir=str(out))


def test_steps_ten_times_larger_are_cut_back_to_the_same_result(tmp_path):
    """Δλ = 1 in one step (ten times the default first step): the step
    controller cuts back as needed and ends where small steps end."""
    _, small = run(punch(), tmp_path / "small")
    _, large = run(punch(initial=1.0, max=1.0), tmp_path / "large")
    f_small, f_large = small.steps[-1]["punch_fz"], large.steps[-1]["punch_fz"]
    assert large.steps[-1]["load_factor"] == pytest.approx(1.0)
    # load-path dependence at the punch edge is real (docs/verification.md §1:
    # +0.9 % at 32x32x8 for smaller steps)
    assert abs(f_large - f_small) < 0.02 * abs(f_small)


def test_penetration_falls_monotonically_over_six_decades_of_penalty(tmp_path):
    """Automatic penalty with factors 1 … 1e6: every run converges (cutting
    back if it must) and the largest penetration falls monotonically,
    roughly like 1/ε_N."""
    penetrations = []
    for k, s in enumerate([1.0, 1e2, 1e4, 1e6]):
        sim, _ = run(punch(), tmp_path / f"s{k}", [f"contact.0.eps_n=0", "contact.1.eps_n=0",
                                                   f"contact.0.penalty_factor={s}", f"contact.1.penalty_factor={s}",
                                                   # the sharp law: smoothed, the limit gap is the band's δ
                                                   "contact.0.smoothing=0", "contact.1.smoothing=0"])
        penetrations.append(max(c.max_penetration(sim.u) for c in sim.contacts))
    assert all(a > b for a, b in zip(penetrations, penetrations[1:])), penetrations
    assert penetrations[0] / penetrations[-1] > 1e4


def test_initial_penetration_is_pushed_out(tmp_path):
    """The punch starts 0.2 mm inside the plate (λ = 0: no motion yet): the
    first step pushes the surface out to the penalty's penetration."""
    data = punch()
    for key in ("lo", "hi"):
        data["contact"][0][key][2] -= 0.2
    sim, w = run(data, tmp_path)
    closed = w.steps[0]["punch_closed_nodes"]
    assert closed > 0
    assert sim.contacts[0].max_penetration(sim.u) < 0.05


def test_bodies_that_separate(tmp_path):
    """The upper block, meshed in touch with the lower one (closed at the
    start), is pulled away: the contact opens completely, its force goes to
    zero, nothing is NaN."""
    data = tomllib.loads((ROOT / "scenes" / "blocks.toml").read_text())
    data["pressure"] = []
    data["bc"].append({"surface": "top.zmax", "fix": ["z"], "motion": [0.0, 0.0, 0.05]})
    sim, w = run(data, tmp_path, ["output.xdmf=false"])
    c = sim.contacts[0]
    assert c.num_closed(sim.u) == 0
    assert np.allclose(c.force(sim.u), 0.0)
    assert np.all(np.isfinite(sim.u.x.array))


def test_active_set_changes_are_counted_and_reported(tmp_path):
    """Each step's count of Newton iterations whose contact active set
    changed is in summary.json; past the threshold steps.chatter_warning the
    run says so."""
    import json

    messages = []
    data = punch()
    data["steps"]["chatter_warning"] = 1
    sc = scene.load(data, [f"output.dir={tmp_path}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=messages.append)
    w = sim.run(out_dir=str(tmp_path))
    steps = json.loads((tmp_path / "summary.json").read_text())["steps"]
    changes = [s["active_set_changes"] for s in steps]
    assert changes[0] >= 1  # the first step closes the contact: its active set grows
    assert all(0 <= c <= s["newton_iterations"] for c, s in zip(changes, steps))
    assert sum("chattering" in m for m in messages) == sum(c >= 1 for c in changes)
    assert len(w.steps) == len(steps)


@pytest.mark.parametrize("ratio", [10.0, 1e2, 1e3, 1e4])
def test_near_incompressible_sphere_limit_pressure(ratio, tmp_path):
    """K/μ = 10 … 10⁴ on the inflated sphere with the locking-free mixed
    formulation (quadratic, 4 × 4 × 1 octant): arc length passes the limit
    point and its pressure is within 1 % of the 1D oracle's for that K."""
    from hypercontact.sphere1d import PAPER, limit_point

    mu = 2.0 * (PAPER["alpha1"] + PAPER["alpha2"])
    K = ratio * mu
    params = dict(PAPER, K=K, i2="usual")
    u_ref, p_ref = limit_point("mooney_rivlin", params)
    sc = scene.load(ROOT / "scenes" / "sphere.toml", [
        f"output.dir={tmp_path}", "output.xdmf=false", f"material.parameters.K={K}", "mesh.n=4", "mesh.m=1",
        'discretisation.formulation="mixed"', "discretisation.quadrature_degree=4", "steps.max=0.15",
        f"steps.stop_value={1.2 * u_ref}"])
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    writer = sim.run()
    assert len(writer.limit_points) == 1
    p = np.array([s["pressure_inner"] for s in writer.steps])
    assert p.max() == pytest.approx(p_ref, rel=0.01)
