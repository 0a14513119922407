"""The paper's four friction cases of the punch as built-in scenes: they are
the frictionless punch with only the friction keys changed, and on a coarse
mesh they keep vertical equilibrium with friction and move the plate the way
the paper says (friction under the punch lifts the plate's edge and corner
more, friction on the base less). bench/punch_friction.py runs them on the
real meshes."""
import tomllib

import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import cli, scene
from hypercontact.results import ResultsWriter
from hypercontact.simulation import Simulation

CASES = {"punch_mu0_0": (0.0, 0.0), "punch_mu0.3_0": (0.3, 0.0), "punch_mu1_0": (1.0, 0.0), "punch_mu0_1": (0.0, 1.0)}


def test_the_four_cases_are_the_punch_with_friction_only():
    punch = tomllib.loads((ROOT / "scenes" / "punch.toml").read_text())
    listed = []

    class Out:
        def write(self, text):
            listed.append(text)

    cli.list_scenes(Out())
    for name, (mu1, mu2) in CASES.items():
        assert any(line.startswith(name + " ") for line in "".join(listed).splitlines())
        case = tomllib.loads((ROOT / "scenes" / f"{name}.toml").read_text())
        assert [c["mu"] for c in case["contact"]] == [mu1, mu2]
        assert f"({mu1:g}, {mu2:g})" in case["title"]
        for c in case["contact"]:
            del c["mu"], c["eps_t"]
        del case["title"], case["output"]["dir"]
        reference = {k: v for k, v in punch.items() if k != "title"}
        reference["output"] = {k: v for k, v in punch["output"].items() if k != "dir"}
        assert case == reference, name
        scene.load(ROOT / "scenes" / f"{name}.toml")  # valid


@pytest.fixture(scope="module")
def coarse(tmp_path_factory):
    comm = MPI.COMM_WORLD
    out = comm.bcast(str(tmp_path_factory.mktemp("punch_friction")) if comm.rank == 0 else None, root=0)
    rows = {}
    with pytest.MonkeyPatch.context() as m:
        m.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})
        for name in CASES:
            sc = scene.load(ROOT / "scenes" / f"{name}.toml",
                            ["mesh.n=4", "mesh.m=1", "output.xdmf=false", f"output.dir={out}/{name}"])
            rows[name] = Simulation(sc, comm, log=quiet).run().steps
    return rows


def test_equilibrium_with_friction(coarse):
    """The symmetry planes take no vertical force, so the punch force equals
    the base reaction, friction on the punch's side walls included."""
    for name, steps in coarse.items():
        assert steps[-1]["load_factor"] == pytest.approx(1.0)
        for s in steps:
            assert s["punch_fz"] + s["base_fz"] == pytest.approx(0.0, abs=1e-8 * abs(s["punch_fz"])), name
            if any(CASES[name]):
                assert s["dissipation_step"] >= 0.0
        if any(CASES[name]):
            assert steps[-1]["dissipation"] > 0.0


def test_friction_under_the_punch_lifts_more_on_the_base_less(coarse):
    ref = coarse["punch_mu0_0"][-1]
    assert ref["edge_uz"] > 0 and ref["corner_uz"] > 0
    for name in ("punch_mu0.3_0", "punch_mu1_0"):
        last = coarse[name][-1]
        assert last["edge_uz"] > ref["edge_uz"] and last["corner_uz"] > ref["corner_uz"], name
        assert -last["punch_fz"] > -ref["punch_fz"]  # and it takes more force to indent
    last = coarse["punch_mu0_1"][-1]
    assert last["edge_uz"] < ref["edge_uz"] and last["corner_uz"] < ref["corner_uz"]


