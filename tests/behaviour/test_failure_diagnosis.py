"""A failed attempt says where its residual is left and what each of its
Newton solves did.

- ``largest_residuals`` against a closed form: at u = 0 a uniform pressure p
  on the top of a box leaves, at each node of the top face, its share of the
  load as the residual force: p·hx·hy at an inner node of a trilinear mesh,
  4/9·p·hx·hy at the centre node of a 9-node face (Simpson's weights) on the
  mixed Q2–Q1 formulation, whose unknown interleaves the pressure dofs (the
  rows must be the displacement's).
- A real failure (no forced reason): the punch's first step with two Newton
  iterations allowed fails with full steps and again with the backtracking
  fallback; the story lists both solves and locates the largest residual.
"""
import json

import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI
from petsc4py import PETSc

from hypercontact import scene
from hypercontact.simulation import Simulation, StepFailure
from hypercontact.solve.monitor import largest_residuals
from hypercontact.solve.newton_solver import NewtonSolver

BOX = """
title = "box under a uniform pressure, a lid far above"
[mesh]
builder = "box"
size = [2.0, 3.0, 1.0]
n = 4
m = 2
[material]
law = "mooney_rivlin"
parameters = {{ alpha1 = 0.1863, alpha2 = 0.0098, K = 5.0, i2 = "usual" }}
[discretisation]
{discretisation}
[[bc]]
surface = "zmin"
fix = ["x", "y", "z"]
[[pressure]]
surface = "zmax"
value = {p}
[[contact]]
name = "lid"
surface = "zmax"
obstacle = "plane"
point = [0.0, 0.0, 5.0]
normal = [0.0, 0.0, -1.0]
eps_n = 100.0
"""


@pytest.mark.mpi
@pytest.mark.parametrize("discretisation, share", [
    ("degree = 1", 1.0),
    ('degree = 2\nformulation = "mixed"\nquadrature_degree = 4', 4.0 / 9.0),
])
def test_largest_residuals_are_the_nodal_shares_of_a_pressure(out_dir, discretisation, share):
    p, hx, hy = 0.01, 2.0 / 4, 3.0 / 4
    folder = out_dir
    path = folder / "box.toml"
    if MPI.COMM_WORLD.rank == 0:
        path.write_text(BOX.format(discretisation=discretisation, p=p))
    MPI.COMM_WORLD.barrier()
    sim = Simulation(scene.load(path, [f"output.dir={folder}", "output.xdmf=false"]), MPI.COMM_WORLD, log=quiet)
    model = sim.model
    model.set_load_factor(1.0)
    b = model.problem.b
    model.problem.residual(None, model.w.vector, b)
    top = largest_residuals(model, b)
    assert len(top) == 5
    expected = share * p * hx * hy
    for entry in top:
        x, y, z = entry["point"]
        assert entry["force"] == pytest.approx(expected, rel=1e-10)
        assert abs(entry["residual"][2]) == pytest.approx(expected, rel=1e-10)
        assert max(abs(entry["residual"][0]), abs(entry["residual"][1])) < 1e-12 * expected
        assert z == pytest.approx(1.0) and 0 < x < 2 and 0 < y < 3
        assert entry["current"] == pytest.approx(entry["point"])  # u = 0
        if share == 1.0:  # nodal slave points on the trilinear mesh: each top node is the lid's, open
            assert entry["slave_of"] == [{"contact": "lid", "status": "open"}]
    # nothing larger elsewhere: the largest listed is the largest node force of the whole residual
    assert b.norm(PETSc.NormType.INFINITY) <= expected * (1 + 1e-10)  # the ∞-norm of a row never exceeds its node's force


