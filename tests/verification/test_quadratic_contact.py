"""Rigid-obstacle contact with quadratic elements, tetrahedra and the mixed
formulation: the contact patch test — the block between two frictionless
rigid planes is in a homogeneous state, which every one of these spaces holds
exactly, so the computed forces, stretches and pressures must equal the
closed form of tests/reference/homogeneous.py (independent of the code)
whenever the contact integration is consistent (nodal weights ∫N_i dA, Gauss points, or a
pressure per facet)."""
import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation
from reference.block import D, EPS, PARAMS, block_scene
from reference.homogeneous import compressed_block, mooney_rivlin_principal

#: (cells, degree, formulation, integration) that integrate a uniform pressure exactly: 9-node
#: quadrilateral nodal weights ∫N_i dA are positive and consistent; Gauss points always are.
EXACT = [
    ("hexahedra", 2, "displacement", "nodal"),
    ("hexahedra", 2, "displacement", "gauss"),
    ("hexahedra", 1, "displacement", "gauss"),
    ("hexahedra", 2, "mixed", "nodal"),
    ("hexahedra", 2, "mixed", "gauss"),
    ("tetrahedra", 1, "displacement", "nodal"),
    ("tetrahedra", 1, "displacement", "gauss"),
    ("tetrahedra", 2, "displacement", "gauss"),
    ("tetrahedra", 2, "mixed", "gauss"),
    ("tetrahedra", 2, "displacement", "auto"),  # "auto" picks Gauss points on 6-node triangles
    ("hexahedra", 2, "displacement", "auto"),
    # a pressure per facet gives every node its consistent load ∫N_a p dA
    ("tetrahedra", 2, "displacement", "facet"),
    ("tetrahedra", 2, "mixed", "facet"),
    ("hexahedra", 2, "displacement", "facet"),
    ("hexahedra", 1, "displacement", "facet"),
    ("tetrahedra", 1, "displacement", "facet"),
]


def quadratic_block_scene(out, cells, degree, formulation, integration):
    s = block_scene(out)
    s["mesh"]["cells"] = cells
    s["discretisation"] = {"degree": degree, "formulation": formulation,
                           "quadrature_degree": 4 if degree == 2 else 2}
    for c in s["contact"]:
        c["integration"] = integration
    return s


def closed_form():
    return compressed_block(lambda a, b, c: mooney_rivlin_principal(a, b, c, **PARAMS), 1.0, D, EPS)


@pytest.mark.mpi
@pytest.mark.parametrize("cells, degree, formulation, integration", EXACT)
def test_patch_test_homogeneous_state(cells, degree, formulation, integration, out_dir):
    sim = Simulation(scene.load(quadratic_block_scene(out_dir, cells, degree, formulation, integration)),
                     MPI.COMM_WORLD, log=quiet)
    sim.run()
    lat, l3, P3 = closed_form()
    top, base = sim.contacts
    assert top.force(sim.u)[2] == pytest.approx(P3, rel=1e-6)
    assert base.force(sim.u)[2] == pytest.approx(-P3, rel=1e-6)
    # every slave point carries the same pressure −P3 (a consistent integration of a uniform one)
    for c in (top, base):
        p = np.concatenate(MPI.COMM_WORLD.allgather(c.state.pressure))
        assert len(p) > 0
        assert np.allclose(p, -P3, rtol=1e-6), (p.min(), p.max(), -P3)
    # the homogeneous deformation at every node: x = lat X, y = lat Y, z = λ3 Z + g (base gap)
    X = sim.V.tabulate_dof_coordinates()[: sim.V.dofmap.index_map.size_local]
    u = sim.u.x.array.reshape(-1, 3)[: len(X)]
    g = P3 / EPS  # the base's penalty gap (negative: penetration)
    assert np.allclose(X[:, 0] + u[:, 0], lat * X[:, 0], atol=1e-7)
    assert np.allclose(X[:, 2] + u[:, 2], l3 * X[:, 2] + g, atol=1e-7)


