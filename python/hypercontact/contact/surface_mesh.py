"""The contact surfaces of a dolfinx mesh as plain arrays: slave nodes with
their areas, boundary quadrilaterals as node quadruples, and the facet across
each facet edge. What the C++ kernels take; nothing here depends on λ or u."""
import numpy as np
import ufl

from .. import _dolfinx as dfx


def nodal_areas(V, facet_tags, tag):
    """A_i = ∫_Γ N_i dA on the tagged surface, owned nodes (parallel-safe:
    assembled as a dolfinx form and summed over ranks; ghosts are 0)."""
    v = ufl.TestFunction(V)
    ds = dfx.facet_integration_measure(V.mesh, facet_tags, quadrature_degree=2)
    L = dfx.compile_form(ufl.dot(v, ufl.as_vector((1.0, 0.0, 0.0))) * ds(tag))
    b = dfx.assemble_vector_owned(L)
    with b.localForm() as bl:
        area = bl.array_r[0::3].copy()
    b.destroy()
    area[dfx.num_owned_nodes(V):] = 0.0  # ghosts are counted on their owner
    return area


def surface_facets(V, facet_tags, tag, owned_only=True):
    """The tagged boundary quadrilaterals of this rank as (f, 4) process-local
    node indices, counter-clockwise seen from outside the body (so that
    (x1 − x0) × (x3 − x0) points out of the body)."""
    facets = dfx.facets_with_tag(facet_tags, tag)
    vertices, cell = dfx.facet_vertex_nodes(V, facets)
    centres = dfx.cell_node_centres(V, cell)
    X = dfx.node_coordinates(V)
    keep = np.ones(len(facets), bool) if not owned_only else cell < dfx.num_owned_cells(V.mesh)
    out = []
    for quad, centre in zip(vertices[keep][:, [0, 1, 3, 2]], centres[keep]):  # tensor-product → cyclic
        x = X[quad]
        if np.dot(np.cross(x[1] - x[0], x[3] - x[0]), x.mean(axis=0) - centre) < 0:
            quad = quad[::-1]
        out.append(quad)
    return np.array(out, dtype=np.int32).reshape(-1, 4)


def edge_neighbours(facets):
    """(f, k): the facet across edge j (node j → j+1) of each facet, −1 if the
    edge is on the boundary of the surface (k nodes per facet)."""
    f, k = facets.shape
    b = np.roll(facets, -1, axis=1)
    lo, hi = np.minimum(facets, b).ravel().astype(np.int64), np.maximum(facets, b).ravel().astype(np.int64)
    key = lo * (int(facets.max()) + 1) + hi
    order = np.argsort(key, kind="stable")
    sk = key[order]
    out = np.full(k * f, -1, np.int32)
    for i in np.flatnonzero(sk[1:] == sk[:-1]):  # an edge shared by two facets (a manifold surface)
        e1, e2 = order[i], order[i + 1]
        out[e1], out[e2] = e2 // k, e1 // k
    return out.reshape(f, k)


GAUSS_2X2 = np.array([-1.0, 1.0]) / np.sqrt(3.0)


def gauss_points(quads, X):
    """The 2 × 2 Gauss points of bilinear quadrilaterals (f, 4) with node
    coordinates X: (nodes (4f, 4), weights M_i (4f, 4), det J × w (4f,))."""
    Xs = X[quads]
    nodes, weights, areas = [], [], []
    for s in GAUSS_2X2:
        for t in GAUSS_2X2:
            M = 0.25 * np.array([(1 - s) * (1 - t), (1 + s) * (1 - t), (1 + s) * (1 + t), (1 - s) * (1 + t)])
            dMs = 0.25 * np.array([-(1 - t), (1 - t), (1 + t), -(1 + t)])
            dMt = 0.25 * np.array([-(1 - s), -(1 + s), (1 + s), (1 - s)])
            a1, a2 = np.einsum("a,fak->fk", dMs, Xs), np.einsum("a,fak->fk", dMt, Xs)
            nodes.append(quads)
            weights.append(np.broadcast_to(M, (len(quads), 4)))
            areas.append(np.linalg.norm(np.cross(a1, a2), axis=1))
    return (np.ascontiguousarray(np.concatenate(nodes), dtype=np.int32).reshape(-1, 4),
            np.ascontiguousarray(np.concatenate(weights)).reshape(-1, 4), np.concatenate(areas))
