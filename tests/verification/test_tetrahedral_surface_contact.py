"""Contact against a deformable master of linear tetrahedra (3-node master
facets): two blocks meshed apart in one .msh, stacked between frictionless
rigid planes. With matching meshes node-to-surface contact passes the patch
test, so the homogeneous state of the closed form (tests/reference/stack.py)
holds: forces, the lateral stretch at every node, the interface pressure —
nodal and Gauss-point integration, single- and two-pass, and under 2 ranks."""
import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation
from reference.homogeneous import mooney_rivlin_principal
from reference.stack import stacked_block, write_stack_msh

PARAMS = dict(alpha1=0.1863, alpha2=0.0098, K=5.0)
EPS, D = 50.0, 0.1


def stack_scene(out, msh, integration="nodal", passes=1):
    plane = {"obstacle": "plane", "eps_n": EPS}
    return {
        "mesh": {"builder": "file", "file": str(msh)},
        "material": {"law": "mooney_rivlin", "parameters": PARAMS},
        "bc": [{"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]}],
        "contact": [
            {"name": "top", "surface": "top", **plane, "point": [0, 0, 1.0], "normal": [0, 0, -1.0],
             "motion": [0, 0, -D]},
            {"name": "base", "surface": "base", **plane, "point": [0, 0, 0], "normal": [0, 0, 1.0]},
            {"name": "interface", "surface": "upper_bottom", "obstacle": "surface", "master": "lower_top",
             "eps_n": EPS, "integration": integration, "passes": passes},
        ],
        "steps": {"initial": 0.25, "max": 0.5},
        "solver": {"rtol": 1e-12, "atol": 1e-12},
        "output": {"dir": str(out), "xdmf": False},
    }


def assert_stack_closed_form(sim, passes):
    """The converged stack equals the closed form: plate and interface forces to 1e-6,
    every node at the lateral stretch to 1e-7 (two-pass on matching meshes: each surface
    is slave once and both passes press, ε_i = 2 ε_N). Returns P3."""
    top, base, *interface = sim.contacts
    lat, l3, P3 = stacked_block(lambda a, b, c: mooney_rivlin_principal(a, b, c, **PARAMS), 1.0, D, EPS,
                                passes * EPS)
    assert top.force(sim.u)[2] == pytest.approx(P3, rel=1e-6)
    assert base.force(sim.u)[2] == pytest.approx(-P3, rel=1e-6)
    for c in interface:  # the upper block's bottom is pressed up by −P3 / passes from each pass
        f = c.force(sim.u)[2]
        assert (f if c is interface[0] else -f) == pytest.approx(-P3 / passes, rel=1e-6)
    X = sim.V.tabulate_dof_coordinates()[: sim.V.dofmap.index_map.size_local]
    u = sim.u.x.array.reshape(-1, 3)[: len(X)]
    np.testing.assert_allclose(X[:, 0] + u[:, 0], lat * X[:, 0], atol=1e-7)
    np.testing.assert_allclose(X[:, 1] + u[:, 1], lat * X[:, 1], atol=1e-7)
    return P3


@pytest.mark.mpi
@pytest.mark.parametrize("integration, passes", [("nodal", 1), ("gauss", 1), ("nodal", 2)])
def test_stacked_tetrahedral_blocks_are_in_the_homogeneous_state(integration, passes, out_dir):
    msh = out_dir / "stack.msh"
    write_stack_msh(msh)
    sim = Simulation(scene.load(stack_scene(out_dir, msh, integration, passes)), MPI.COMM_WORLD, log=quiet)
    assert sim.V.mesh.topology.cell_type.name == "tetrahedron"
    sim.run()
    P3 = assert_stack_closed_form(sim, passes)
    interface = sim.contacts[2:]
    p = np.concatenate(MPI.COMM_WORLD.allgather(interface[0].state.pressure))
    closed = p[p > 0]
    assert len(closed) == (9 if integration == "nodal" else 3 * 8)  # 3 × 3 nodes, or 8 triangles × 3
    np.testing.assert_allclose(closed, -P3 / passes, rtol=1e-6)


def sliding_jacobian_error(sim):
    """After ``sim`` ran (friction history set): a perturbed state whose upper block moves
    on sideways, points in stick and in slip (asserted); (error, largest entry) of the
    assembled matrix against central differences of the assembled residual."""
    from hypercontact import _dolfinx as dfx
    from reference.finite_differences import constrained_dofs, simulation_jacobian_error

    constrained = constrained_dofs(sim)
    rng = np.random.default_rng(7)
    u = sim.w.x.array
    u[~constrained] += 1e-4 * rng.standard_normal(np.count_nonzero(~constrained))
    interface = sim.contacts[2]
    X = dfx.node_coordinates(sim.V)
    slaves = interface.geometry.nodes  # the upper block's bottom nodes (nodal integration)
    moving = np.zeros(u.size, bool)
    moving.reshape(-1, 3)[slaves[X[slaves, 1] > 0.4], 0] = True
    u[moving & ~constrained] += 2e-3
    sim.update_pairing(fresh=True)
    state = np.asarray(interface.evaluate(sim.u).state)
    assert np.count_nonzero(state == 1) >= 2 and np.count_nonzero(state == 2) >= 2
    err, scale, J, free = simulation_jacobian_error(sim, constrained)
    return err, scale


def test_assembled_jacobian_with_friction_on_triangle_masters(tmp_path):
    """Volume + normal + friction against 3-node master facets: after converged steps (history
    set), a perturbed state whose upper block moves on sideways — points in stick and in slip —
    every free entry of the assembled matrix equals the central difference of the assembled
    residual to 1e-6 of the largest entry."""
    msh = tmp_path / "stack.msh"
    write_stack_msh(msh)
    s = stack_scene(tmp_path, msh)
    s["contact"][2].update(mu=0.3, eps_t=EPS)  # stiff enough for the sideways motion to make points slip
    sim = Simulation(scene.load(s), MPI.COMM_SELF, log=quiet)
    sim.run()
    err, scale = sliding_jacobian_error(sim)
    assert err < 1e-6 * scale
