"""Chattering: contact status that keeps changing inside a load step.

Stick/slip flips. A stiff block pressed onto a frictional obstacle (a rigid
plane, or the top of another stiff block) by an initial overlap δ and
dragged sideways by its top: the normal force is N = ε_N A δ and the drag
force ε_T A s λ while the block sticks, so every point starts to slip at
λ* = μ δ / s, all in the same load step. The flip count of each step must
be the number of points that changed between stick and slip from the
previous converged step's states to this one's (recomputed here from the
committed states), hence all slave points in the step that contains λ* and
none in the others; the Newton iterations with a stick/slip change are
counted, written to curves.csv and summary.json, and warned about past
steps.chatter_warning.
"""
import csv
import json

import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import _dolfinx as dfx
from hypercontact import scene
from hypercontact.contact import SLIP, STICK
from hypercontact.results import ResultsWriter
from hypercontact.simulation import Simulation, StepFailure

from conftest import ROOT

G, EPS, MU, DELTA, DRAG = 1.0e6, 10.0, 0.3, 0.01, 0.0065
LAMBDA_SLIP = MU * DELTA / DRAG  # ≈ 0.46: inside the 5th step of Δλ = 0.1


@pytest.fixture(scope="module", autouse=True)
def no_pictures():
    with pytest.MonkeyPatch.context() as m:
        m.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})
        yield


def rigid_drag(out):
    """A 2 × 2 × 1 block on a rigid plane at z = δ, top moved by (λ s, 0, 0)."""
    return {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 2, "m": 1},
        "material": {"law": "neo_hookean", "parameters": {"mu": G, "K": G}},
        "bc": [{"surface": "zmax", "fix": ["x", "y", "z"], "motion": [DRAG, 0.0, 0.0]},
               {"surface": "ymin", "fix": ["y"]}, {"surface": "ymax", "fix": ["y"]}],
        "contact": [{"name": "base", "surface": "zmin", "obstacle": "plane", "point": [0.0, 0.0, DELTA],
                     "normal": [0.0, 0.0, 1.0], "eps_n": EPS, "eps_t": EPS, "mu": MU}],
        # from the last converged state (no secant predictor): the onset step's Newton iterations
        # are then what leave the stick set; predicted, it starts sliding already
        "steps": {"initial": 0.1, "max": 0.1, "chatter_warning": 1, "predictor": "none"},
        "solver": {"rtol": 1e-12, "atol": 1e-13, "max_it": 30, "linesearch": "basic"},
        "output": {"dir": str(out), "xdmf": False, "symmetry_factor": 1.0},
    }


def surface_drag(out):
    """The blocks scene: a 0.5 × 0.5 × 0.25 block (2 × 2) overlapping the
    1 × 1 × 0.5 lower block (4 × 4) by δ, both stiff, its top moved by
    (λ s, 0, 0); the lower block's bottom held."""
    data = scene.load(ROOT / "scenes" / "blocks.toml", [f"output.dir={out}", "output.xdmf=false"])
    material = {"law": "neo_hookean", "parameters": {"mu": G, "K": G}}
    data["material"] = material
    data["body"][0].update(size=[0.5, 0.5, 0.25], origin=[0.25, 0.25, 0.5 - DELTA], n=2, m=1, material=material)
    data["mesh"].update(n=4, m=1)
    data["bc"] = [{"surface": "zmin", "fix": ["x", "y", "z"], "motion": [0.0, 0.0, 0.0]},
                  {"surface": "top.zmax", "fix": ["x", "y", "z"], "motion": [DRAG, 0.0, 0.0]}]
    data["pressure"] = []
    data["contact"][0].update(eps_n=EPS, eps_t=EPS, mu=MU)
    data["steps"].update(initial=0.1, max=0.1, chatter_warning=1, predictor="none")  # as rigid_drag
    data["solver"].update(rtol=1e-12, atol=1e-13, max_it=30, linesearch="basic")
    data["output"].update(probes={}, symmetry_factor=1.0)
    return data


def gather(a):
    return np.concatenate(MPI.COMM_WORLD.allgather(np.asarray(a)))


@pytest.mark.mpi
@pytest.mark.parametrize("build", [rigid_drag, surface_drag], ids=["rigid", "surface"])
def test_stick_slip_flips_counted_on_the_step_where_the_block_starts_to_slide(build, tmp_path_factory):
    comm = MPI.COMM_WORLD
    out = comm.bcast(str(tmp_path_factory.mktemp("drag")) if comm.rank == 0 else None, root=0)
    messages = []
    sim = Simulation(scene.load(build(out)), comm, log=messages.append)
    (c,) = sim.contacts
    statuses, commit = [], c.commit

    def recording_commit():
        commit()
        statuses.append(gather(np.asarray(c.state.state)))

    c.commit = recording_commit
    writer = sim.run()
    steps = writer.steps
    assert len(steps) == 10 and steps[-1]["load_factor"] == pytest.approx(1.0)
    n_points = len(statuses[0])
    previous = np.zeros(n_points)
    for k, (s, status) in enumerate(zip(steps, statuses)):
        flipped = ((previous == STICK) & (status == SLIP)) | ((previous == SLIP) & (status == STICK))
        assert s["base_stick_slip_flips" if c.name == "base" else f"{c.name}_stick_slip_flips"] == flipped.sum()
        assert s["stick_slip_flips"] == flipped.sum()
        assert 0 <= s["stick_slip_changes"] <= s["newton_iterations"]
        lo, hi = s["load_factor"] - 0.1, s["load_factor"]
        if lo < LAMBDA_SLIP < hi:  # the closed form's onset: every point slips from now on
            assert np.all(status == SLIP) and np.all(previous == STICK)
            assert s["stick_slip_flips"] == n_points
            assert s["stick_slip_changes"] >= 1  # the step's iterations left the stick set
        else:
            assert s["stick_slip_flips"] == 0
            assert np.all(status == (STICK if hi < LAMBDA_SLIP else SLIP))
        previous = status
    # curves.csv and summary.json carry the same numbers; the warning fires on each step with a change
    if comm.rank == 0:
        with open(writer.out / "curves.csv", newline="") as f:
            rows = list(csv.DictReader(f))
        summary = json.loads((writer.out / "summary.json").read_text())["steps"]
        for s, r, j in zip(steps, rows, summary):
            for key in ("stick_slip_changes", "stick_slip_flips", f"{c.name}_stick_slip_flips"):
                assert int(r[key]) == s[key] == j[key]
        warned = sum("stick/slip status changed" in m for m in messages)
        assert warned == sum(s["stick_slip_changes"] >= 1 for s in steps) >= 1


