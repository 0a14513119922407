"""gmsh files as users write them: tetrahedra and hexahedra, first and second
order (Mesh.ElementOrder = 2), run as they are — checked on the stacked blocks'
closed form (tests/reference/stack.py); a file that mixes kinds or orders, or
has elements dolfinx cannot build, is refused with a message naming them."""
import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import geometry, scene
from hypercontact.simulation import Simulation
from reference.homogeneous import mooney_rivlin_principal
from reference.homogeneous import compressed_block
from reference.stack import write_stack_msh

PARAMS = dict(alpha1=0.1863, alpha2=0.0098, K=5.0)
EPS, D = 50.0, 0.1


@pytest.mark.parametrize("cells", ["tetrahedra", "hexahedra"])
def test_second_order_file_runs_quadratic_elements_exactly(cells, out_dir):
    """A second-order .msh (curved-capable P2 geometry) with degree-2 elements: the lower block
    of the stack between the base plane and a top plane at z = ½ (the upper block held
    clear of it, fixed in place) is in the closed form's homogeneous state."""
    msh = out_dir / f"stack2_{cells}.msh"
    write_stack_msh(msh, cells=cells, order=2)
    plane = {"obstacle": "plane", "eps_n": EPS}
    data = {
        "mesh": {"builder": "file", "file": str(msh)},
        "material": {"law": "mooney_rivlin", "parameters": PARAMS},
        "discretisation": {"degree": 2, "quadrature_degree": 4},
        "bc": [{"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]},
               {"surface": "upper_bottom", "fix": ["x", "y", "z"]}],
        "contact": [
            {"name": "top", "surface": "lower_top", **plane, "point": [0, 0, 0.5], "normal": [0, 0, -1.0],
             "motion": [0, 0, -D / 2]},
            {"name": "base", "surface": "base", **plane, "point": [0, 0, 0], "normal": [0, 0, 1.0]},
        ],
        "steps": {"initial": 0.25, "max": 0.5},
        "solver": {"rtol": 1e-12, "atol": 1e-12},
        "output": {"dir": str(out_dir), "xdmf": False},
    }
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet)
    assert sim.V.mesh.geometry.dofmap.links(0).size == (10 if cells == "tetrahedra" else 27)
    sim.run()
    # the lower block (height ½) pressed by d/2 between two planes: homogeneous.py's two gaps
    lat, l3, P3 = compressed_block(lambda a, b, c: mooney_rivlin_principal(a, b, c, **PARAMS), 0.5, D / 2, EPS)
    top, base = sim.contacts
    assert top.force(sim.u)[2] == pytest.approx(P3, rel=1e-6)
    assert base.force(sim.u)[2] == pytest.approx(-P3, rel=1e-6)
    X = sim.V.tabulate_dof_coordinates()[: sim.V.dofmap.index_map.size_local]
    u = sim.u.x.array.reshape(-1, 3)[: len(X)]
    lower = X[:, 2] < 0.5 + 1e-9
    # (the upper block's bottom nodes at z = ½ are fixed; the lower block's top nodes there are not)
    moving = lower & ~((np.abs(X[:, 2] - 0.5) < 1e-9) & (np.abs(u[:, 2]) < 1e-14))
    np.testing.assert_allclose(X[moving, 0] + u[moving, 0], lat * X[moving, 0], atol=1e-7)


