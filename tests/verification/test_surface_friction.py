"""Coulomb friction against a deformable master surface (FrictionalSurfaceContact,
C++ evaluate_surface_friction), checked against references independent of
the friction code:

- a small elastic block pressed onto a larger deformable block and dragged
  sideways by its top: sticks below μN, then slides with every slave point on
  the Coulomb cone (Σ w|t| = μ Σ w p_N to 1e-6) and the resultant tangential
  force at μN; the dissipation is never negative and in steady sliding equals
  μN × the drag increment (energy balance: the elastic energy is steady);
- the assembled whole-system Jacobian (volume + normal + friction, old-facet
  columns included) against central differences of the assembled residual,
  with points in stick and in slip;
- μ = 0 builds no friction object, calls no friction kernel, and the
  frictional assembly with μ = 0 equals the frictionless one exactly.
"""
import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import _cpp, scene
from hypercontact import _dolfinx as dfx
from reference.finite_differences import constrained_dofs, simulation_jacobian_error
from hypercontact.phases import run_phase
from hypercontact.simulation import Simulation
from hypercontact.solve.newton_solver import NewtonSolver
from hypercontact.contact.factory import _surface_law
from hypercontact.contact.pair import Contact

SCENES = __import__("pathlib").Path(__file__).resolve().parents[2] / "scenes"
MU, PRESS = 0.3, 0.01
STICK, SLIP = 1, 2


def slider_scene(mu=MU):
    """The blocks scene with a 0.5 × 0.5 × 0.25 block (4 × 4 facets) on the
    1 × 1 × 0.5 lower block (4 × 4), both bottoms/tops driven, no pressure."""
    sc = scene.load(SCENES / "blocks.toml", overrides=[
        "output.xdmf=false", f"contact.0.mu={mu}", "contact.0.eps_n=100", "steps.initial=0.5", "steps.max=0.5",
        # the sharp law: its reported pressure ε_N <-g> is the friction cone's; smoothed, the normal
        # element reports ε_N P(ĝ) with the signed distance ĝ, which differs from g off a facet's face
        "contact.0.smoothing=0"])
    b = sc["body"][0]
    b["size"], b["origin"], b["n"], b["m"] = [0.5, 0.5, 0.25], [0.25, 0.25, 0.5], 4, 2
    sc["bc"] = [{"surface": "zmin", "fix": ["x", "y", "z"], "motion": [0.0, 0.0, 0.0]},
                {"surface": "top.zmax", "fix": ["x", "y", "z"], "motion": [0.0, 0.0, -PRESS]}]
    sc["pressure"] = []
    sc["output"]["probes"] = {}
    return sc


def forces(c):
    """(Σ w|t|, resultant tangential force on the slider, N = Σ w p_N, states)
    at the last converged step."""
    s = c.law.committed
    w, t = c.geometry.point_area, np.asarray(s.traction)
    return ((w * np.linalg.norm(t, axis=1)).sum(), -(w[:, None] * t).sum(axis=0),
            (w * np.asarray(s.pressure)).sum(), np.asarray(s.state))


def test_block_sticks_below_mu_n_then_slides_at_mu_n(tmp_path):
    sim = Simulation(slider_scene(), MPI.COMM_SELF, log=lambda *a, **k: None)
    c = sim.contacts[0]
    assert c.frictional and c.deformable
    run_phase(sim, {1: [0.0, 0.0, -PRESS]}, tmp_path / "press")
    dissipation = [c.law.dissipation_step]
    # stick: a drag of 0.002 (a fifth of the slip onset) leaves most points stuck, |F_t| < μN
    run_phase(sim, {1: [0.002, 0.0, -PRESS]}, tmp_path / "stick")
    dissipation.append(c.law.dissipation_step)
    _, Ft, N, state = forces(c)
    assert N > 0 and np.count_nonzero(state == STICK) > 2 * np.count_nonzero(state == SLIP)
    assert np.linalg.norm(Ft) < 0.5 * MU * N and Ft[0] < 0  # resists the drag (+x)
    # slide: every closed point on the cone; the resultant at μN
    for k, dx in enumerate((0.02, 0.03)):
        run_phase(sim, {1: [dx, 0.0, -PRESS]}, tmp_path / f"slide{k}")
        dissipation.append(c.law.dissipation_step)
    sum_t, Ft, N, state = forces(c)
    closed = np.asarray(c.law.committed.pressure) > 0
    assert np.all(state[closed] == SLIP) and closed.sum() >= 20
    assert abs(sum_t - MU * N) < 1e-6 * MU * N
    assert abs(np.linalg.norm(Ft) - MU * N) < 1e-3 * MU * N
    assert abs(Ft[0] + MU * N) < 1e-3 * MU * N
    assert min(dissipation) >= 0.0
    # steady sliding: the step's dissipation is the work of the friction force over the drag step
    # (the last phase: two steps of 0.005), within the penalty and master-strain effects (< 2 %)
    assert abs(c.law.dissipation_step - MU * N * 0.005) < 0.02 * MU * N * 0.005