def chatter_run(out, overrides=()):
    messages = []
    sc = scene.load(ROOT / "scenes" / "chatter.toml",
                    [f"output.dir={out}", "output.xdmf=false", "steps.max_cutbacks=0", *overrides])
    sim = Simulation(sc, MPI.COMM_SELF, log=messages.append)
    try:
        sim.run()
        return sim, messages, True
    except StepFailure:
        return sim, messages, False


def reactions(sim):
    """z-sums of the internal-force residual ∫ P : ∇v over the nodes of the
    ball's flat top (z = 10) and of the block's bottom (z = −10): the
    reactions of the supports, from the volume forms alone."""
    b = dfx.assemble_vector_owned(sim.problem.R)
    with b.localForm() as bl:
        r = bl.array_r.copy()
    b.destroy()
    X = dfx.node_coordinates(sim.V)[: dfx.num_owned_nodes(sim.V)]
    rz = np.array([r[sim.unknown_dof(i, 2)] for i in range(len(X))])
    return rz[np.isclose(X[:, 2], 10.0)].sum(), rz[np.isclose(X[:, 2], -10.0)].sum()


def test_full_newton_converges_on_the_smoothed_law(tmp_path):
    """The same push with full Newton steps and the default smoothed contact
    law (the sharp law chatters, below): the step converges, to the force the
    line search finds with the sharp law (the band is 1e-6 of an element)."""
    smooth, _, ok = chatter_run(tmp_path / "smooth", ['solver.linesearch="basic"'])
    assert ok
    sharp, _, ok_sharp = chatter_run(tmp_path / "sharp", ["contact.0.smoothing=0"])
    assert ok_sharp
    f_smooth, f_sharp = smooth.contacts[0].force(smooth.u)[2], sharp.contacts[0].force(sharp.u)[2]
    assert f_smooth == pytest.approx(f_sharp, rel=1e-4)


def test_full_newton_chatters_and_the_line_search_converges_to_equilibrium(tmp_path):
    """scenes/chatter.toml: a hemisphere whose pole just touches a block,
    pushed 0.03 mm in one step with a penalty of 1e6. Full Newton steps
    cycle the active set (a change in most iterations, reported as
    chattering, the step fails); the backtracking line search converges,
    with few active-set changes, to a state in equilibrium: the contact
    force on the ball equals the reactions of its flat top and of the
    block's bottom computed from the volume forms alone, and equals the
    force of the same push reached in ten small steps."""
    # without the cycle stop full steps run to max_it; with it (the default) they stop as stalled once
    # |R| revisits its values (a period-3 cycle here) without a new smallest |R| in 4 iterations
    for stall_its in (0, 4):
        plain, messages, ok = chatter_run(tmp_path / f"plain{stall_its}", [
            'solver.linesearch="basic"', "contact.0.smoothing=0", f"solver.stall_its={stall_its}"])
        assert not ok
        its = len(plain.newton.history.active_sets) - 1
        solve = plain.newton.solves[-1]
        if stall_its == 0:
            assert its == plain.scene["solver"]["max_it"] and solve["reason"] == "DIVERGED_MAX_IT"
        else:
            norms = solve["residual_norms"]
            assert solve["reason"] == "STALLED" and its < plain.scene["solver"]["max_it"]
            assert min(abs(norms[-1] / norms[-1 - p] - 1) for p in (2, 3)) <= 0.05  # a revisit
            assert min(norms[-4:]) > 0.95 * min(norms[:-4])  # no new smallest |R| in the last four
        assert plain.newton.history.active_set_changes() >= 0.8 * its  # the active set changed in almost every iteration
        assert any("contact active set changed" in m and "chattering" in m for m in messages)

    damped, messages, ok = chatter_run(tmp_path / "damped")
    assert ok and damped.scene["solver"]["linesearch"] == "auto"  # bt with a deformable master
    assert damped.newton.history.active_set_changes() < damped.scene["steps"]["chatter_warning"]
    assert not any("chattering" in m for m in messages)
    c = damped.contacts[0]
    force = c.force(damped.u)
    assert force[2] > 0 and c.num_closed(damped.u) >= 1  # the block pushes the ball up
    top, bottom = reactions(damped)
    assert top == pytest.approx(-force[2], rel=1e-6)
    assert bottom == pytest.approx(force[2], rel=1e-6)

    stepped, _, ok = chatter_run(tmp_path / "stepped", ["steps.initial=0.1", "steps.max=0.1"])
    assert ok
    assert stepped.contacts[0].force(stepped.u)[2] == pytest.approx(force[2], rel=1e-6)
