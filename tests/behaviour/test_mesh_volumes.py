"""A gmsh file's physical volumes: every meshed volume in exactly one, or the
file is refused, naming the volume (dolfinx reads the cells of physical
volumes only, once per physical volume)."""
import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import geometry

LOWER, UPPER = 0.4, 0.6  # the parts' lengths along z (cross-section 1 × 1)


def write_bar_msh(path, orphan=False, overlap=False):
    """[0,1]² × [0, LOWER] and [0,1]² × [LOWER, 1], fragmented (one shared face), 2 × 2 hexahedra across and
    0.2 along z, to ``path`` (rank 0). Physical volumes "lower" and "upper"; surfaces xmin ... zmax.
    ``orphan``: the upper part in no physical volume (saved all the same); ``overlap``: both parts in a third
    physical volume "all" too."""
    if MPI.COMM_WORLD.rank == 0:
        gmsh = geometry._gmsh()
        gmsh.clear()
        gmsh.model.add("bar")
        a = gmsh.model.occ.addBox(0, 0, 0, 1, 1, LOWER)
        b = gmsh.model.occ.addBox(0, 0, LOWER, 1, 1, UPPER)
        gmsh.model.occ.fragment([(3, a)], [(3, b)])
        gmsh.model.occ.synchronize()
        for _, tag in gmsh.model.getEntities(1):
            lo_hi = np.array(gmsh.model.getBoundingBox(1, tag)).reshape(2, 3)
            length = np.ptp(lo_hi, axis=0)
            gmsh.model.mesh.setTransfiniteCurve(tag, (round(length[2] / 0.2) if length[2] > 1e-6 else 2) + 1)
        for _, tag in gmsh.model.getEntities(2):
            gmsh.model.mesh.setTransfiniteSurface(tag)
            gmsh.model.mesh.setRecombine(2, tag)
        parts = sorted((gmsh.model.getBoundingBox(3, t)[2], t) for _, t in gmsh.model.getEntities(3))
        for _, tag in parts:
            gmsh.model.mesh.setTransfiniteVolume(tag)
        names = {}
        for _, tag in gmsh.model.getEntities(2):
            lo, hi = np.array(gmsh.model.getBoundingBox(2, tag)).reshape(2, 3)
            for axis in range(3):
                if hi[axis] - lo[axis] < 1e-6 and (lo[axis] < 1e-6 or lo[axis] > 1 - 1e-6):
                    names.setdefault("xyz"[axis] + ("min" if lo[axis] < 1e-6 else "max"), []).append(tag)
        for i, (name, tags) in enumerate(sorted(names.items()), start=1):
            gmsh.model.addPhysicalGroup(2, tags, i)
            gmsh.model.setPhysicalName(2, i, name)
        for i, (name, (_, tag)) in enumerate(zip(("lower", "upper"), parts[: 1 if orphan else 2]), start=100):
            gmsh.model.addPhysicalGroup(3, [tag], i)
            gmsh.model.setPhysicalName(3, i, name)
        if overlap:
            gmsh.model.addPhysicalGroup(3, [t for _, t in parts], 200)
            gmsh.model.setPhysicalName(3, 200, "all")
        gmsh.option.setNumber("Mesh.SaveAll", 1 if orphan else 0)
        gmsh.model.mesh.generate(3)
        gmsh.write(str(path))
        gmsh.option.setNumber("Mesh.SaveAll", 0)
        gmsh.clear()
    MPI.COMM_WORLD.barrier()


@pytest.mark.parametrize("kind, words", [
    ("orphan", r"the elements of volume \d+ are in no physical volume \(its physical volumes: lower\)"),
    ("overlap", r"volume \d+ is in the physical volumes '(lower|upper)' and 'all': a cell can be in one only"),
])
def test_cells_in_no_or_two_physical_volumes_are_refused(kind, words, out_dir):
    """dolfinx reads the cells of physical volumes only (a volume in none would lose its cells), once per
    physical volume (in two: its cells twice)."""
    msh = out_dir / f"{kind}.msh"
    write_bar_msh(msh, orphan=kind == "orphan", overlap=kind == "overlap")
    with pytest.raises(ValueError, match=f"mesh file '.*{kind}\\.msh'.*{words}"):
        geometry.read_msh(MPI.COMM_WORLD, msh)