def test_assembled_jacobian_matches_finite_differences_in_stick_and_slip(tmp_path):
    """Volume + normal + friction: after a converged drag step (history set,
    some points slipping), a perturbed state; every free entry of the
    assembled matrix equals the central difference of the assembled
    residual to 1e-6 of the largest entry."""
    sc = slider_scene()
    sc["body"][0]["n"] = 3
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    run_phase(sim, {1: [0.0, 0.0, -PRESS]}, tmp_path / "press")
    run_phase(sim, {1: [0.004, 0.0, -PRESS]}, tmp_path / "drag")
    c = sim.contacts[0]
    # The prescribed values stay where the drag phase left them (Simulation.set_load_factor would
    # reset them to λ × the scene's motion: the Dirichlet lifting would then differ from the
    # solution's boundary values and put a spurious term into the finite differences).
    rng = np.random.default_rng(5)
    constrained = constrained_dofs(sim)
    u = sim.w.x.array
    u[~constrained] += 2e-4 * rng.standard_normal(np.count_nonzero(~constrained))
    X = dfx.node_coordinates(sim.V)
    moving = np.zeros(u.size, bool)
    moving.reshape(-1, 3)[X[:, 2] > 0.5 + 1e-9, 0] = True
    u[moving & ~constrained] += 1e-3  # the slider moves on: more points slip (driven dofs stay put)
    sim.update_pairing(fresh=True)
    state = np.asarray(c.evaluate(sim.u).state)
    assert np.count_nonzero(state == STICK) >= 2 and np.count_nonzero(state == SLIP) >= 2
    assert np.any(c.law.history.facet != np.asarray(c.evaluate(sim.u).facet))  # old-facet columns matter
    err, scale, J, free = simulation_jacobian_error(sim, constrained)
    assert err < 1e-6 * scale
    assert np.abs(J - J.T)[np.ix_(free, free)].max() > 1e3 * err  # the friction tangent is not symmetric


def test_mu_zero_is_exactly_frictionless(tmp_path, monkeypatch):
    """μ = 0: no friction object and no friction kernel call; and the
    frictional assembly run with μ = 0 adds exactly the frictionless
    residual and tangent."""
    def forbidden(*args, **kwargs):
        raise AssertionError("a friction kernel was called with mu = 0")

    sc = slider_scene(mu=0.0)
    with monkeypatch.context() as m:
        m.setattr(_cpp, "evaluate_surface_friction", forbidden)
        sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
        run_phase(sim, {1: [0.0, 0.0, -PRESS]}, tmp_path / "press")
    assert not any(c.frictional for c in sim.contacts)
    # the same state through the frictional assembly with μ = 0: the same geometry with the Coulomb law
    plain = sim.contacts[0]
    settings, candidates = sim.contact_settings[0], plain.geometry.candidates
    law = _surface_law(dict(sc["contact"][0], mu=1.0), settings, plain.geometry, plain.comm, 1.0)  # μ > 0 builds it
    law.mu = 0.0
    plain.geometry.candidates = candidates
    fric = Contact(plain.name, plain.geometry, law, plain.enforcement, plain.eps_n, plain.smoothing, plain.entry)
    p = sim.problem
    out = []
    for contact in (plain, fric):
        b = p.b.duplicate()
        b.zeroEntries()
        contact.prepare(sim.u)
        contact.add_residual(b)
        b.assemble()
        A = p.A.duplicate()
        A.zeroEntries()
        contact.add_tangent(A)
        A.assemble()
        out.append((b.array.copy(), A.convert("dense").getDenseArray().copy()))
    assert np.count_nonzero(out[0][0]) > 0
    assert np.array_equal(out[0][0], out[1][0]) and np.array_equal(out[0][1], out[1][1])


