"""Coulomb friction on a rigid base: a block pressed down and dragged
sideways by its top face. With a wide friction cone every node sticks; with
μ = 0.3 every node slides, each with a tangential traction of exactly μ times
its contact pressure (the slip direction is not only x: the compressed block
also spreads sideways)."""
import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import _cpp, scene
from hypercontact.contact.law import Coulomb
from hypercontact.contact.rigid import RigidFrictionHistory
from hypercontact.results import ResultsWriter
from hypercontact.simulation import Simulation

MU = 0.3


def dragged_block(out, shift, mu=MU, steps=(0.25, 0.25), friction_keys=True, xdmf=False, coulomb_law=False,
                  petsc=None):
    """Top face held and moved by (shift, 0, −0.1); bottom on a rigid base."""
    data = {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 2, "m": 2},
        "material": {"law": "mooney_rivlin", "parameters": {"alpha1": 0.1863, "alpha2": 0.0098, "K": 5.0}},
        "bc": [{"surface": "zmax", "fix": ["x", "y", "z"], "motion": [shift, 0.0, -0.1]}],
        "contact": [{"name": "base", "surface": "zmin", "obstacle": "plane", "eps_n": 100.0, "eps_t": 100.0,
                     "mu": mu}],
        "steps": {"initial": steps[0], "max": steps[1]},
        "solver": {"rtol": 1e-12, "atol": 1e-12, "max_it": 40, "petsc": petsc or {}},  # line search "auto": bt
        "output": {"dir": str(out), "xdmf": xdmf},
    }
    if not friction_keys:  # the scene as a frictionless user writes it
        del data["contact"][0]["eps_t"], data["contact"][0]["mu"]
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet)
    if coulomb_law:  # the Coulomb law with this μ, even μ = 0 (the factory builds it for μ > 0 only)
        c = sim.contacts[0]
        c.law = Coulomb(mu, c.eps_n, RigidFrictionHistory(c.geometry), c.comm)
    return sim, sim.run()


@pytest.mark.mpi
def test_wide_cone_sticks(out_dir):
    mu = 5.0
    sim, writer = dragged_block(out_dir, 0.002, mu=mu)
    last = writer.steps[-1]
    fx, fz = last["base_fx"], last["base_fz"]
    assert fz > 0 and 0 < -fx < 0.5 * mu * fz  # holds the block back, well inside the cone
    assert last["base_dissipation"] == pytest.approx(0.0, abs=1e-14)
    (base,) = sim.contacts
    state = base.law.committed
    assert np.all(np.asarray(state.state) == 1)  # every node sticks


@pytest.mark.mpi
def test_large_drag_slides_at_mu_times_normal_force(out_dir):
    sim, writer = dragged_block(out_dir, 0.3)
    last = writer.steps[-1]
    fx, fy, fz = last["base_fx"], last["base_fy"], last["base_fz"]
    (base,) = sim.contacts
    state = base.law.committed
    assert np.all(np.asarray(state.state) == 2)  # every node slides
    t = np.linalg.norm(np.asarray(state.traction), axis=1)
    p = np.asarray(base.evaluate(sim.u).pressure)
    assert np.allclose(t, MU * p, rtol=1e-9, atol=0)  # on the Coulomb cone, node by node
    assert 0.9 * MU * fz < -fx < MU * fz and np.hypot(fx, fy) <= MU * fz * (1 + 1e-9)
    # dissipation accumulates, never decreases, and is positive once sliding
    d = [s["base_dissipation"] for s in writer.steps]
    assert all(b >= a - 1e-14 for a, b in zip(d, d[1:])) and d[-1] > 0
    # Newton still converges fast with the non-symmetric slip tangent
    assert max(s["newton_iterations"] for s in writer.steps) <= 10


@pytest.mark.mpi
def test_zero_friction_builds_no_friction(out_dir):
    sim, writer = dragged_block(out_dir, 0.3, mu=0.0)
    assert not any(c.frictional for c in sim.contacts)
    assert "frictionless" in sim.effects[1]
    assert writer.steps[-1]["base_fx"] == pytest.approx(0.0, abs=1e-12)


def test_zero_friction_equals_frictionless_exactly_and_calls_no_friction_kernel(out_dir, monkeypatch):
    """μ = 0 (with a tangential penalty given) runs no friction kernel and
    writes exactly what the scene without friction keys writes; and the
    friction code itself, forced onto the μ = 0 contact, adds exactly
    nothing (same solution, bit for bit)."""
    calls = []

    def forbidden(name):
        def kernel(*args, **kwargs):
            calls.append(name)
            raise AssertionError(f"{name} called with μ = 0")
        return kernel

    monkeypatch.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})
    with monkeypatch.context() as m:
        m.setattr(_cpp, "evaluate_rigid_friction", forbidden("evaluate_rigid_friction"))
        sim0, w0 = dragged_block(out_dir / "mu0", 0.3, mu=0.0, xdmf=True)
        simf, wf = dragged_block(out_dir / "frictionless", 0.3, friction_keys=False, xdmf=True)
    assert not calls
    assert w0.columns == wf.columns and not any("dissipation" in c or "slip" in c for c in w0.columns)
    assert [{k: s[k] for k in w0.columns} for s in w0.steps] == [{k: s[k] for k in wf.columns} for s in wf.steps]
    assert np.array_equal(sim0.u.x.array, simf.u.x.array)
    assert w0.fields == wf.fields and not any("slip" in name for name in w0.fields)
    if MPI.COMM_WORLD.rank == 0:
        assert (out_dir / "mu0" / "curves.csv").read_bytes() == (out_dir / "frictionless" / "curves.csv").read_bytes()
    # The friction kernel at μ = 0 (forced: the simulation never builds it so) is frictionless exactly;
    # a frictional contact makes the solver take LU, so it is told to factorise as the frictionless
    # run does (LDLᵀ: its tangent is symmetric), else the two differ by the factorisation's rounding.
    simk, wk = dragged_block(out_dir / "kernel", 0.3, mu=0.0, coulomb_law=True, petsc={"pc_type": "cholesky"})
    assert simk.contacts[0].frictional
    assert np.array_equal(simk.u.x.array, simf.u.x.array)
    assert wk.steps[-1]["base_dissipation"] == 0.0 and wk.steps[-1]["base_fx"] == wf.steps[-1]["base_fx"]


def test_cut_back_leaves_the_history_as_if_never_failed(out_dir):
    """One huge first step that fails and is cut back gives the same final
    state as steps that never failed (the history is committed only after
    converged steps)."""
    sim_a, wa = dragged_block(out_dir / "a", 0.3, steps=(0.25, 0.25))
    sim_b, wb = dragged_block(out_dir / "b", 0.3, steps=(1.0, 0.25))
    # both end at λ = 1; paths differ, so compare the sliding force law, exact in both
    for sim in (sim_a, sim_b):
        (base,) = sim.contacts
        t = np.linalg.norm(np.asarray(base.law.committed.traction), axis=1)
        assert np.allclose(t, MU * np.asarray(base.evaluate(sim.u).pressure), rtol=1e-9, atol=0)
    assert len(wb.steps) >= 1