@pytest.mark.mpi
def test_six_node_triangle_nodal_weights_are_positive(out_dir):
    """The 6-node triangle's corner integrals ∫N_c dA vanish; the split-facet weights are
    positive (corner A/12, edge A/4 per facet) and sum to the area."""
    sim = Simulation(scene.load(quadratic_block_scene(out_dir, "tetrahedra", 2, "displacement", "nodal")),
                     MPI.COMM_WORLD, log=quiet)
    for c in sim.contacts:
        area = c.geometry.area
        assert np.all(area > 0)
        assert MPI.COMM_WORLD.allreduce(area.sum(), op=MPI.SUM) == pytest.approx(1.0, rel=1e-12)
        # the 2 × 2 face split into 8 six-node triangles: every one of its 5 × 5 nodes is a slave node
        assert MPI.COMM_WORLD.allreduce(len(area), op=MPI.SUM) == 25


@pytest.mark.parametrize("cells, degree, formulation, integration", [
    ("hexahedra", 2, "mixed", "nodal"), ("hexahedra", 2, "displacement", "gauss"),
    ("tetrahedra", 2, "displacement", "gauss"), ("tetrahedra", 2, "mixed", "gauss")])
def test_assembled_jacobian_matches_finite_differences_with_friction(cells, degree, formulation, integration,
                                                                      tmp_path):
    """Volume (mixed: with the pressure unknown) + normal + friction against the rigid planes:
    after converged steps that slide the base (friction history set), at a perturbed state
    with points in stick and in slip, every free entry of the assembled matrix equals the
    central difference of the assembled residual to 1e-6 of the largest entry — the slave
    points' dofs found in the unknown (the mixed formulation's displacement block) and every
    Gauss point's element spread over its facet's nodes."""
    from hypercontact import _dolfinx as dfx
    from reference.finite_differences import constrained_dofs, simulation_jacobian_error

    s = quadratic_block_scene(tmp_path, cells, degree, formulation, integration)
    s["contact"][1].update(mu=0.3, motion=[0.02, 0.0, 0.0])
    s["contact"][0]["mu"] = 0.3
    sim = Simulation(scene.load(s), MPI.COMM_SELF, log=quiet)
    sim.run()
    constrained = constrained_dofs(sim)
    rng = np.random.default_rng(3)
    w = sim.w.x.array
    w[~constrained] += 1e-4 * rng.standard_normal(np.count_nonzero(~constrained))
    # the base's slave nodes on one side move on by 2e-3: those slip, the others stick
    X = dfx.node_coordinates(sim.V)
    shift = np.zeros((len(X), 3))
    shift[(X[:, 2] < 1e-9) & (X[:, 1] > 0.5), 0] = 2e-3
    index = np.arange(3 * len(X)) if sim.model._u_dofs is None else sim.model._u_dofs
    w[index] += np.where(constrained[index], 0.0, shift.ravel())
    sim.model.sync_displacement()
    base = sim.contacts[1]
    state = np.asarray(base.evaluate(sim.u).state)
    assert np.count_nonzero(state == 1) >= 2 and np.count_nonzero(state == 2) >= 2
    err, scale, J, free = simulation_jacobian_error(sim, constrained)
    assert err < 1e-6 * scale


