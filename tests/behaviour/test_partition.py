"""The same mesh is split the same way however many meshes the process built
before it: a checkpoint holds each rank's own part of the solution and
contact history, and is resumed in a process that may have built other
meshes first (under pytest, every earlier test's). dolfinx's default
partitioner drew on SCOTCH's random state; _dolfinx.partitioner seeds it on
every call. Meaningful under mpirun -n 2 (scripts/test.sh runs it so)."""
import numpy as np
import pytest
from mpi4py import MPI

from hypercontact.geometry import build_mesh
from hypercontact.scene.mesh import Mesh

SHELL = dict(builder="shell_octant", inner_radius=95.0, thickness=1.0, n=16, m=4)
OTHERS = [dict(builder="box", size=[2.0, 3.0, 1.5], n=3, m=2, grading=[3.0, 1.0, -2.0], cells="tetrahedra"),
          dict(builder="box", size=[1.0, 1.0, 1.0], n=5, m=3), dict(builder="oring", n=4, m=4)]


def owned_cells(spec):
    mesh = build_mesh(MPI.COMM_WORLD, Mesh(**spec).dict()).mesh
    n = mesh.topology.index_map(3).size_local
    return np.sort(np.asarray(mesh.topology.original_cell_index[:n]))


@pytest.mark.mpi
def test_the_same_mesh_is_split_alike_after_other_meshes():
    first = owned_cells(SHELL)
    for spec in OTHERS * 3:
        owned_cells(spec)
        assert np.array_equal(owned_cells(SHELL), first)
    # the parts cover the mesh once
    sizes = MPI.COMM_WORLD.allgather(len(first))
    assert sum(sizes) == 3 * 8 * 8 * 4
