"""A graded box of tetrahedra (mesh.cells = "tetrahedra" with a grading):
each graded hexahedron split into six tetrahedra around its main diagonal,
each boundary quadrilateral into the two triangles that match
(geometry.kuhn_tetrahedra). Checked against the box itself: every tetrahedron
has positive volume and together they have the box's volume (an overlap or a
gap would change the sum of the positive volumes); the split conforms (a face
cut along different diagonals from its two sides would leave interior
triangles without a neighbour: more exterior facets than the boundary's);
each named surface has its plane's area; the hexahedral graded box of the
same keys has the same volume and surfaces."""
import numpy as np
import pytest
import ufl
from dolfinx import fem
from mpi4py import MPI

from hypercontact import _dolfinx as dfx
from hypercontact.geometry import build_mesh, graded_box_arrays, kuhn_tetrahedra
from hypercontact.scene.mesh import Mesh

SIZE, ORIGIN, N, M = [2.0, 3.0, 1.5], [0.5, -1.0, -1.5], 3, 2
GRADING = [3.0, 1.0, -2.0]  # clustered towards xmin, uniform along y, towards zmax
AREAS = {"xmin": SIZE[1] * SIZE[2], "xmax": SIZE[1] * SIZE[2], "ymin": SIZE[0] * SIZE[2],
         "ymax": SIZE[0] * SIZE[2], "zmin": SIZE[0] * SIZE[1], "zmax": SIZE[0] * SIZE[1]}


def signed_volumes(x, tets):
    P = np.asarray(x)[tets]
    return np.einsum("ij,ij->i", P[:, 1] - P[:, 0], np.cross(P[:, 2] - P[:, 0], P[:, 3] - P[:, 0])) / 6.0


def test_the_split_of_the_graded_grid_has_positive_tetrahedra_filling_the_box():
    x, hexes, _, quads, _ = graded_box_arrays(SIZE, N, M, ORIGIN, GRADING)
    tets, triangles = kuhn_tetrahedra(hexes, quads)
    assert tets.shape == (6 * N * N * M, 4) and triangles.shape == (2 * len(quads), 3)
    v = signed_volumes(x, tets)
    assert v.min() > 0.0
    assert v.sum() == pytest.approx(np.prod(SIZE), rel=1e-12)
    # each quadrilateral's two triangles have its area and face outwards alike (one normal per quadrilateral)
    P = x[triangles]
    normals = np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]).reshape(-1, 2, 3)
    assert np.allclose(normals[:, 0] / np.linalg.norm(normals[:, 0], axis=1)[:, None],
                       normals[:, 1] / np.linalg.norm(normals[:, 1], axis=1)[:, None])


def mesh_of(cells):
    spec = Mesh(builder="box", size=SIZE, origin=ORIGIN, n=N, m=M, grading=GRADING, cells=cells)
    return build_mesh(MPI.COMM_WORLD, spec.dict())


def integral(body, measure):
    return dfx.assemble_scalar(fem.form(fem.Constant(body.mesh, 1.0) * measure), body.mesh.comm)


@pytest.mark.mpi
@pytest.mark.parametrize("cells", ["tetrahedra", "hexahedra"])
def test_graded_box_volume_surfaces_and_conformity(cells):
    body = mesh_of(cells)
    mesh = body.mesh
    assert mesh.topology.cell_type.name == ("tetrahedron" if cells == "tetrahedra" else "hexahedron")
    per_hex = 6 if cells == "tetrahedra" else 1
    assert mesh.topology.index_map(3).size_global == per_hex * N * N * M
    assert integral(body, ufl.dx(domain=mesh)) == pytest.approx(np.prod(SIZE), rel=1e-12)
    # conforming: the exterior facets are exactly the boundary's (2 triangles per boundary quadrilateral)
    mesh.topology.create_connectivity(2, 3)
    exterior = dfx.owned_exterior_facets(mesh)[0]
    per_quad = 2 if cells == "tetrahedra" else 1
    assert mesh.comm.allreduce(len(exterior), op=MPI.SUM) == per_quad * (2 * N * N + 4 * N * M)
    assert set(body.surfaces) == set(AREAS)
    ds = ufl.Measure("ds", domain=mesh, subdomain_data=body.facet_tags)
    for name, area in AREAS.items():
        assert integral(body, ds(body.surfaces[name])) == pytest.approx(area, rel=1e-12), name
    assert integral(body, ufl.ds(domain=mesh)) == pytest.approx(sum(AREAS.values()), rel=1e-12)
    # graded: the cells at the xmin side are thinner than those at xmax (t³ spacing)
    x = mesh.geometry.x
    assert mesh.comm.allreduce(float(np.min(np.where(x[:, 0] > ORIGIN[0], x[:, 0], np.inf)) - ORIGIN[0])
                               if len(x) else np.inf, op=MPI.MIN) == pytest.approx(SIZE[0] / N ** 3)


