"""Contact against a deformable master of quadratic elements (9-node
quadrilateral and 6-node triangle master facets): two blocks of second-order
hexahedra or tetrahedra meshed apart in one .msh, stacked between
frictionless rigid planes. With matching meshes node-to-surface contact passes
the patch test, so the homogeneous state of the closed form
(tests/reference/stack.py, independent of the code) holds: forces, the
lateral stretch at every node, the interface pressure at every slave point —
for the displacement and the mixed (Taylor–Hood) formulation, single- and
two-pass, and under 2 ranks, with the faceted and the smooth master. Then the
assembled tangent with friction against both kinds of curved master facet,
faceted and smooth, against central differences; and the non-matching patch
test, where the faceted quadratic master 2-cycles at high penalty and the
smooth one converges, its σ_zz spread falling with the penalty."""
import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation
from reference.stack import write_stack_msh
from test_tetrahedral_surface_contact import EPS, assert_stack_closed_form, sliding_jacobian_error, stack_scene

ROOT_SCENES = ROOT / "scenes"

#: (cells, formulation, integration, passes) whose slave integration of a uniform pressure is
#: exact: 9-node quadrilateral nodal weights ∫N_i dA are positive and consistent, Gauss points
#: always are (the corner weights of a 6-node triangle vanish, so its nodes are no rule).
EXACT = [
    ("hexahedra", "displacement", "nodal", 1),
    ("hexahedra", "displacement", "gauss", 1),
    ("hexahedra", "displacement", "nodal", 2),
    ("hexahedra", "mixed", "nodal", 1),
    ("tetrahedra", "displacement", "gauss", 1),
    ("tetrahedra", "displacement", "gauss", 2),
    ("tetrahedra", "mixed", "gauss", 1),
]


def quadratic_stack_scene(out, msh, formulation="displacement", integration="nodal", passes=1,
                          master_surface="faceted"):
    s = stack_scene(out, msh, integration, passes)
    s["discretisation"] = {"degree": 2, "formulation": formulation}  # quadrature degree 4 by default
    s["contact"][2]["master_surface"] = master_surface
    return s


@pytest.mark.mpi
@pytest.mark.parametrize("cells, formulation, integration, passes, master_surface",
                         [(*case, "faceted") for case in EXACT] +
                         [("hexahedra", "displacement", "nodal", 1, "smooth"),
                          ("tetrahedra", "displacement", "gauss", 2, "smooth")])
def test_stacked_quadratic_blocks_are_in_the_homogeneous_state(cells, formulation, integration, passes,
                                                                master_surface, out_dir):
    """(The smooth master's nodal normals on the flat interface are its facets' normals, so
    it must hold the same closed form.)"""
    msh = out_dir / "stack.msh"
    write_stack_msh(msh, cells=cells, order=2)
    sim = Simulation(scene.load(quadratic_stack_scene(out_dir, msh, formulation, integration, passes,
                                                      master_surface)),
                     MPI.COMM_WORLD, log=quiet)
    assert sim.V.ufl_element().degree() == 2
    sim.run()
    P3 = assert_stack_closed_form(sim, passes)
    interface = sim.contacts[2:]
    assert interface[0].geometry.facets.shape[1] == (9 if cells == "hexahedra" else 6)
    for c in interface:  # every slave point of every pass closed, at the one uniform pressure
        p = np.concatenate(MPI.COMM_WORLD.allgather(c.state.pressure))
        area = np.concatenate(MPI.COMM_WORLD.allgather(c.geometry.point_area))
        assert len(p) >= 25 and np.all(p[area > 0] > 0)
        np.testing.assert_allclose(p[area > 0], -P3 / passes, rtol=1e-6)


@pytest.mark.parametrize("master_surface", ["faceted", "smooth"])
@pytest.mark.parametrize("cells", ["hexahedra", "tetrahedra"])
def test_assembled_jacobian_with_friction_on_curved_masters(cells, master_surface, tmp_path):
    """Volume + normal + friction against 9-node and 6-node master facets of curved
    (second-order) meshes, faceted and smooth (the smooth element's columns reach the
    nodes of the neighbouring facets through the nodal normals: the matrix pattern must
    hold them): after converged steps (history set), a perturbed state whose upper block
    moves on sideways — points in stick and in slip — every free entry of the assembled
    matrix equals the central difference of the assembled residual to 1e-6 of the
    largest entry."""
    msh = tmp_path / "stack.msh"
    write_stack_msh(msh, cells=cells, order=2)
    s = quadratic_stack_scene(tmp_path, msh, master_surface=master_surface)
    s["contact"][2].update(mu=0.3, eps_t=EPS)  # stiff enough for the sideways motion to make points slip
    sim = Simulation(scene.load(s), MPI.COMM_SELF, log=quiet)
    sim.run()
    err, scale = sliding_jacobian_error(sim)
    assert err < 1e-6 * scale


