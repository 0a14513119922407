"""The smooth master surface (master_surface = "smooth", docs/method.md §3.6) in
scenes: on a flat master it is the faceted element (the contact patch test
passes the same), its settings are checked with the key named, and on a
curved master — a block pressed onto a stiff meshed cylinder — its assembled
tangent is the derivative of its residual, with and without friction."""
import tomllib

import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation
from reference.finite_differences import assembled_and_fd_jacobians, constrained_dofs
from reference.runs import column, run



def blocks(master_surface, stiff_master=False, **change):
    """The contact patch test (scenes/blocks.toml) with this master surface (the lower block's
    top), the lower block 10⁶ times stiffer if ``stiff_master``."""
    data = tomllib.loads(scene.scene_path("blocks").read_text())
    if stiff_master:
        data["material"]["parameters"] = {"mu": 1e6, "K": 2e6}
    data["contact"][0].update(master_surface=master_surface, **change)
    data.setdefault("output", {}).update(xdmf=False)
    return data


def test_on_a_flat_master_it_is_the_faceted_element(tmp_path):
    """The patch test with the lower block 10⁶ times stiffer: its top, the master, stays flat to
    about 1e-12 (with equal blocks the non-uniform penalty pressure of the non-matching meshes
    waves it by ~1e-6 of the force, and the two elements then differ by that much, as they
    should): every nodal normal is the facet normal, so the smooth element's gap, normal and
    force are the faceted element's, and the whole run agrees to 1e-9; the smooth points report
    feature 3."""
    _, faceted = run(blocks("faceted", stiff_master=True), tmp_path / "faceted")
    sim, smooth = run(blocks("smooth", stiff_master=True), tmp_path / "smooth")
    assert len(smooth.steps) == len(faceted.steps)
    for key in ("interface_fz", "interface_closed_nodes", "newton_iterations"):
        assert column(smooth, key) == pytest.approx(column(faceted, key), rel=1e-9, abs=1e-12), key
    state = sim.contacts[0].evaluate(sim.u)
    closed = state.pressure > 0
    assert closed.sum() > 0 and np.all(state.feature[closed] == 3)


def test_settings_are_checked_naming_the_key(tmp_path):
    with pytest.raises(scene.SceneError, match=r"contact\[0\]\.master_surface"):
        scene.load(blocks("nagata"))


def block_on_cylinder(mu):
    """A soft block (1 × 0.5 × 0.3, its nodes off the master's node lines: a point exactly on a
    facet edge has no derivative to compare with) pressed 0.06 onto a stiff tube sector (length 0.5 along its
    axis z, the block inside that length: no slave point near the master's rim) of outer radius 1
    with 8 facets over 120° (a deformable faceted master: its facets turn by 15°) and moved 0.03
    across the axis."""
    return {"title": "block on a cylinder",
            "mesh": {"builder": "tube", "inner_radius": 0.8, "thickness": 0.2, "length": 0.5, "layers": 2,
                     "angles": [30.0, 150.0], "n": 8, "m": 1},
            "material": {"law": "neo_hookean", "parameters": {"mu": 1000.0, "K": 5000.0}},
            "body": [{"name": "block", "builder": "box", "size": [1.0, 0.5, 0.3], "origin": [-0.47, 1.0, 0.12],
                      "n": 6, "m": 2, "material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 5.0}}}],
            "bc": [{"surface": "block.ymax", "fix": ["x", "y", "z"], "motion": [0.03, -0.06, 0.0]},
                   {"surface": "inner", "fix": ["x", "y", "z"]}],
            "contact": [{"name": "c", "surface": "block.ymin", "obstacle": "surface", "master": "outer",
                         "master_surface": "smooth", "mu": mu, "eps_n": 200.0, "eps_t": 200.0}],
            "steps": {"initial": 0.25, "max": 0.25}, "output": {"xdmf": False}}


@pytest.mark.parametrize("mu", [0.0, 0.3])
def test_tangent_on_a_curved_master(tmp_path, mu):
    """Block on the faceted cylinder (smooth master), at the converged end of the path with
    points on several facets, before the step is committed (after the commit a slipping point's
    history puts it exactly on the Coulomb cone, where the tangent has no meaning): the
    assembled tangent against central differences of the residual over every free dof (the
    smooth element's neighbour stencil and, with friction, the old facets' columns included)."""
    sim = Simulation(scene.load(block_on_cylinder(mu), [f"output.dir={tmp_path}"]), MPI.COMM_SELF, log=quiet)
    c = sim.contacts[0]
    commit, seen = c.commit, {}

    def check_then_commit():
        if c.geometry.load_factor == pytest.approx(1.0):
            state = c.evaluate(sim.u)
            closed = state.pressure > 0
            seen["facets"] = len(np.unique(state.facet[closed]))
            seen["closed"], seen["smooth"] = int(closed.sum()), bool(np.all(state.feature[closed] == 3))
            seen["slip"] = int((np.asarray(getattr(state, "state", np.zeros(0)))[closed] == 2).sum()) if mu else 0
            problem, x = sim.problem, sim.problem.x
            sim.w.vector.copy(x)
            free = np.flatnonzero(~constrained_dofs(sim))
            # h below the penalty's smoothing band (1e-6 of the element layer)
            J, J_fd = assembled_and_fd_jacobians(problem, x, free, h=1e-8)
            A, B = J[np.ix_(free, free)], J_fd[np.ix_(free, free)]
            seen["error"], seen["scale"] = np.abs(A - B).max(), np.abs(B).max()
        commit()

    c.commit = check_then_commit
    sim.run()
    assert seen["closed"] >= 6 and seen["facets"] >= 2 and seen["smooth"]
    if mu > 0:
        assert seen["slip"] > 0
    assert seen["error"] <= 1e-6 * seen["scale"]
