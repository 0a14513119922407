"""Self-contact (docs/method.md §3.5): a surface that is its own master. A slave
node never pairs with the facets that touch its own facets, nor with facets
that do not face it in the reference configuration. Checked on a hollow tube
(the tube builder, a half model x >= 0 with the symmetry plane x = 0, plane
strain) crushed between two rigid plates until its inner wall touches itself:
before the touch the self-contact must change nothing (the quarter model
without it gives the same forces), at the touch its tangent must be the
derivative of its residual; the builder against the polygon's closed form."""
import math

import numpy as np
import pytest
import ufl
from conftest import quiet
from mpi4py import MPI

from hypercontact import _dolfinx as dfx
from hypercontact import scene
from hypercontact.simulation import Simulation
from reference.finite_differences import assembled_and_fd_jacobians
from reference.runs import column, run

R_IN, T = 8.0, 2.0


def tube(half=True, delta=7.5, n=24, m=3, self_contact=True, master_surface="faceted"):
    """The tube of inner radius 8 and wall 2 (mm) crushed by plates moving δ each: the half
    model (θ from −90° to 90°, both cut faces on x = 0) with both plates and the inner wall's
    self-contact, or the quarter model (θ from 0° to 90°, the cut face θ = 0 on y = 0)."""
    data = {"title": "tube crushed between plates",
            "mesh": {"builder": "tube", "inner_radius": R_IN, "thickness": T, "length": 1.0, "layers": 1,
                     "n": n if half else n // 2, "m": m, "angles": [-90.0, 90.0] if half else [0.0, 90.0]},
            "material": {"law": "neo_hookean", "parameters": {"mu": 0.5, "K": 5.0}},
            "bc": [{"surface": "zmin", "fix": ["z"]}, {"surface": "zmax", "fix": ["z"]},
                   {"surface": "end", "fix": ["x"]}, {"surface": "start", "fix": ["x"] if half else ["y"]}],
            "contact": [{"name": "top", "surface": "outer", "obstacle": "plane", "point": [0.0, R_IN + T, 0.0],
                         "normal": [0.0, -1.0, 0.0], "motion": [0.0, -delta, 0.0]}],
            "steps": {"initial": 0.1, "max": 0.1},
            "output": {"xdmf": False, "probes": {"crown": [0.0, R_IN, 0.0]}}}
    if half:
        data["contact"].append({"name": "bottom", "surface": "outer", "obstacle": "plane",
                                "point": [0.0, -R_IN - T, 0.0], "normal": [0.0, 1.0, 0.0],
                                "motion": [0.0, delta, 0.0]})
        if self_contact:
            data["contact"].append({"name": "fold", "surface": "inner", "obstacle": "surface", "master": "inner",
                                    "master_surface": master_surface})
    return data


def test_tube_builder_against_the_polygon(tmp_path):
    """Straight-sided cells: the sector's volume and its inner and outer areas are
    those of the inscribed polygons, exactly; the cut faces lie on their planes."""
    n, m, length = 12, 2, 3.0
    data = tube(n=n, m=m)
    data["mesh"].update(length=length, layers=2, angles=[0.0, 90.0])
    sim = Simulation(scene.load(data, [f"output.dir={tmp_path}"]), MPI.COMM_SELF, log=quiet)
    mesh, tags, surfaces = sim.body.mesh, sim.body.facet_tags, sim.body.surfaces
    one = dfx.constant(mesh, 1.0)
    ds = dfx.facet_integration_measure(mesh, tags, 2)
    volume = dfx.assemble_scalar(dfx.compile_form(one * ufl.dx(domain=mesh)), MPI.COMM_SELF)
    dtheta = math.radians(90.0 / n)
    r_out = R_IN + T
    assert volume == pytest.approx(0.5 * n * (r_out**2 - R_IN**2) * math.sin(dtheta) * length, rel=1e-12)
    for name, r in (("inner", R_IN), ("outer", r_out)):
        area = dfx.assemble_scalar(dfx.compile_form(one * ds(surfaces[name])), MPI.COMM_SELF)
        assert area == pytest.approx(n * 2 * r * math.sin(dtheta / 2) * length, rel=1e-12), name
    X = dfx.node_coordinates(sim.V)
    for name, axis in (("start", 1), ("end", 0)):  # θ = 0 on y = 0, θ = 90° on x = 0
        nodes, _ = dfx.facet_vertex_nodes(sim.V, dfx.facets_with_tag(tags, surfaces[name]))
        assert len(nodes) > 0 and np.abs(X[nodes.ravel(), axis]).max() <= 1e-12 * r_out


def test_tube_builder_refuses_a_sector_beyond_half_a_turn():
    data = tube()
    data["mesh"]["angles"] = [0.0, 270.0]
    with pytest.raises(scene.SceneError, match=r"mesh\.angles.*at most 180"):
        scene.load(data)


@pytest.mark.parametrize("change, key, message", [
    ({"passes": 2}, "passes", "two-sided already"),
    ({"integration": "gauss"}, "integration", 'needs integration = "nodal"'),
    ({"mu": 0.3}, "mu", "frictionless"),
    ({"master": "inner+outer"}, "master", "slave surface alone"),
])
def test_self_contact_settings_refused_name_the_key(change, key, message):
    data = tube()
    data["contact"][2].update(change)
    with pytest.raises(scene.SceneError, match=rf"contact\[2\]\.{key}.*{message}"):
        scene.load(data)


def test_before_the_fold_self_contact_changes_nothing(tmp_path):
    """Crushed to δ = 7.5 mm (the inner wall's crown 0.4 mm from its mirror image),
    the wall bending hard at θ = 0: no slave point closes, and the plate force of
    the half model with self-contact equals the quarter model's without it (the
    same equations by symmetry) to 1e-10 at every step — the exclusion keeps each
    node from its own and its neighbours' facets under large deformation."""
    sim, half = run(tube(), tmp_path / "half")
    _, quarter = run(tube(half=False), tmp_path / "quarter")
    assert len(half.steps) == len(quarter.steps) >= 10
    assert np.all(column(half, "fold_closed_nodes") == 0)
    f_half, f_quarter = column(half, "top_fy"), column(quarter, "top_fy")
    assert np.abs(f_half - f_quarter).max() <= 1e-10 * np.abs(f_quarter).max()
    assert column(half, "crown_uy")[-1] < -7.0  # the crown moved most of the way to the axis
    # the search did look: the folding sides bring facets of the same wall within the capture distance
    assert sim.contacts[-1].geometry.candidates[1].size > 0


def test_self_contact_tangent_at_the_touch(tmp_path):
    """Crushed to δ = 7.98 mm the inner wall touches itself near the crown (slave
    points closed on both walls): the assembled tangent equals central
    differences of the residual."""
    sim, w = run(tube(delta=7.98), tmp_path)
    c = sim.contacts[-1]
    gap = np.asarray(c.evaluate(sim.u).gap)
    closed = gap < 0
    assert closed.sum() >= 4
    X = c.geometry.X[c.geometry.point_nodes[:, 0]]
    assert (X[closed, 1] > 0).any() and (X[closed, 1] < 0).any()  # points of both walls
    problem, x = sim.problem, sim.problem.x
    sim.w.vector.copy(x)
    free = np.flatnonzero(~np.isin(np.arange(x.getSize()), np.concatenate([dfx.bc_dofs(bc) for bc in sim.bcs])))
    # h below the smoothing band of the penalty (1e-6 × the layer, 7e-7 mm) and the closed gaps (~1e-6 mm)
    J, J_fd = assembled_and_fd_jacobians(problem, x, free, h=1e-8)
    A, B = J[np.ix_(free, free)], J_fd[np.ix_(free, free)]
    assert np.abs(A - B).max() <= 1e-5 * np.abs(B).max()


def mirror_model(delta, eps_n):
    """The quarter model (θ from 0° to 90°) whose inner wall meets the rigid frictionless plane
    y = 0 instead of its mirror image, with penalty ``eps_n``."""
    data = tube(half=False, delta=delta)
    data["contact"].append({"name": "fold", "surface": "inner", "obstacle": "plane", "point": [0.0, 0.0, 0.0],
                            "normal": [0.0, 1.0, 0.0], "eps_n": eps_n})
    return data


def test_past_the_fold_smooth_self_contact_equals_the_mirror_model(tmp_path):
    """Crushed to δ = 9 mm (the walls fold flat at 7.98 mm, then each is squeezed to half its
    thickness): the half model with the inner wall's self-contact on a smooth master against
    the quarter model pressed onto a rigid frictionless plane at y = 0, where the walls meet.
    By symmetry these are the same equations when the quarter's penalty is 4 ε_N: where the
    walls overlap by δ_o, a point of either wall is a slave point against the other (self-
    contact is two-sided), so the pressure between them is 2 ε_N δ_o; in the quarter model a
    wall at depth d = δ_o / 2 below y = 0 carries ε d. The plate force must agree at every load
    factor both runs reached (the issue's bound is 1 %), and the walls' overlap must be twice
    the quarter's penetration of its plane (no point passes further through the other wall)."""
    sim, half = run(tube(delta=9.0, master_surface="smooth"), tmp_path / "half")
    eps = sim.contacts[-1].eps_n
    sim_q, quarter = run(mirror_model(9.0, 4 * eps), tmp_path / "quarter")
    lam_h, lam_q = column(half, "load_factor"), column(quarter, "load_factor")
    assert lam_h[-1] == pytest.approx(1.0) and lam_q[-1] == pytest.approx(1.0)
    common = [(i, j) for i, lam in enumerate(lam_h) for j in np.flatnonzero(np.isclose(lam_q, lam, rtol=0, atol=1e-9))]
    assert len(common) >= 10
    f_half = column(half, "top_fy")[[i for i, _ in common]]
    f_quarter = column(quarter, "top_fy")[[j for _, j in common]]
    assert np.abs(f_half - f_quarter).max() <= 1e-4 * np.abs(f_quarter).max()
    assert column(half, "fold_closed_nodes")[-1] > 0 and abs(f_quarter[-1]) > 20.0  # well past the touch
    overlap = -np.asarray(sim.contacts[-1].evaluate(sim.u).gap).min()
    depth = -np.asarray(sim_q.contacts[-1].evaluate(sim_q.u).gap).min()
    assert depth > 0 and overlap == pytest.approx(2 * depth, rel=1e-3)


def test_a_flat_surface_does_not_contact_itself(tmp_path):
    """A slab's top surface as its own master, the slab squeezed sideways by 20 % (its top stays
    flat): no point may close, faceted or smooth, and the force is that of the run without the
    self-contact, to rounding."""
    def slab(self_contact=None):
        data = {"title": "slab", "mesh": {"builder": "box", "size": [4.0, 4.0, 1.0], "n": 4, "m": 1},
                "material": {"law": "neo_hookean", "parameters": {"mu": 0.5, "K": 5.0}},
                "bc": [{"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]},
                       {"surface": "zmin", "fix": ["z"]}],
                "contact": [{"name": "press", "surface": "xmax", "obstacle": "plane", "point": [4.0, 0.0, 0.0],
                             "normal": [-1.0, 0.0, 0.0], "motion": [-0.8, 0.0, 0.0]}],
                "steps": {"initial": 0.25, "max": 0.25}, "output": {"xdmf": False}}
        if self_contact:
            data["contact"].append({"name": "top", "surface": "zmax", "obstacle": "surface", "master": "zmax",
                                    "master_surface": self_contact})
        return data

    _, plain = run(slab(), tmp_path / "plain")
    for kind in ("faceted", "smooth"):
        sim, w = run(slab(kind), tmp_path / kind)
        assert np.all(column(w, "top_closed_nodes") == 0), kind
        assert column(w, "press_fx") == pytest.approx(column(plain, "press_fx"), rel=1e-10), kind
        assert sim.contacts[-1].geometry.candidates[1].size == 0, kind  # every pair excluded


@pytest.mark.mpi
@pytest.mark.parametrize("delta, master_surface", [(7.98, "faceted"), (8.8, "smooth")])
def test_self_contact_on_two_ranks_equals_serial(out_dir, delta, master_surface):
    data = tube(delta=delta, master_surface=master_surface)
    _, par = run(data, out_dir / f"par{master_surface}", MPI.COMM_WORLD)
    _, ser = run(data, out_dir / f"ser{master_surface}{MPI.COMM_WORLD.rank}", MPI.COMM_SELF)
    assert len(par.steps) == len(ser.steps)
    for key in ("top_fy", "crown_uy", "fold_closed_nodes"):
        assert column(par, key) == pytest.approx(column(ser, key), rel=1e-8, abs=1e-12), key
