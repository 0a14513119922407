"""A deformable master surface as contact geometry: slave points of one
surface against the facets of another surface of the same mesh (possibly of
another body), node-to-surface with closest-point projection.

Data layout. The two surfaces, small next to the volume, are *shared across
ranks*: every rank holds the reference coordinates, global dof numbers and,
at each evaluation, the current displacement of every node of both surfaces
(the "contact nodes", ordered by global node index). Each slave point is
evaluated once, on the rank that owns it (its slave node, or for Gauss-point
integration its slave facet), and adds its rows and columns with global
indices into the PETSc vector and matrix; rows owned by another rank travel
with PETSc's assembly.

Slave points. Nodal integration (the paper): one point per slave node with
the node's area (quadratic elements: the positive weights of
:func:`~.surface_mesh.nodal_areas`). Gauss-point integration: the Gauss
points of every slave facet (2 × 2 on bilinear, 3 × 3 on biquadratic
quadrilaterals, 3 and 6 on linear and quadratic triangles), each a
combination Σ M_i x_i of the facet's nodes with weight det J × w_q.

Master facets have all the nodes of the displacement's boundary facets:
3 or 4 with linear elements, 6 or 9 (curved) with quadratic ones. In the
mixed formulation the contact reads and assembles the displacement block of
the unknown (``u_dofs``, ``u_global``).

Pairing. The broad phase (C++ ``find_candidates``) lists for every slave
point the master facets whose box, inflated by the capture distance, contains
it; the narrow phase (C++) projects the point onto each candidate and keeps
the closest. The candidates are found at the start of a load step and fix the
matrix pattern (slave point × candidate facet nodes); after the step has
converged they are searched again, and if a point has a candidate that was
not in the pattern the pattern grows (:meth:`SurfacePairing.update_pairing`).
"""
import numpy as np
from mpi4py import MPI

from .. import _cpp
from .. import _dolfinx as dfx
from .surface_mesh import (edge_neighbours, facet_gauss_points, gauss_points, nodal_areas, surface_facet_nodes,
                           surface_facets)

#: C++ PairingStatus::Paired
PAIRED = 2


