"""The contact surfaces of a dolfinx mesh as plain arrays: slave nodes with
their areas, boundary facets (quadrilaterals, triangles) as node tuples, and
the facet across each facet edge. What the C++ kernels take; nothing here depends on λ or u."""
import numpy as np
import ufl

from .. import _dolfinx as dfx


def six_node_triangles(V):
    """Whether the boundary facets of V are 6-node triangles (quadratic tetrahedra)."""
    return dfx.degree_of(V) == 2 and dfx.facet_type(V.mesh) == "triangle"


def nodal_areas(V, facet_tags, tag):
    """The slave nodes' areas A_i on the tagged surface, owned nodes
    (parallel-safe: summed over ranks; ghosts are 0). Positive weights that
    sum to the area and integrate linear functions exactly:

    - A_i = ∫_Γ N_i dA where that is positive: linear triangles (A/3 per
      corner), bilinear and biquadratic (9-node) quadrilaterals (corner
      A/36, edge 4A/36, centre 16A/36 on a parallelogram);
    - 6-node triangles, whose corner integrals ∫ N_c dA vanish (a node-
      to-surface corner would carry no contact): the weights of the facet
      split into four 3-node triangles through its edge nodes, corner A/12,
      edge A/4 (docs/method.md §3.4)."""
    if six_node_triangles(V):
        return _split_triangle_areas(V, facet_tags, tag)
    v = ufl.TestFunction(V)
    ds = dfx.facet_integration_measure(V.mesh, facet_tags, quadrature_degree=2 * dfx.degree_of(V))
    L = dfx.compile_form(ufl.dot(v, ufl.as_vector((1.0, 0.0, 0.0))) * ds(tag))
    b = dfx.assemble_vector_owned(L)
    with b.localForm() as bl:
        area = bl.array_r[0::3].copy()
    b.destroy()
    area[dfx.num_owned_nodes(V):] = 0.0  # ghosts are counted on their owner
    return area


#: A degree-4 rule on the reference triangle (6 points; weights sum to ½).
_TRI6_POINTS = np.array([[0.445948490915965, 0.445948490915965], [0.445948490915965, 0.108103018168070],
                         [0.108103018168070, 0.445948490915965], [0.091576213509771, 0.091576213509771],
                         [0.091576213509771, 0.816847572980459], [0.816847572980459, 0.091576213509771]])
_TRI6_WEIGHTS = 0.5 * np.array([0.223381589678011] * 3 + [0.109951743655322] * 3)


def triangle6_derivatives(xi):
    """∂N_a/∂ξ_α (6 × 2) of the 6-node triangle: corners 0, 1, 2 at (0,0), (1,0), (0,1),
    edge node 3 + j the midpoint of corner j → j + 1."""
    s, t = xi
    r = 1.0 - s - t
    return np.array([[1 - 4 * r, 1 - 4 * r], [4 * s - 1, 0.0], [0.0, 4 * t - 1],
                     [4 * (r - s), -4 * s], [4 * t, 4 * s], [-4 * t, 4 * (r - t)]])


def triangle6_areas(nodes, X):
    """Area of each 6-node triangle (f, 6) with node coordinates X (curved edges included)."""
    Xs = X[nodes]
    area = np.zeros(len(nodes))
    for xi, w in zip(_TRI6_POINTS, _TRI6_WEIGHTS):
        d = triangle6_derivatives(xi)
        a1, a2 = np.einsum("a,fak->fk", d[:, 0], Xs), np.einsum("a,fak->fk", d[:, 1], Xs)
        area += w * np.linalg.norm(np.cross(a1, a2), axis=1)
    return area


def _split_triangle_areas(V, facet_tags, tag):
    nodes = surface_facet_nodes(V, facet_tags, tag)
    A = triangle6_areas(nodes, dfx.node_coordinates(V))
    local = np.zeros(dfx.num_local_nodes(V))
    np.add.at(local, nodes[:, :3].ravel(), np.repeat(A / 12.0, 3))
    np.add.at(local, nodes[:, 3:].ravel(), np.repeat(A / 4.0, 3))
    return dfx.owned_node_sums(V, local)


def surface_facets(V, facet_tags, tag, owned_only=True):
    """The tagged boundary facets of this rank — quadrilaterals (f, 4) or
    triangles (f, 3) — as process-local node indices of their vertices,
    counter-clockwise seen from outside the body (so that
    (x1 − x0) × (x_{k−1} − x0) points out of the body)."""
    facets = dfx.facets_with_tag(facet_tags, tag)
    vertices, cell = dfx.facet_vertex_nodes(V, facets)
    k = vertices.shape[1] if len(facets) else (3 if dfx.facet_type(V.mesh) == "triangle" else 4)
    centres = dfx.cell_node_centres(V, cell)
    X = dfx.node_coordinates(V)
    keep = np.ones(len(facets), bool) if not owned_only else cell < dfx.num_owned_cells(V.mesh)
    cyclic = [0, 1, 3, 2] if k == 4 else [0, 1, 2]  # tensor-product → cyclic
    out = []
    for nodes, centre in zip(vertices[keep][:, cyclic], centres[keep]):
        x = X[nodes]
        if np.dot(np.cross(x[1] - x[0], x[-1] - x[0]), x.mean(axis=0) - centre) < 0:
            nodes = nodes[::-1]
        out.append(nodes)
    return np.array(out, dtype=np.int32).reshape(-1, k)


