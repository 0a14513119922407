"""A block between two frictionless rigid planes is in a homogeneous state:
the computed force must match the closed form from ψ (tests/reference)."""
import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation
from reference.block import D, EPS, PARAMS, block_scene, write_block_msh
from reference.homogeneous import compressed_block, mooney_rivlin_principal



@pytest.mark.mpi
@pytest.mark.parametrize("i2, builder", [("usual", "box"), ("paper", "box"), ("usual", "file")])
def test_force_matches_closed_form(i2, builder, out_dir):
    mesh_file = None
    if builder == "file":
        mesh_file = out_dir / "block.msh"
        write_block_msh(mesh_file)
    sim = Simulation(scene.load(block_scene(out_dir, i2, mesh_file=mesh_file)), MPI.COMM_WORLD, log=quiet)
    sim.run()
    top, base = sim.contacts
    f_top = top.force(sim.u)
    lat, l3, P3 = compressed_block(
        lambda a, b, c: mooney_rivlin_principal(a, b, c, **PARAMS, i2=i2), 1.0, D, EPS)
    assert P3 < 0
    assert f_top[2] == pytest.approx(P3 * 1.0, rel=1e-6)
    assert base.force(sim.u)[2] == pytest.approx(-P3, rel=1e-6)
    # the homogeneous state itself: lateral stretch at a corner node
    corner = np.array([1.0, 1.0, 1.0])
    X = sim.V.tabulate_dof_coordinates()[: sim.V.dofmap.index_map.size_local]
    hit = np.flatnonzero(np.linalg.norm(X - corner, axis=1) < 1e-12)
    if hit.size:
        ux = sim.u.x.array.reshape(-1, 3)[hit[0], 0]
        assert 1.0 + ux == pytest.approx(lat, rel=1e-6)
