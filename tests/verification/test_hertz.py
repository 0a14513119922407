"""Hertz contact (scenes/hertz.toml: an elastic hemisphere R = 10 mm on an
elastic block, both neo-Hookean E = 10 MPa, ν = 0.3) on a coarse mesh,
against Hertz's solution at the computed force:
a_H = (3FR/4E*)^(1/3), p0_H = 3F/(2π a_H²), E* = E/(2(1−ν²)).

Tolerances (the refinement study is bench/hertz.py → bench/results/hertz.md):
- contact radius: with nodal integration the contact boundary is only
  known to lie between the outermost closed and the first open slave node,
  so |a_FE − a_H| ≤ h, the reference spacing of the slave nodes there
  (measured on the mesh, not chosen);
- peak pressure of the Hertz profile fitted to the closed nodes: the bench
  measures −15.6 % at this mesh (block 8/8, ball 6/6), −10.5 % at the
  scene's default mesh (16/16, 12/12), the error shrinking under
  refinement; the test allows 20 %, i.e. the error at this mesh with a
  margin of a quarter of it (the nodal pressure at the pole itself is
  not asserted with a single pass: it sits ~25 % low at every level, see the bench; with
  two passes it is within 5 %, asserted below).
"""
import numpy as np
import pytest
from mpi4py import MPI

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("bench_hertz", ROOT / "bench" / "hertz.py")
H = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(H)

COARSE = (8, 8, 6, 6)  # block n, m; ball n, m


@pytest.fixture(scope="module")
def coarse(tmp_path_factory):
    sim, writer = H.run(*COARSE, tmp_path_factory.mktemp("hertz"), MPI.COMM_SELF)
    return sim, writer


def test_hertz_contact_radius_within_one_slave_node_spacing(coarse):
    sim, writer = coarse
    assert writer.steps[-1]["load_factor"] == pytest.approx(1.0)
    X, x, gap, p, F = H.slave_profile(sim)
    a_H, p0_H, _ = H.hertz(F)
    geo = H.contact_radius(X, x, gap, p)
    lo, hi = geo["bracket"]
    assert lo < hi
    h = geo["h_slave"]
    assert 0.0 < h < a_H  # the contact zone is resolved by at least one cell
    assert abs(geo["a_gap"] - a_H) <= h
    assert abs(geo["a_fit"] - a_H) <= h
    # Hertz's radius itself lies inside the bracket of closed/open nodes, widened by a node spacing
    assert lo - h <= a_H <= hi


def test_hertz_peak_pressure_of_the_fitted_profile(coarse):
    sim, _ = coarse
    X, x, gap, p, F = H.slave_profile(sim)
    a_H, p0_H, _ = H.hertz(F)
    geo = H.contact_radius(X, x, gap, p)
    assert abs(geo["p0_fit"] / p0_H - 1.0) <= 0.20


def test_single_pass_traction_is_the_slave_pressure(coarse):
    """vertical_tractions with one pass: the force on a slave node over its area is
    its own penalty pressure times the master normal's z component (serial run)."""
    from hypercontact.hertz import vertical_tractions

    sim, _ = coarse
    X, x, gap, p, _ = H.slave_profile(sim)
    X_t, _, t = vertical_tractions(sim, "hertz")
    assert np.array_equal(X, X_t)
    state = sim.contacts[0].evaluate(sim.u)
    n_z = np.asarray(state.normal)[:, 2]
    face = np.asarray(state.feature) == 0
    closed = (gap < 0) & face
    assert closed.sum() >= 10
    assert np.allclose(t[closed], p[closed] * n_z[closed], rtol=1e-9, atol=0)
    pole = int(np.argmin(np.hypot(X[:, 0], X[:, 1])))
    assert closed[pole] and t[pole] == pytest.approx(p[pole], rel=1e-3)
    assert np.all(np.abs(t[(gap > 0) & np.isfinite(t)]) <= 1e-12)


@pytest.mark.slow
def test_two_pass_pole_pressure_within_five_percent_on_the_default_mesh(tmp_path):
    """Single pass, the pole node's pressure is ~24 % below Hertz's p0 at every level
    (bench/results/hertz.md): the block's surface, finer than the ball's at the pole, has nodes
    inside the ball's facets that no slave point holds (bench/results/hertz_pole.md). With
    two passes the block's nodes are slave points too, and the traction at the ball's pole
    node from both passes is within 5 % of p0 at the run's force, on the scene's default mesh."""
    from hypercontact.hertz import vertical_tractions

    sim, writer = H.run(*H.LEVELS["default"], tmp_path, MPI.COMM_SELF, extra=["contact.0.passes=2"])
    assert writer.steps[-1]["load_factor"] == pytest.approx(1.0)
    X, _, t = vertical_tractions(sim, "hertz")
    F = 4.0 * sum(float(c.force(sim.u)[2]) * (1 if c.name == "hertz" else -1) for c in sim.contacts)
    _, p0_H, _ = H.hertz(F)
    pole = int(np.argmin(np.hypot(X[:, 0], X[:, 1])))
    assert t[pole] == pytest.approx(p0_H, rel=0.05)
    # the second pass carries part of it: the first pass's own pressure at the pole is far below
    p_first = np.asarray(sim.contacts[0].evaluate(sim.u).pressure)
    assert p_first[pole] < 0.6 * t[pole]


@pytest.mark.mpi
def test_hertz_two_ranks_equal_serial(out_dir, tmp_path):
    """The coarse Hertz scene on the ranks of COMM_WORLD equals a serial run."""
    comm = MPI.COMM_WORLD
    if comm.size < 2:
        pytest.skip("needs mpirun -n 2")
    par, _ = H.run(*COARSE, out_dir, comm)
    f_par = par.contacts[0].force(par.u)
    ser, _ = H.run(*COARSE, tmp_path / "serial", MPI.COMM_SELF)
    f_ser = ser.contacts[0].force(ser.u)
    assert f_par[2] > 0.0
    assert np.allclose(f_par, f_ser, rtol=1e-8, atol=1e-12)
    probe_par = par.probes["top"].value(par.u)
    probe_ser = ser.probes["top"].value(ser.u)
    assert np.allclose(probe_par, probe_ser, rtol=1e-8, atol=1e-12)


def test_approach_against_a_rigid_plane_is_the_plane_against_the_sphere_top(tmp_path):
    """hertz.measure against a rigid obstacle: δ = the obstacle's displacement − the sphere
    top's (here the plane moves up 0.1 and the flat top is held: δ = 0.1)."""
    import tomllib

    from hypercontact import hertz, scene
    from hypercontact.simulation import Simulation

    data = tomllib.loads((ROOT / "scenes" / "hertz.toml").read_text())
    data["mesh"].update(n=2, m=2, grading=[1.0, 1.0, 1.0])
    data["body"][0].update(n=4, m=4, grading=[1.0, 1.0, 1.0])
    data["bc"][-1]["motion"] = [0.0, 0.0, 0.0]
    data["contact"] = [{"name": "hertz", "surface": "ball.curved", "obstacle": "plane", "point": [0, 0, 0],
                        "normal": [0, 0, 1], "motion": [0, 0, 0.1], "eps_n": 1000.0}]
    data["output"] = {**data.get("output", {}), "dir": str(tmp_path), "xdmf": False}
    sc = scene.load(data)
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    sim.run()
    measured = hertz.measure(sim, hertz.geometry(sc))
    assert measured["delta"] == pytest.approx(0.1, rel=1e-12)
    assert measured["F"] > 0