def test_assembled_tangent_is_the_derivative_of_the_residual(tmp_path):
    """Newton's matrix with friction under the box punch (face, edges and
    side walls), volume, normal contact with the base and Dirichlet
    conditions included, against central differences of the assembled
    residual, at a state with open, sticking and slipping nodes (≤ 1e-6
    relative)."""
    import numpy as np

    from hypercontact import _dolfinx as dfx
    from hypercontact.contact import OPEN, SLIP, STICK

    sc = scene.load(ROOT / "scenes" / "punch_mu0.3_0.toml",
                    ["mesh.n=4", "mesh.m=1", "output.xdmf=false", f"output.dir={tmp_path}"])
    class Stop(Exception):
        pass

    def stop_after_three_steps(message):
        if message.startswith("step   3"):
            raise Stop

    with pytest.MonkeyPatch.context() as m:
        m.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})
        sim = Simulation(sc, MPI.COMM_SELF, log=stop_after_three_steps)
        with pytest.raises(Stop):
            sim.run()
    # a step of indentation (Δλ = 0.25) against the history of the last converged step: some nodes slip
    sim.set_load_factor(sim.contacts[0].law.history.lam_committed + 0.25)
    assert sim.newton.solve()[0]
    P, x = sim.problem, sim.problem.x.copy()
    sim.w.vector.copy(x)
    fixed = np.concatenate([dfx.bc_dofs(bc) for bc in sim.bcs])
    rng = np.random.default_rng(7)

    def residual(xv):
        b = P.b.duplicate()
        P.residual(None, xv, b)
        return b.array.copy()

    for trial in range(3):
        x0 = x.copy()
        x0.array[:] += 1e-5 * rng.standard_normal(x.array.size)
        x0.array[fixed] = x.array[fixed]
        d = x.duplicate()
        d.array[:] = rng.standard_normal(x.array.size)
        d.array[fixed] = 0.0
        residual(x0)
        states = np.asarray(sim.contacts[0].state.state)
        assert {OPEN, STICK, SLIP} <= set(states.tolist()), np.bincount(states)
        P.jacobian(None, x0, P.A, P.A)
        Ad = d.duplicate()
        P.A.mult(d, Ad)
        errors = []
        for h in (1e-6, 1e-7):  # the smaller step, should the larger cross a stick–slip switch
            xp, xm = x0.copy(), x0.copy()
            xp.axpy(h, d)
            xm.axpy(-h, d)
            fd = (residual(xp) - residual(xm)) / (2 * h)
            errors.append(np.linalg.norm(fd - Ad.array) / np.linalg.norm(fd))
        assert min(errors) <= 1e-6, errors


def test_friction_on_punch_and_base_at_once(coarse, tmp_path):
    """(μ1, μ2) = (0.3, 1), scenes/punch_mu0.3_1.toml, on 4 × 4 × 1 (issue
    #4: full Newton steps cycle from the first step; the scene's l2 line
    search converges): full indentation, equilibrium, every slipping node of
    both contacts on its Coulomb cone |t| = μ p_N and every sticking node
    inside it; friction on both faces holds the plate at least as much as
    either alone: more force than either single-friction case, and the edge
    and corner stay on the base as with base friction alone."""
    import numpy as np

    from hypercontact.contact import SLIP, STICK

    sc = scene.load(ROOT / "scenes" / "punch_mu0.3_1.toml",
                    ["mesh.n=4", "mesh.m=1", "output.xdmf=false", f"output.dir={tmp_path}"])
    with pytest.MonkeyPatch.context() as m:
        m.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})
        sim = Simulation(sc, MPI.COMM_SELF, log=quiet)
        last = sim.run().steps[-1]
    assert last["load_factor"] == pytest.approx(1.0)
    assert last["punch_fz"] + last["base_fz"] == pytest.approx(0.0, abs=1e-8 * abs(last["punch_fz"]))
    slipping = 0
    for c, mu in zip(sim.contacts, (0.3, 1.0)):
        state = c.law.committed
        status = np.asarray(state.state)
        p = np.asarray(c.evaluate(sim.u).pressure)
        t = np.linalg.norm(np.asarray(state.traction), axis=1)
        slip, stick = status == SLIP, status == STICK
        assert np.allclose(t[slip], mu * p[slip], rtol=1e-9, atol=1e-12), c.name
        assert np.all(t[stick] <= mu * p[stick] * (1 + 1e-9) + 1e-12), c.name
        slipping += np.count_nonzero(slip)
    assert slipping > 0
    force = -last["punch_fz"]
    assert force > -coarse["punch_mu0.3_0"][-1]["punch_fz"]
    assert force > -coarse["punch_mu0_1"][-1]["punch_fz"]
    base_only = coarse["punch_mu0_1"][-1]
    for probe in ("edge_uz", "corner_uz"):  # on the base: at most the penalty's penetration scale
        assert abs(last[probe]) < 1e-3 and abs(base_only[probe]) < 1e-3, probe