def test_a_point_over_a_kinked_master_edge_is_named_in_the_failure_story(tmp_path):
    """The patch-test blocks (5 × 5 slave facets on 4 × 4 master facets) with quadratic
    elements and ε_N = 10⁴: the slave nodes on x = 0.5 or y = 0.5 lie exactly over an
    inner edge of the master, which the non-uniform contact pressure kinks; such a node
    switches between the two facets every Newton iteration and the step cannot
    converge (a limitation of node-to-surface contact on a C0 master): the full-step
    fallback 2-cycles and is stopped as stalled. The run stops with that diagnosis:
    the failed attempt's story counts the facet switches in every iteration of that
    solve and names the points, all on those lines of the interface."""
    import json

    from hypercontact.simulation import StepFailure

    s = scene.load(ROOT_SCENES / "blocks.toml", overrides=[
        "discretisation.degree=2", "contact.0.eps_n=1e4", "steps.max_cutbacks=0", "output.xdmf=false",
        f'output.dir="{tmp_path}"'])
    messages = []
    sim = Simulation(s, MPI.COMM_SELF, log=messages.append)
    with pytest.raises(StepFailure):
        sim.run()
    [story] = json.loads((tmp_path / "summary.json").read_text())["failed_attempts"]
    switches = story["master_facet_flips_per_iteration"]
    warn = sim.scene["steps"]["chatter_warning"]
    assert story["reason"] == "STALLED" and story["solves"][-1]["line_search"] == "basic"
    assert len(switches) == story["newton_iterations"] >= warn and all(n > 0 for n in switches)
    named = story["most_master_facet_flips"]
    assert len(named) == 5 and named[0]["flips"] >= len(switches) - 1
    for f in named:
        x, y, z = f["point"]
        assert f["contact"] == "interface" and abs(z - 0.5) < 1e-9
        assert min(abs(x - 0.5), abs(y - 0.5)) < 1e-9
    assert any("switched master facet" in m for m in messages)


def patch_run(tmp_path, eps_n, integration, master_surface):
    """The patch-test blocks with quadratic hexahedra: (Newton iterations per step, σ_zz
    spread)."""
    from reference.patch_spread import sigma_zz_spread

    s = scene.load(ROOT_SCENES / "blocks.toml", overrides=[
        "discretisation.degree=2", f"contact.0.eps_n={eps_n}", f'contact.0.integration="{integration}"',
        f'contact.0.master_surface="{master_surface}"', "steps.max_cutbacks=0", "output.xdmf=false",
        f'output.dir="{tmp_path / (integration + str(eps_n))}"'])
    sim = Simulation(s, MPI.COMM_SELF, log=quiet)
    writer = sim.run()
    return [st["newton_iterations"] for st in writer.steps], sigma_zz_spread(sim)


def test_a_smooth_quadratic_master_converges_where_the_faceted_one_cycles(tmp_path):
    """The same non-matching blocks as above (5 × 5 slave facets on 4 × 4 master facets, 27-node
    hexahedra) with master_surface = "smooth": the averaged nodal normals make the master's
    normal continuous over its inner edges, so the points over them no longer switch facets.
    At ε_N = 10⁴, where the faceted master stops, both the nodal and the Gauss-point slaves
    converge in each of the two steps without a cut-back, in few Newton iterations (measured 4
    and 3); with Gauss points the σ_zz spread falls as the penalty rises (the patch test's
    penalty limit; measured 5.6 %, 1.6 %, 1.0 % at 10³, 10⁴, 10⁵)."""
    its, _ = patch_run(tmp_path, 1e4, "nodal", "smooth")
    assert len(its) == 2 and max(its) <= 6
    spreads = []
    for eps_n in (1e3, 1e4, 1e5):
        its, spread = patch_run(tmp_path, eps_n, "gauss", "smooth")
        assert len(its) == 2 and max(its) <= 6
        spreads.append(spread)
    assert spreads[0] > spreads[1] > spreads[2]
    assert spreads[1] < 0.03