@pytest.mark.mpi
@pytest.mark.parametrize("fallback_max_it", [0, 1])
def test_a_failed_attempt_lists_each_solve_and_where_its_residual_is(out_dir, fallback_max_it):
    """With fallback_max_it = 1 the backtracking fallback stops after one iteration (0: max_it), and
    the next attempt's full-step solve has max_it again. Both limits count from the step's start: a
    fallback that starts at an iterate of the full-step solve (from_iterate) takes that many fewer."""
    sc = scene.load(ROOT / "scenes" / "punch.toml", [
        "mesh.n=4", "mesh.m=1", "output.xdmf=false", f"output.dir={out_dir}", "solver.max_it=2",
        "steps.max_cutbacks=1", f"solver.fallback_max_it={fallback_max_it}"])
    messages = []
    sim = Simulation(sc, MPI.COMM_WORLD, log=messages.append)
    with pytest.raises(StepFailure):
        sim.run()
    line = [m for m in messages if "failed (" in m][-1]
    assert "largest residual force" in line
    if MPI.COMM_WORLD.rank != 0:
        return
    stories = json.loads((out_dir / "summary.json").read_text())["failed_attempts"]
    assert len(stories) == 2
    fallback = fallback_max_it or 2
    starts = [story["solves"][1]["from_iterate"] for story in stories]
    assert all(0 <= k < fallback for k in starts)  # the fallback takes at least one iteration of its own
    assert [[s["newton_iterations"] for s in story["solves"]] for story in stories] == [
        [2, fallback - k] for k in starts]
    story, k = stories[-1], starts[-1]
    solves = story["solves"]
    assert [s["line_search"] for s in solves] == ["basic", "bt"]  # full steps, then the fallback
    assert all(s["reason"] == s["snes_reason"] == "DIVERGED_MAX_IT" for s in solves)
    assert [len(s["residual_norms"]) for s in solves] == [3, fallback - k + 1]
    assert solves[1]["residual_norms"][0] == solves[0]["residual_norms"][k]  # it starts at that iterate
    assert story["attempt_newton_iterations"] == 2 + fallback - k and story["newton_iterations"] == fallback - k
    assert story["residual_norms"] == solves[-1]["residual_norms"]
    assert sum(s["linear_iterations"] for s in solves) == story["linear_iterations"]
    # the listed node forces are pieces of the last residual: the largest at most its norm, at least
    # its norm over the root of the node count (every row is a displacement row; at the iterate the
    # Dirichlet rows are zero)
    forces = [e["force"] for e in story["largest_residuals"]]
    norm, nodes = story["residual_norms"][-1], 5 * 5 * 2
    assert forces == sorted(forces, reverse=True) and len(forces) == 5
    assert np.sqrt(np.sum(np.square(forces))) <= norm * (1 + 1e-12)
    assert forces[0] >= norm / np.sqrt(nodes)
    assert f"{forces[0]:.3g}" in line
    # the frictionless punch's points are open or closed (they slide: no stick, no slip)
    statuses = {s["status"] for e in story["largest_residuals"] for s in e["slave_of"]}
    assert statuses and statuses <= {"open", "closed"}



@pytest.mark.mpi
def test_the_backtracking_fallback_resumes_where_it_would_take_the_full_steps_again(out_dir, monkeypatch):
    """The punch with every full-step solve stopped after 2 iterations, so every step goes on with
    the backtracking fallback. Started from the step's start, the fallback takes the full-step
    solve's first step again, whole (it lowers |R| by far more than the 5 % that makes that sure),
    to the same iterate (and the second too where it lowered |R| by 5 %); started at that iterate
    (NewtonSolver.resume_fallback, the default) it computes the same iterates after it, in as many
    Newton iterations fewer per step, the step control takes the same steps (it counts the
    iterations from the step's start), and the run ends on the same state."""
    runs = {}
    for resume in (False, True):
        monkeypatch.setattr(NewtonSolver, "resume_fallback", resume)
        folder = out_dir / f"resume{resume}"
        folder.mkdir(exist_ok=True)
        sc = scene.load(ROOT / "scenes" / "punch.toml", [
            "mesh.n=4", "mesh.m=1", "output.xdmf=false", f"output.dir={folder}", "solver.max_it=2",
            "solver.fallback_max_it=12", "steps.max=0.25"])
        sim = Simulation(sc, MPI.COMM_WORLD, log=quiet)
        sim.run()
        runs[resume] = (folder / "summary.json", sim.contacts[0].force(sim.u)[2], sim.u.x.array.copy())
    (again, force_again, u_again), (resumed, force, u) = runs[False], runs[True]
    assert np.allclose(u, u_again, rtol=0, atol=1e-12 * np.abs(u_again).max())
    assert force == pytest.approx(force_again, rel=1e-12)
    if MPI.COMM_WORLD.rank != 0:  # rank 0 writes summary.json
        return
    again, resumed = (json.loads(f.read_text()) for f in (again, resumed))
    assert resumed["status"] == again["status"] == "completed"
    steps = len(again["steps"])
    assert len(resumed["steps"]) == steps and steps >= 4 and not again["failed_attempts"]
    # the step control sees the iterations from the step's start: the same steps
    assert [s["load_factor"] for s in resumed["steps"]] == [s["load_factor"] for s in again["steps"]]
    for s_again, s in zip(again["steps"], resumed["steps"]):
        # each step: two full steps, then the fallback, shorter by the full steps it did not take again
        done = s_again["newton_iterations"] - s["newton_iterations"]
        assert done in (1, 2)
        # the same iterates: their |R| equal to the round-off of the step's residual, 1e-12 |R_0| (on two
        # ranks MUMPS's factorisations differ in the last bits from one run to the next)
        round_off = 1e-12 * s_again["residual_norms"][0]
        assert s["residual_norms"] == pytest.approx(s_again["residual_norms"][done:], rel=0, abs=round_off)