def test_mixed_kinds_are_refused(out_dir):
    """Hexahedra in one volume and tetrahedra in the other: refused, both named."""
    msh = out_dir / "mixed.msh"
    if MPI.COMM_WORLD.rank == 0:
        gmsh = geometry._gmsh()
        gmsh.clear()
        gmsh.model.add("mixed")
        gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
        gmsh.model.occ.addBox(2, 0, 0, 1, 1, 1)
        gmsh.model.occ.synchronize()
        for _, tag in gmsh.model.getEntities(1):
            gmsh.model.mesh.setTransfiniteCurve(tag, 3)
        for _, tag in gmsh.model.getEntities(2):
            gmsh.model.mesh.setTransfiniteSurface(tag)
            b = gmsh.model.getBoundingBox(2, tag)
            if b[3] < 1.5:
                gmsh.model.mesh.setRecombine(2, tag)
        for _, tag in gmsh.model.getEntities(3):
            gmsh.model.mesh.setTransfiniteVolume(tag)
        gmsh.model.addPhysicalGroup(2, [1], 1)
        gmsh.model.setPhysicalName(2, 1, "side")
        gmsh.model.addPhysicalGroup(3, [1, 2], 100)
        gmsh.option.setNumber("Mesh.ElementOrder", 1)
        gmsh.model.mesh.generate(3)
        gmsh.write(str(msh))
        gmsh.clear()
    MPI.COMM_WORLD.barrier()
    with pytest.raises(ValueError, match=r"mixes volume elements \((8-node hexahedra and 4-node tetrahedra|"
                                         r"4-node tetrahedra and 8-node hexahedra)\): one kind and one order"):
        geometry.read_msh(MPI.COMM_WORLD, msh)


@pytest.mark.mpi
def test_a_contact_surface_with_faces_inside_the_body_is_refused(out_dir):
    """Two conforming boxes in one body, the surface group "top" holding the top face and the face
    the boxes share: contact on it is refused before the run, naming the key and the count."""
    from hypercontact.scene.errors import SceneError

    msh = out_dir / "inner_face.msh"
    if MPI.COMM_WORLD.rank == 0:
        gmsh = geometry._gmsh()
        gmsh.clear()
        gmsh.model.add("inner_face")
        gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
        gmsh.model.occ.addBox(0, 0, 1, 1, 1, 1)
        gmsh.model.occ.fragment([(3, 1)], [(3, 2)])
        gmsh.model.occ.synchronize()
        faces = {}
        for _, tag in gmsh.model.getEntities(2):
            b = gmsh.model.getBoundingBox(2, tag)
            if abs(b[2] - b[5]) < 1e-4:  # horizontal (occ pads its boxes by ~1e-7)
                faces[round((b[2] + b[5]) / 2)] = tag
        gmsh.model.addPhysicalGroup(2, [faces[2], faces[1]], 1)
        gmsh.model.setPhysicalName(2, 1, "top")
        gmsh.model.addPhysicalGroup(2, [faces[0]], 2)
        gmsh.model.setPhysicalName(2, 2, "bottom")
        gmsh.model.addPhysicalGroup(3, [e[1] for e in gmsh.model.getEntities(3)], 100)
        gmsh.model.setPhysicalName(3, 100, "body")
        gmsh.option.setNumber("Mesh.CharacteristicLengthMax", 0.5)
        gmsh.model.mesh.generate(3)
        gmsh.write(str(msh))
        gmsh.option.setNumber("Mesh.CharacteristicLengthMax", 1e22)
        gmsh.clear()
    MPI.COMM_WORLD.barrier()
    data = {"mesh": {"builder": "file", "file": str(msh)},
            "material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 10.0}},
            "bc": [{"surface": "bottom", "fix": ["x", "y", "z"]}],
            "contact": [{"name": "lid", "surface": "top", "obstacle": "plane", "point": [0, 0, 2.0],
                         "normal": [0, 0, -1.0], "motion": [0, 0, -0.1]}],
            "output": {"dir": str(out_dir / "inner_face"), "xdmf": False}}
    with pytest.raises(SceneError, match=r"contact\[0\]\.surface: surface 'top' has \d+ facets inside the body"):
        Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet)
    data["contact"][0]["surface"] = "bottom"  # a boundary surface passes the check
    data["bc"][0]["surface"] = "top"
    data["contact"][0].update(point=[0, 0, 0], normal=[0, 0, 1.0])
    Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet)