class SurfacePairing:
    """Slave points of the slave surfaces and the facets of the master surfaces."""

    #: adds rows anywhere, by global index: the matrix pattern follows the pairing
    assembly = "global"

    def __init__(self, V, facet_tags, slave_tags, master_tags, constrained, integration, capture, name,
                 u_dofs=None, u_global=None, smooth=False):
        """``constrained``: mask of the unknown's process-local dofs; ``u_dofs``,
        ``u_global``: the local and global indices in the unknown of V's local
        dofs (the mixed formulation), None if the unknown is the displacement."""
        self.comm = comm = V.mesh.comm
        gidx = dfx.global_node_indices(V).astype(np.int64)
        facets_of = surface_facet_nodes if dfx.degree_of(V) == 2 else surface_facets
        slave_quads = np.concatenate([facets_of(V, facet_tags, t) for t in slave_tags])
        master_quads = np.concatenate([facets_of(V, facet_tags, t) for t in master_tags])
        self._u_dofs = u_dofs
        self._num_v_dofs = 3 * dfx.num_local_nodes(V)
        v_constrained = constrained if u_dofs is None else constrained[u_dofs]
        self._share_contact_nodes(V, gidx, np.concatenate([slave_quads.ravel(), master_quads.ravel()]),
                                  v_constrained, u_global)

        def to_contact(local_nodes):
            return np.searchsorted(self.global_ids, gidx[local_nodes]).astype(np.int32)

        k = master_quads.shape[1]  # 4, 9: quadrilaterals (hexahedra), 3, 6: triangles (tetrahedra)
        mq = to_contact(master_quads.ravel()).reshape(-1, k)  # each boundary facet is on one rank
        self.facets = np.ascontiguousarray(np.concatenate(comm.allgather(mq))) if comm.size > 1 else mq
        if len(self.facets) == 0:
            raise ValueError(f"contact {name!r}: the master surface has no facets")
        corners = 3 if k in (3, 6) else 4
        self.edge_neighbour = np.ascontiguousarray(edge_neighbours(np.ascontiguousarray(self.facets[:, :corners])))
        if integration == "nodal":
            area = sum(nodal_areas(V, facet_tags, t) for t in slave_tags)
            nodes = np.flatnonzero(area > 0.0)
            self.point_nodes = np.full((len(nodes), 4), -1, np.int32)
            self.point_nodes[:, 0] = to_contact(nodes)
            self.point_weights = np.zeros((len(nodes), 4))
            self.point_weights[:, 0] = 1.0
            self.point_area = area[nodes].copy()
            self.nodes = nodes.astype(np.int32)
        else:
            sq = to_contact(slave_quads.ravel()).reshape(-1, slave_quads.shape[1])
            if sq.shape[1] == 4:
                self.point_nodes, self.point_weights, self.point_area = gauss_points(sq, self.X)
            elif sq.shape[1] == 3:  # the 3 Gauss points of each triangle, padded to 4 nodes (the 4th: none)
                nodes, weights, self.point_area = facet_gauss_points(sq, self.X)
                self.point_nodes = np.hstack([nodes, np.full((len(nodes), 1), -1, np.int32)])
                self.point_weights = np.hstack([weights, np.zeros((len(nodes), 1))])
            else:  # curved slave facets: 3 × 3 or 6 points, each over the facet's 9 or 6 nodes
                self.point_nodes, self.point_weights, self.point_area = facet_gauss_points(sq, self.X)
            self.nodes = None
        self.num_points = comm.allreduce(len(self.point_area), op=MPI.SUM)
        size = np.linalg.norm(self.X[self.facets[:, 2]] - self.X[self.facets[:, 0]], axis=1).max()
        self.capture = float(capture) if capture > 0 else 1.0 * size
        #: self-contact (the slave surface is its own master): per contact node, the facets it may not pair with
        self.excluded = self._self_contact_exclusion(corners) if set(slave_tags) & set(master_tags) else None
        self.candidates = None  # (offsets, indices) of the current pairing: the matrix pattern
        self.extra_nodes = None  # callable: further (point, contact node) couplings (friction history)
        #: smooth master (C++ smooth_master.hpp): per facet, the nodes its nodal normals depend on (CSR)
        self.smooth = bool(smooth)
        self.stencil = self._facet_stencils() if self.smooth else None
        self.repairings = 0
        self.load_factor = 0.0

    def _share_contact_nodes(self, V, gidx, local_nodes, constrained, u_global=None):
        """Every node of either surface, known on all ranks: global ids, reference coordinates
        and global dofs (−1 where constrained; in the unknown's numbering ``u_global`` if
        given, else 3 × node + component), ordered by global id."""
        comm, n_owned = self.comm, dfx.num_owned_nodes(V)
        local_ids = np.unique(gidx[local_nodes])
        all_ids = np.unique(np.concatenate(comm.allgather(local_ids))) if comm.size > 1 else local_ids
        self.num_nodes = len(all_ids)
        self.owned_local = np.flatnonzero(np.isin(gidx[:n_owned], all_ids)).astype(np.int32)
        unknown = None if u_global is None else u_global.reshape(-1, 3)[self.owned_local]
        data = comm.allgather((gidx[self.owned_local], dfx.node_coordinates(V)[self.owned_local],
                               constrained.reshape(-1, 3)[self.owned_local], unknown))
        ids = np.concatenate([d[0] for d in data])
        order = np.argsort(ids)
        assert np.array_equal(ids[order], all_ids), "every contact node must have one owner"
        self._gather_order = order
        self.X = np.ascontiguousarray(np.concatenate([d[1] for d in data])[order])
        if u_global is None:
            dofs = 3 * all_ids[:, None] + np.arange(3)
        else:
            dofs = np.concatenate([d[3] for d in data])[order].astype(np.int64)
        dofs[np.concatenate([d[2] for d in data])[order]] = -1  # constrained: Dirichlet rows stay exact
        self.dofs = np.ascontiguousarray(dofs.astype(np.int32))
        self.global_ids = all_ids

    def set_load_factor(self, load_factor):
        """The master moves with the solution: nothing depends on λ here."""
        self.load_factor = load_factor

    def displacement(self):
        return 0.0

    # --- coordinates -----------------------------------------------------------
    def coordinates(self, u):
        """Current coordinates of all contact nodes (every rank); u the
        displacement or (mixed formulation) the unknown it is part of. Collective."""
        values = u.x.array
        if values.size == self._num_v_dofs:
            mine = np.ascontiguousarray(values.reshape(-1, 3)[self.owned_local])
        else:
            mine = np.ascontiguousarray(values[self._u_dofs.reshape(-1, 3)[self.owned_local]])
        parts = self.comm.allgather(mine) if self.comm.size > 1 else [mine]
        return np.ascontiguousarray(self.X + np.concatenate(parts)[self._gather_order])

    def slave_points(self, x):
        """Positions of this rank's slave points at contact-node coordinates x."""
        nodes = np.where(self.point_nodes >= 0, self.point_nodes, 0)
        return np.ascontiguousarray(np.einsum("pa,pak->pk", self.point_weights, x[nodes]))

    def point_coordinates(self, u):
        """(reference, current) coordinates of this rank's slave points. Collective."""
        return self.slave_points(self.X), self.slave_points(self.coordinates(u))

    def field_nodes(self):
        """Process-local node of each slave point, or None (Gauss points have no node)."""
        return self.nodes

    def point_ids(self):
        """Global id of each slave point's (first) slave node."""
        return self.global_ids[self.point_nodes[:, 0]].astype(np.int64)

    # --- pairing and pattern ---------------------------------------------------
    def search(self, x):
        """Broad phase at contact-node coordinates x: (offsets, indices) of candidate facets
        (self-contact: without the excluded ones)."""
        offsets, idx = _cpp.find_candidates(self.slave_points(x), x, self.facets, self.capture)
        if self.excluded is None or len(idx) == 0:
            return offsets, idx
        ring, incidence, corners = self.excluded
        node_normal, facet_normal = self._normals(x, incidence, corners)
        point = np.repeat(np.arange(len(self.point_area)), np.diff(offsets))
        node = self.point_nodes[point, 0]
        keep = np.einsum("pk,pk->p", node_normal[node], facet_normal[idx]) < 0.0  # facing: few pairs
        facing = np.flatnonzero(keep)
        if len(facing):
            keep[facing] = np.asarray(ring[node[facing], np.asarray(idx, dtype=np.int64)[facing]]).ravel() == 0
        counts = np.bincount(point[keep], minlength=len(self.point_area))
        return np.concatenate([[0], np.cumsum(counts)]).astype(offsets.dtype), np.ascontiguousarray(idx[keep])

    def _normals(self, x, incidence, corners):
        """Unit facet normals and area-weighted nodal normals at coordinates x."""
        c = self.facets[:, :corners]
        if corners == 4:
            normal = np.cross(x[c[:, 2]] - x[c[:, 0]], x[c[:, 3]] - x[c[:, 1]])
        else:
            normal = np.cross(x[c[:, 1]] - x[c[:, 0]], x[c[:, 2]] - x[c[:, 0]])
        node_normal = incidence @ normal  # area-weighted sum over the node's facets
        node_normal /= np.maximum(np.linalg.norm(node_normal, axis=1, keepdims=True), 1e-300)
        facet_normal = normal / np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-300)
        return node_normal, facet_normal

    def _incidence(self):
        """The contact node × master facet incidence (sparse, 1 where the node is on the facet)."""
        from scipy import sparse

        rows = self.facets.ravel()
        cols = np.repeat(np.arange(len(self.facets)), self.facets.shape[1])
        return sparse.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(len(self.X), len(self.facets)))

    def _self_contact_exclusion(self, corners):
        """Self-contact: what excludes a (slave node, facet) pair from the search — the facets
        that touch the node's own facets (its facets and their neighbours, by a shared node: a
        sparse contact node × facet count), and, at each search, the facets that do not face the
        node in the configuration searched (facet normal · the node's normal ≥ 0: a slave point
        meets a facet of the same surface only where the surface has folded back onto itself, as
        the two inner walls of a flattened tube). The facing test is made on the current
        configuration, not the reference one: points of a tube's inner wall 60° apart face each
        other once the tube is flat, not before. Returns (ring, incidence, corners)."""
        incidence = self._incidence()
        ring = (incidence @ incidence.T) @ incidence  # node → facets sharing a node with its facets
        return ring.tocsr(), incidence, corners

    def _facet_stencils(self):
        """Smooth master: per facet, the nodes of every facet that shares a node with it (its
        nodal normals are made of them), as CSR (offsets, nodes)."""
        incidence = self._incidence()
        stencil = ((incidence.T @ incidence) @ incidence.T).tocsr()  # facet → nodes of its neighbours
        stencil.sort_indices()
        return stencil.indptr.astype(np.int64), stencil.indices.astype(np.int32)

    def update_pairing(self, u, fresh):
        """With ``fresh`` (a step starts): search at u and make it the pairing.
        Otherwise (after a converged solve): search again and add the facets
        outside the pairing to it (the union, so that a point on the border of
        two facets keeps both). Returns whether the pairing changed (all ranks)."""
        new = self.search(self.coordinates(u))
        if fresh:
            same = self.candidates is not None and all(np.array_equal(a, b) for a, b in zip(new, self.candidates))
            changed = not self.comm.allreduce(bool(same), op=MPI.LAND)
            if changed:
                self.candidates = new
            return changed
        n_points, n_facets = len(self.point_area), len(self.facets)

        def keys(csr):
            offsets, idx = csr
            return np.repeat(np.arange(n_points, dtype=np.int64), np.diff(offsets)) * n_facets + idx

        old, new = keys(self.candidates), keys(new)
        changed = self.comm.allreduce(int(np.count_nonzero(~np.isin(new, old))), op=MPI.SUM) > 0
        if changed:
            merged = np.union1d(old, new)
            counts = np.bincount(merged // n_facets, minlength=n_points)
            offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int32)
            self.candidates = (offsets, (merged % n_facets).astype(np.int32))
            self.repairings += 1
        return changed

    def point_node_pairs(self, extra=None):
        """(point, contact node) pairs: each point's slave nodes, its candidate
        facets' nodes, and ``extra`` pairs (the friction history's facets)."""
        offsets, cand = self.candidates
        n_points = len(self.point_area)
        per_candidate = np.repeat(np.arange(n_points), np.diff(offsets))
        points = [np.repeat(np.arange(n_points), self.point_nodes.shape[1])]
        nodes = [self.point_nodes.ravel()]
        if self.stencil is None:
            points.append(np.repeat(per_candidate, self.facets.shape[1]))
            nodes.append(self.facets[cand].ravel())
        else:  # smooth master: the candidates' stencils (their facets' nodes among them)
            offsets_s, stencil_nodes = self.stencil
            lengths = offsets_s[cand + 1] - offsets_s[cand]
            starts = np.repeat(offsets_s[cand] - np.cumsum(lengths) + lengths, lengths)
            points.append(np.repeat(per_candidate, lengths))
            nodes.append(stencil_nodes[starts + np.arange(lengths.sum())])
        if extra is not None:
            points.append(extra[0])
            nodes.append(extra[1])
        return np.concatenate(points), np.concatenate(nodes)

    def couplings(self, extra=None):
        """Global dof pairs (rows, cols) this rank's points add to the matrix:
        every dof of a point's nodes with every other; constrained dofs left
        out. Vectorised: a self-join per point."""
        points, nodes = self.point_node_pairs(extra)
        keep = nodes >= 0
        key = np.unique(points[keep].astype(np.int64) * self.num_nodes + nodes[keep])
        P, N = key // self.num_nodes, key % self.num_nodes
        counts = np.bincount(P, minlength=len(self.point_area))
        starts = np.cumsum(counts) - counts
        rep = counts[P]
        rows = np.repeat(N, rep)
        within = np.arange(rep.sum()) - np.repeat(np.cumsum(rep) - rep, rep)
        cols = N[np.repeat(starts[P], rep) + within]
        R = np.repeat(self.dofs[rows], 3, axis=1).ravel()
        C = np.tile(self.dofs[cols], (1, 3)).ravel()
        ok = (R >= 0) & (C >= 0)
        return R[ok].astype(np.int64), C[ok].astype(np.int64)

    # --- what an evaluation says ------------------------------------------------
    def active(self, state, augmented):
        """Points active in the evaluation: g ≤ 0, or (augmented) p_N > 0."""
        return np.flatnonzero(state.pressure > 0.0) if augmented else np.flatnonzero(state.gap <= 0.0)

    closed = active

    def max_penetration(self, state):
        """Largest penetration ⟨−g⟩ over the paired slave points (all ranks)."""
        gap = state.gap[state.status == PAIRED]
        local = float(max(0.0, -gap.min())) if len(gap) else 0.0
        return self.comm.allreduce(local, op=MPI.MAX)


