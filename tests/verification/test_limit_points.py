"""Limit points located, not sampled (docs/method.md §8): where Δλ changes
sign, continuation searches the two steps around the turn for the extremum of
λ, re-solving each from its saved start with smaller sizes. The located
point is checked against the maximum of the same mesh's curve traced with very
small steps by the other constraint (displacement control of a probe, located
off), without and with contact."""
import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation


def run(name, out, overrides):
    sc = scene.load(ROOT / "scenes" / f"{name}.toml", [f"output.dir={out}", "output.xdmf=false", *overrides])
    return Simulation(sc, MPI.COMM_SELF, log=quiet).run()


def column(writer, key):
    return np.array([s[key] for s in writer.steps])


def finely_traced_maximum(writer, probe):
    """The largest sampled λ of a finely stepped run, and the probe's displacement
    at the vertex of the parabola through it and its two neighbours in (u, λ)."""
    lam, u = column(writer, "load_factor"), column(writer, probe)
    k = int(np.argmax(lam))
    assert 0 < k < len(lam) - 1, "the fine run must bracket the maximum"
    a, b, _ = np.polyfit(u[k - 1:k + 2], lam[k - 1:k + 2], 2)
    return lam[k], -b / (2 * a), np.diff(u[k - 1:k + 2]).max()


CASES = {
    # free sphere, K = 200 (the case): the equator's radial displacement is the path's measure
    "sphere": (["mesh.n=8", "mesh.m=2", "material.parameters.K=200"], "equator", "x", 42.0),
    # against the rigid plane: the apex is held, the pole keeps moving; the limit has contact active
    "sphere_plane": (["mesh.n=8", "mesh.m=1"], "pole", "z", 63.0),
}


@pytest.mark.parametrize("name", CASES)
def test_located_limit_is_the_maximum_of_the_finely_traced_curve(name, tmp_path):
    """Arc length with the scene's own step sizes locates the maximum of λ to
    1e-4 in load and 0.5 % in the probe's displacement of the same mesh's curve
    traced by displacement control in steps of 1/250 of the way (located off)."""
    sets, probe, axis, stop = CASES[name]
    coarse = run(name, tmp_path / "coarse", sets)
    assert len(coarse.limit_points) == 1
    limit = coarse.limit_points[0]
    lam = column(coarse, "load_factor")
    assert limit["kind"] == "maximum" and limit["located"]
    assert limit["sampled_load_factor"] == lam.max()
    assert limit["load_factor"] >= lam.max()
    assert limit["bracket"] < 1.0 and limit["re_solves"] >= 1
    fine = run(name, tmp_path / "fine", sets + [
        "steps.control=displacement", f"steps.stop_probe={probe}", f"steps.stop_component={axis}",
        f"steps.stop_value={stop}", "steps.initial=0.004", "steps.max=0.004", "steps.max_steps=400",
        "steps.locate_limits=false"])
    lam_fine, u_fine, spacing = finely_traced_maximum(fine, f"{probe}_u{axis}")
    assert spacing < 0.005 * u_fine
    assert fine.limit_points and not fine.limit_points[0]["located"]
    u_located = limit["probes"][probe]["xyz".index(axis)]
    assert limit["load_factor"] == pytest.approx(lam_fine, rel=1e-4)
    assert u_located == pytest.approx(u_fine, rel=5e-3)
    # the sampled maximum of the coarse run is further off than the located point
    assert abs(limit["sampled_load_factor"] / lam_fine - 1) > abs(limit["load_factor"] / lam_fine - 1)


def test_displacement_control_locates_the_same_limit(tmp_path):
    """The limit point is a property of the discrete equations, not of the
    constraint that traces them: displacement control of the equator locates the
    arc length's point (to the location tolerance)."""
    sets = CASES["sphere"][0]
    arc = run("sphere", tmp_path / "arc", sets + ["steps.stop_value=50"])
    disp = run("sphere", tmp_path / "disp", sets + ["steps.control=displacement", "steps.stop_value=50"])
    a, d = arc.limit_points[0], disp.limit_points[0]
    assert a["located"] and d["located"]
    assert d["load_factor"] == pytest.approx(a["load_factor"], rel=1e-6)
    assert d["probes"]["equator"][0] == pytest.approx(a["probes"]["equator"][0], rel=5e-3)


def test_locating_leaves_the_path_unchanged(tmp_path):
    """The re-solves start from the step's saved state and the run goes on from
    the step it had taken: every step is the same with and without locating."""
    sets = CASES["sphere_plane"][0] + ["contact.0.mu=0.3", "steps.stop_value=70"]
    on = run("sphere_plane", tmp_path / "on", sets)
    off = run("sphere_plane", tmp_path / "off", sets + ["steps.locate_limits=false"])
    assert on.limit_points[0]["located"] and on.limit_points[0]["re_solves"] >= 1
    assert on.limit_points[0]["load_factor"] > on.limit_points[0]["sampled_load_factor"]
    assert off.limit_points[0]["load_factor"] == off.limit_points[0]["sampled_load_factor"]
    assert len(on.steps) == len(off.steps)
    for key in ("load_factor", "pole_uz", "wall_fx", "wall_dissipation"):
        assert column(on, key) == pytest.approx(column(off, key), rel=1e-10, abs=1e-12), key
