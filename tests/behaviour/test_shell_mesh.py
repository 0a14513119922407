"""The structured hexahedral mesh of a shell octant (hypercontact.shell):
cell count, element quality at the poles and the centre, nodes on the spheres
and planes, and second-order convergence of volume and area."""
import math

import numpy as np
import pytest
import ufl
from dolfinx import fem
from mpi4py import MPI

from hypercontact.shell import build_shell_octant

RI, T = 95.0, 1.0
RO = RI + T


def global_min_max(comm, values):
    lo = values.min() if values.size else np.inf
    hi = values.max() if values.size else -np.inf
    return comm.allreduce(lo, op=MPI.MIN), comm.allreduce(hi, op=MPI.MAX)


def corner_jacobians(mesh):
    """det of the trilinear map's Jacobian at the 8 corners of every local cell.

    dolfinx hexahedra number vertices in tensor-product order, vertex
    v = i + 2 j + 4 k at reference point (i, j, k): the derivative along
    reference axis d at v is ±(x[v ^ 2^d] - x[v]), + where bit d of v is 0.
    """
    cells = mesh.geometry.dofmap.array.reshape(-1, 8)
    X = mesh.geometry.x[cells]  # (cells, 8, 3)
    dets = np.empty((len(cells), 8))
    for v in range(8):
        edges = [(-1.0 if v & bit else 1.0) * (X[:, v ^ bit] - X[:, v]) for bit in (1, 2, 4)]
        dets[:, v] = np.linalg.det(np.stack(edges, axis=-1))
    return dets


def facet_nodes(body, name):
    """The local facets tagged `name` and the coordinates of their nodes.

    The nodes are the dofs of a first-order Lagrange space on those facets
    (the same points as the mesh geometry: the coordinate element is Q1 too).
    """
    mesh = body.mesh
    facets = body.facet_tags.indices[body.facet_tags.values == body.surfaces[name]]
    V = fem.FunctionSpace(mesh, ("Lagrange", 1))
    dofs = fem.locate_dofs_topological(V, 2, facets)
    return facets, V.tabulate_dof_coordinates()[dofs]


@pytest.mark.mpi
def test_cell_count_and_corner_jacobians():
    comm = MPI.COMM_WORLD
    n, m = 16, 4
    body = build_shell_octant(comm, RI, T, n, m)
    assert body.mesh.topology.index_map(3).size_global == 3 * (n // 2) ** 2 * m
    assert set(body.surfaces) == {"inner", "outer", "xmin", "ymin", "zmin"}
    jmin, jmax = global_min_max(comm, corner_jacobians(body.mesh))
    assert jmin > 0.0
    # Bound: the uniform great-circle arcs give patch edges of 45° at a pole
    # (right angle) and of arccos(sqrt(2/3)) = 35.26° at the centre (120°
    # angle, three patches meet), and tangential sizes grow like r: the
    # smallest corner Jacobian (inner sphere, at the centre) over the largest
    # (outer sphere, at a pole) tends to (35.26/45)² sin(120°) (RI/RO)² = 0.521.
    # A latitude-longitude mesh would have elements collapsing at the pole
    # (ratio ~ 1/n), a bad split a much smaller angle; demand 0.9 of the limit.
    limit = (math.acos(math.sqrt(2.0 / 3.0)) / (math.pi / 4)) ** 2 * math.sin(2 * math.pi / 3) * (RI / RO) ** 2
    assert jmin / jmax > 0.9 * limit
    assert jmin / jmax < 1.1 * limit  # the bound above is the real one, not a loose guess


@pytest.mark.mpi
def test_boundary_nodes_on_spheres_and_planes():
    comm = MPI.COMM_WORLD
    n, m = 8, 2
    body = build_shell_octant(comm, RI, T, n, m)
    expected_facets = {"inner": 3 * (n // 2) ** 2, "outer": 3 * (n // 2) ** 2, "xmin": n * m, "ymin": n * m, "zmin": n * m}
    for name, count in expected_facets.items():
        facets, x = facet_nodes(body, name)
        owned = facets < body.mesh.topology.index_map(2).size_local
        assert comm.allreduce(int(owned.sum())) == count, name
        if name in ("inner", "outer"):
            radius = RI if name == "inner" else RO
            error = np.abs(np.linalg.norm(x, axis=1) - radius) / radius
        else:
            error = np.abs(x[:, "xyz".index(name[0])]) / RO
        assert global_min_max(comm, error)[1] < 1e-8, name
    # every node lies in the octant of the shell
    x = body.mesh.geometry.x
    r = np.linalg.norm(x, axis=1)
    rmin, rmax = global_min_max(comm, r)
    assert rmin > RI * (1 - 1e-8) and rmax < RO * (1 + 1e-8)
    assert global_min_max(comm, x.min(axis=1))[0] > -1e-8 * RO


def rate(errors):
    return [math.log2(e0 / e1) for e0, e1 in zip(errors, errors[1:])]


@pytest.mark.mpi
def test_volume_and_area_converge_at_second_order():
    comm = MPI.COMM_WORLD
    exact_volume = math.pi / 6 * (RO ** 3 - RI ** 3)
    exact_area = math.pi / 2 * RI ** 2
    volume_errors, area_errors = [], []
    for n in (4, 8, 16):
        body = build_shell_octant(comm, RI, T, n, 1)
        mesh = body.mesh
        one = fem.Constant(mesh, 1.0)
        ds = ufl.Measure("ds", domain=mesh, subdomain_data=body.facet_tags)
        volume = comm.allreduce(fem.assemble_scalar(fem.form(one * ufl.dx(domain=mesh))))
        area = comm.allreduce(fem.assemble_scalar(fem.form(one * ds(body.surfaces["inner"]))))
        volume_errors.append(abs(volume - exact_volume) / exact_volume)
        area_errors.append(abs(area - exact_area) / exact_area)
    assert volume_errors[-1] < 1e-2 and area_errors[-1] < 1e-2
    assert min(rate(volume_errors)) >= 1.8, volume_errors
    assert min(rate(area_errors)) >= 1.8, area_errors


@pytest.mark.mpi
@pytest.mark.parametrize("kwargs, name", [
    (dict(n=7), "'n'"), (dict(n=0), "'n'"), (dict(n=-4), "'n'"),
    (dict(m=0), "'m'"), (dict(thickness=-1.0), "'thickness'"), (dict(inner_radius=0.0), "'inner_radius'"),
])
def test_bad_arguments_name_the_argument(kwargs, name):
    with pytest.raises(ValueError, match=name):
        build_shell_octant(MPI.COMM_WORLD, **kwargs)


def test_odd_n_message_says_even():
    with pytest.raises(ValueError, match="'n': expected an even number"):
        build_shell_octant(MPI.COMM_WORLD, n=15)