def test_a_focus_inside_the_box_clusters_the_cells_from_both_sides():
    """focus = the punch's edge (x = y = 20 on a 40 mm plate), grading 2 on x, y and
    towards the top (z = 10, on the box): the focus's coordinate is a grid line, the
    spacing is smallest on both sides of it and grows monotonically away (both
    halves map t² onto their side), the cells fill the box."""
    x, hexes, _, quads, _ = graded_box_arrays([40.0, 40.0, 10.0], 8, 4, [0.0, 0.0, 0.0], [2.0, 2.0, 2.0],
                                              focus=[20.0, 20.0, 10.0])
    for axis, k, c, L in ((0, 8, 20.0, 40.0), (1, 8, 20.0, 40.0), (2, 4, 10.0, 10.0)):
        lines = np.unique(x[:, axis])
        assert len(lines) == k + 1 and lines[0] == 0.0 and lines[-1] == L
        h = np.diff(lines)
        if c < L:
            i = int(np.flatnonzero(lines == c)[0])
            assert i == k // 2  # round(k c / L) cells below the focus
            assert np.all(np.diff(h[:i]) < 0) and np.all(np.diff(h[i:]) > 0)
            assert h[i - 1] == pytest.approx(h[i]) and h[i] < 0.3 * h[0]
        else:  # on the max side: the one-sided rule, clustered towards it
            assert np.all(np.diff(h) < 0)
    tets, _ = kuhn_tetrahedra(hexes, quads)
    v = signed_volumes(x, tets)
    assert v.min() > 0.0 and v.sum() == pytest.approx(40.0 * 40.0 * 10.0, rel=1e-12)


@pytest.mark.parametrize("keys, message", [
    ({"focus": [20.0, 20.0, 10.0]}, "no axis is graded"),
    ({"focus": [50.0, 20.0, 10.0], "grading": [2.0, 2.0, 1.0]}, "x = 50 is outside the box"),
    ({"builder": "shell_octant", "n": 4, "focus": [1.0, 1.0, 1.0]}, "focus applies to the box builder"),
])
def test_a_bad_focus_is_refused_naming_the_key(keys, message):
    from hypercontact import scene

    data = {"mesh": {"builder": "box", "size": [40.0, 40.0, 10.0], **keys},
            "material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 2.0}}}
    with pytest.raises(scene.SceneError, match=rf"mesh\.focus.*{message}"):
        scene.load(data)


def test_a_core_keeps_uniform_cells_on_the_clustered_side_and_grows_smoothly_beyond():
    """core = 1.5 on a 40-long axis graded t³ towards the min side (x, y) or the max side
    (z, g = −3): the cells inside the core are equal, the first cell beyond it is as large
    as a core cell (the shifted power law), the spacing then grows monotonically, no cell
    is more than 2.5 times its neighbour, and the cells fill the box; the core gets more
    cells as n grows. A core of 0 is the plain grading."""
    counts = []
    for n in (12, 16, 20):
        x, hexes, _, quads, _ = graded_box_arrays([40.0, 40.0, 40.0], n, n, [0.0, 0.0, -40.0], [3.0, 3.0, -3.0],
                                                  core=[1.5, 1.5, 1.5])
        for axis in range(3):
            lines = np.unique(x[:, axis])
            assert len(lines) == n + 1
            d = lines - lines[0] if axis < 2 else lines[-1] - lines[::-1]  # distance from the clustered side
            assert d[0] == 0.0 and d[-1] == pytest.approx(40.0, rel=1e-12)
            h = np.diff(d)
            j = int(np.flatnonzero(np.isclose(d, 1.5, rtol=1e-12))[0])  # the core's end is a grid line
            assert np.allclose(h[:j], 1.5 / j, rtol=1e-12)
            assert h[j] == pytest.approx(h[j - 1], rel=1e-6)
            assert np.all(np.diff(h[j:]) > 0)
            assert np.max(np.maximum(h[1:] / h[:-1], h[:-1] / h[1:])) <= 2.5 + 1e-12
            counts.append(j) if axis == 0 else None
        tets, _ = kuhn_tetrahedra(hexes, quads)
        v = signed_volumes(x, tets)
        assert v.min() > 0.0 and v.sum() == pytest.approx(40.0 ** 3, rel=1e-12)
    assert counts == sorted(counts) and counts[-1] > counts[0]
    plain = graded_box_arrays([40.0, 40.0, 40.0], 8, 8, [0.0, 0.0, 0.0], [3.0, 3.0, 3.0])[0]
    zero = graded_box_arrays([40.0, 40.0, 40.0], 8, 8, [0.0, 0.0, 0.0], [3.0, 3.0, 3.0], core=[0.0, 0.0, 0.0])[0]
    assert np.array_equal(plain, zero)


@pytest.mark.parametrize("keys, message", [
    ({"core": [1.0, 1.0, 1.0]}, "needs that axis graded"),
    ({"core": [-1.0, 0.0, 0.0], "grading": [2.0, 1.0, 1.0]}, "x length is negative"),
    ({"core": [40.0, 0.0, 0.0], "grading": [2.0, 1.0, 1.0]}, "must be shorter than the box's"),
    ({"core": [1.0, 0.0, 0.0], "grading": [2.0, 1.0, 1.0], "focus": [20.0, 0.0, 0.0]}, "focus inside the box"),
    ({"builder": "shell_octant", "n": 4, "core": [1.0, 1.0, 1.0]}, "core applies to the box builder"),
])
def test_a_bad_core_is_refused_naming_the_key(keys, message):
    from hypercontact import scene

    data = {"mesh": {"builder": "box", "size": [40.0, 40.0, 10.0], **keys},
            "material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 2.0}}}
    with pytest.raises(scene.SceneError, match=rf"mesh\.core.*{message}"):
        scene.load(data)