class SurfaceFrictionHistory:
    """Per slave point, a *master material point* — the facet the point was
    paired with at the last converged step and ξ* there — and that step's
    tangential traction t. The kernel places the old point at the old facet's
    current nodes, so a master that moves or deforms under a sticking point
    creates no trial traction. Points off the master or without a candidate
    store none (facet −1: the kernel then takes the current point, t = 0)."""

    def __init__(self, geometry):
        n = len(geometry.point_area)
        self.geometry = geometry
        self.facet = np.full(n, -1, np.int32)
        self.xi = np.zeros((n, 2))
        self.traction = np.zeros((n, 3))

    def store(self, state, x=None):
        paired = state.status == PAIRED
        self.facet = np.ascontiguousarray(np.where(paired, state.facet, -1).astype(np.int32))
        self.xi = np.ascontiguousarray(np.where(paired[:, None], state.xi, 0.0))
        self.traction = np.ascontiguousarray(np.where(paired[:, None], state.traction, 0.0))

    def forget(self, x=None):
        """No master point and no traction carried over (facet −1: the kernel takes the current point, t = 0)."""
        self.facet = np.full_like(self.facet, -1)
        self.xi = np.zeros_like(self.xi)
        self.traction = np.zeros_like(self.traction)

    def rebase(self):
        pass

    def pattern_nodes(self):
        """(point, contact node) pairs of the old facets (the friction tangent has their columns)."""
        has = np.flatnonzero(self.facet >= 0)
        return np.repeat(has, self.geometry.facets.shape[1]), self.geometry.facets[self.facet[has]].ravel()

    def state_dict(self):
        return {}, {"facet": self.facet, "xi": self.xi, "traction": self.traction}

    def load_state_dict(self, meta, arrays):
        self.facet = np.ascontiguousarray(arrays["facet"], dtype=np.int32)
        self.xi = np.ascontiguousarray(arrays["xi"], dtype=float)
        self.traction = np.ascontiguousarray(arrays["traction"], dtype=float)