def test_cut_back_restores_the_deformable_master_history_exactly(tmp_path, monkeypatch):
    """In the drag phase, the 2nd Newton solve fails and is cut back, once
    after a real solve that iterated through the friction code and once
    without any iteration: both runs end with the same solution and the same
    history (old facets, ξ, tractions, dissipation)."""
    original_solve = NewtonSolver.solve

    def run(out, real_attempt):
        sim = Simulation(slider_scene(), MPI.COMM_SELF, log=lambda *a, **k: None)
        run_phase(sim, {1: [0.0, 0.0, -PRESS]}, out / "press")
        solve, calls = original_solve, []

        def failing_once(newton, *args):
            calls.append(sim.load_factor.value.item())
            if len(calls) != 2:
                return solve(newton, *args)
            if real_attempt:
                ok, its, norms, reason = solve(newton, *args)
                assert its >= 1
            return False, 0, [], "FORCED_FAILURE"

        with monkeypatch.context() as m:
            m.setattr(NewtonSolver, "solve", failing_once)
            run_phase(sim, {1: [0.004, 0.0, -PRESS]}, out / "drag")
        return sim, calls

    sim_a, calls_a = run(tmp_path / "real", True)
    sim_b, calls_b = run(tmp_path / "none", False)
    assert calls_a == calls_b and calls_a[2] < calls_a[1]  # the 2nd attempt was cut back
    a, b = sim_a.contacts[0], sim_b.contacts[0]
    assert np.abs(sim_a.u.x.array - sim_b.u.x.array).max() <= 1e-10 * np.abs(sim_b.u.x.array).max()
    assert np.array_equal(a.law.history.facet, b.law.history.facet)
    assert np.abs(a.law.history.xi - b.law.history.xi).max() <= 1e-10
    assert np.abs(a.law.history.traction - b.law.history.traction).max() <= 1e-10 * np.abs(b.law.history.traction).max() and np.abs(b.law.history.traction).max() > 0
    assert a.law.dissipation == pytest.approx(b.law.dissipation, rel=1e-10, abs=1e-300)


def test_switched_off_the_pair_carries_nothing_and_forgets_its_master_points(tmp_path):
    """Press the slider, drag it (tractions and master points stored), switch
    the pair off, then on again: off, no force, no closed point, every slave
    point's stored master point and traction gone (facet −1: the kernel then
    takes the current point, t = 0); on again, the blocks press as before."""
    sc = slider_scene()
    for bc in sc["bc"]:
        bc["motion"] = [0.0, 0.0, 0.0]
    sc["bc"][1]["name"] = "slider"
    sc["phase"] = [{"name": "press", "bc": {"slider": [0.0, 0.0, -PRESS]}},
                   {"name": "drag", "bc": {"slider": [0.002, 0.0, -PRESS]}},
                   {"name": "off", "contact": {"interface": {"active": False}}},
                   {"name": "on", "contact": {"interface": {"active": True}}}]
    sc["output"]["dir"] = str(tmp_path)
    sim = Simulation(scene.load(sc), MPI.COMM_SELF, log=lambda *a, **k: None)
    (c,) = sim.contacts
    history = c.law.history
    seen = {}
    commit = c.commit

    def spy():
        commit()
        seen[sim.model.phase] = (history.facet.copy(), np.abs(history.traction).max(), c.on)

    c.commit = spy
    writer = sim.run()
    rows = {k: [s for s in writer.steps if s["phase"] == k] for k in (1, 2, 3, 4)}
    assert np.count_nonzero(seen[1][0] >= 0) > 0 and seen[1][1] > 0  # dragged: master points and tractions
    assert seen[2][2] is False and np.all(seen[2][0] == -1) and seen[2][1] == 0.0
    for s in rows[3]:
        assert s["interface_fz"] == s["interface_closed_nodes"] == 0
    assert seen[3][2] is True and np.count_nonzero(seen[3][0] >= 0) > 0
    n_press, n_on = rows[1][-1]["interface_fz"], rows[4][-1]["interface_fz"]
    assert n_on == pytest.approx(n_press, rel=0.05) and n_on != 0.0