def surface_facet_nodes(V, facet_tags, tag, owned_only=True):
    """All nodes of the tagged facets of a degree-2 space: the vertices as
    :func:`surface_facets` orders them, then edge node j (between vertex j and
    j + 1), then a quadrilateral's centre node — (f, 6) or (f, 9)."""
    corners = surface_facets(V, facet_tags, tag, owned_only)
    facets = dfx.facets_with_tag(facet_tags, tag)
    _, cells = dfx.facet_vertex_nodes(V, facets)
    if owned_only:
        facets = facets[cells < dfx.num_owned_cells(V.mesh)]
    edges, faces = dfx.facet_higher_nodes(V, facets, corners)
    parts = [corners, edges] + ([faces[:, None]] if corners.shape[1] == 4 else [])
    return np.ascontiguousarray(np.hstack(parts), dtype=np.int32)


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


# --- Gauss points of slave facets of any kind ---------------------------------------------------
#: The reference vertices of a quadrilateral, counter-clockwise.
_QUAD_CORNERS = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])
#: The 9-node quadrilateral: corners, edge j's midpoint (between corner j and j + 1), centre.
_QUAD9_NODES = np.vstack([_QUAD_CORNERS, 0.5 * (_QUAD_CORNERS + np.roll(_QUAD_CORNERS, -1, axis=0)), [[0.0, 0.0]]])


def _lagrange3(t):
    """(values, derivatives) of the 1D quadratic Lagrange functions at −1, 0, 1."""
    return (np.array([0.5 * t * (t - 1), 1 - t * t, 0.5 * t * (t + 1)]), np.array([t - 0.5, -2 * t, t + 0.5]))


def facet_shape(k, xi):
    """(N (k,), ∂N/∂ξ (k, 2)) of a slave facet of k nodes — 4 (bilinear) or 9
    (biquadratic) quadrilateral on [−1, 1]², 3 (linear) or 6 (quadratic)
    triangle on the unit triangle — in the node order of :func:`surface_facets`
    and :func:`surface_facet_nodes`."""
    s, t = xi
    if k == 4:
        c = _QUAD_CORNERS
        N = 0.25 * (1 + c[:, 0] * s) * (1 + c[:, 1] * t)
        dN = 0.25 * np.stack([c[:, 0] * (1 + c[:, 1] * t), c[:, 1] * (1 + c[:, 0] * s)], axis=1)
        return N, dN
    if k == 9:
        (ls, dls), (lt, dlt) = _lagrange3(s), _lagrange3(t)
        i, j = (_QUAD9_NODES[:, 0] + 1).astype(int), (_QUAD9_NODES[:, 1] + 1).astype(int)
        return ls[i] * lt[j], np.stack([dls[i] * lt[j], ls[i] * dlt[j]], axis=1)
    if k == 3:
        return np.array([1 - s - t, s, t]), np.array([[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]])
    if k == 6:
        r = 1.0 - s - t
        N = np.array([r * (2 * r - 1), s * (2 * s - 1), t * (2 * t - 1), 4 * r * s, 4 * s * t, 4 * t * r])
        return N, triangle6_derivatives(xi)
    raise ValueError(f"a slave facet has 3, 4, 6 or 9 nodes, not {k}")


def facet_rule(k):
    """(points (q, 2), weights (q,)) exact for the mass matrix of the facet of k nodes on a
    parallelogram / flat triangle: 2 × 2 and 3 × 3 Gauss on quadrilaterals, 3 and 6 points
    (degrees 2 and 4, positive weights) on triangles."""
    if k in (4, 9):
        g, w = np.polynomial.legendre.leggauss(2 if k == 4 else 3)
        return np.array([[a, b] for a in g for b in g]), np.array([wa * wb for wa in w for wb in w])
    if k == 3:
        return np.array([[1 / 6, 1 / 6], [2 / 3, 1 / 6], [1 / 6, 2 / 3]]), np.full(3, 1 / 6)
    if k == 6:
        return _TRI6_POINTS, _TRI6_WEIGHTS
    raise ValueError(f"a slave facet has 3, 4, 6 or 9 nodes, not {k}")


def facet_gauss_points(facets, X):
    """The Gauss points of slave facets (f, k) with node coordinates X: (nodes
    (f q, k), weights M_a (f q, k), det J × w (f q,)), facet by facet."""
    f, k = facets.shape
    points, w = facet_rule(k)
    Xs = X[facets]
    M = np.empty((f, len(w), k))
    area = np.empty((f, len(w)))
    for q, (xi, wq) in enumerate(zip(points, w)):
        N, dN = facet_shape(k, xi)
        a1, a2 = np.einsum("a,fak->fk", dN[:, 0], Xs), np.einsum("a,fak->fk", dN[:, 1], Xs)
        M[:, q] = N
        area[:, q] = wq * np.linalg.norm(np.cross(a1, a2), axis=1)
    nodes = np.repeat(facets, len(w), axis=0)
    return (np.ascontiguousarray(nodes, dtype=np.int32), np.ascontiguousarray(M.reshape(-1, k)),
            area.ravel())