@pytest.mark.mpi
@pytest.mark.parametrize("formulation", ["displacement", "mixed"])
def test_fields_hold_the_contact_pressure_at_the_vertices(formulation, out_dir):
    """fields.xdmf of a quadratic run: displacement and contact fields at the mesh vertices
    (what ParaView reads), the pressure −P3 on both contact faces, 0 elsewhere."""
    import h5py

    s = quadratic_block_scene(out_dir, "hexahedra", 2, formulation, "nodal")
    s["output"]["xdmf"] = True
    sim = Simulation(scene.load(s), MPI.COMM_WORLD, log=quiet)
    sim.run()
    _, _, P3 = closed_form()
    if MPI.COMM_WORLD.rank == 0:
        with h5py.File(out_dir / "fields.h5", "r") as h5:
            X = h5["Mesh/mesh/geometry"][...]
            last = max(h5["Function/contact_pressure"], key=lambda t: float(t.replace("_", ".")))
            p = h5[f"Function/contact_pressure/{last}"][...].ravel()
            u = h5[f"Function/displacement/{last}"][...]
        assert len(X) == 27 and len(p) == 27 and u.shape == (27, 3)  # the 3 × 3 × 3 vertices
        on_plane = np.isclose(X[:, 2], 0.0) | np.isclose(X[:, 2], 1.0)
        np.testing.assert_allclose(p[on_plane], -P3, rtol=1e-6)
        np.testing.assert_allclose(p[~on_plane], 0.0, atol=1e-12)


# --- Coulomb friction on quadratic elements: the stiff block pressed and pushed (the closed forms
# of tests/verification/test_friction_block.py: N = ε_N A δ, T = ε_T A s λ in stick, T = μN in slip)
G, EPS_F, MU, DELTA, PUSH = 1.0e6, 10.0, 0.3, 0.01, 0.0065
RIGID = 5 * EPS_F / G  # the block's compliance: the accuracy of the rigid-block closed forms


@pytest.mark.mpi
@pytest.mark.parametrize("cells, degree, formulation", [("hexahedra", 2, "displacement"),
                                                        ("tetrahedra", 2, "displacement"),
                                                        ("tetrahedra", 2, "mixed")])
def test_friction_sticks_below_mu_n_then_slides_at_mu_n(cells, degree, formulation, out_dir):
    data = {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 2, "m": 1, "cells": cells},
        "material": {"law": "neo_hookean", "parameters": {"mu": G, "K": G}},
        "discretisation": {"degree": degree, "formulation": formulation, "quadrature_degree": 4},
        "bc": [{"surface": "zmax", "fix": ["x", "y", "z"], "motion": [PUSH, 0.0, 0.0]},
               {"surface": "ymin", "fix": ["y"]}, {"surface": "ymax", "fix": ["y"]}],
        "contact": [{"name": "base", "surface": "zmin", "obstacle": "plane", "point": [0.0, 0.0, DELTA],
                     "normal": [0.0, 0.0, 1.0], "eps_n": EPS_F, "eps_t": EPS_F, "mu": MU}],
        "steps": {"initial": 0.1, "max": 0.1},
        "solver": {"rtol": 1e-12, "atol": 1e-13, "max_it": 30},
        "output": {"dir": str(out_dir), "xdmf": False, "symmetry_factor": 1.0},
    }
    writer = Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet).run()
    steps = writer.steps
    assert steps[-1]["load_factor"] == pytest.approx(1.0)
    n_ref = EPS_F * DELTA
    slide_at = MU * n_ref / (EPS_F * PUSH)
    kinds = {"stick": 0, "slide": 0}
    for s in steps:
        T, N = -s["base_fx"], s["base_fz"]
        assert N == pytest.approx(n_ref, rel=RIGID)
        assert s["base_dissipation_step"] >= 0.0
        if s["load_factor"] < slide_at * (1 - 10 * RIGID):
            kinds["stick"] += 1
            assert s["base_slip_nodes"] == 0 and s["base_stick_nodes"] > 0
            assert T == pytest.approx(EPS_F * PUSH * s["load_factor"], rel=RIGID)
        elif s["load_factor"] > slide_at * (1 + 10 * RIGID):
            kinds["slide"] += 1
            assert s["base_stick_nodes"] == 0 and s["base_slip_nodes"] > 0
            assert T == pytest.approx(MU * N, rel=1e-6)
    assert kinds["stick"] >= 3 and kinds["slide"] >= 3
