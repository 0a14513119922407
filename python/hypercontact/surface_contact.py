"""Contact between deformable bodies: a slave surface against the facets of
a master surface (SPEC §1: node-to-surface, closest-point projection,
normal penalty).

Data layout. The two surfaces, small next to the volume, are *shared across
ranks*: every rank holds the reference coordinates, global dof numbers and,
at each residual evaluation, the current displacement of every node of both
surfaces (the "contact nodes", ordered by global node index). Each slave
point is evaluated once, on the rank that owns it (its slave node, or for
Gauss-point integration its slave facet), and adds its rows and columns with
global indices into the PETSc vector and matrix; rows owned by another rank
travel with PETSc's assembly.

Slave points. Nodal integration (the paper): one point per slave node with
the node's area A_i = ∫ N_i dA. Gauss-point integration: the 2 × 2 Gauss
points of every slave facet, each a combination Σ M_i x_i of the facet's four
nodes with weight det J × w_q.

Search. The broad phase (C++ ``find_candidates``) lists for every slave point
the master facets whose box, inflated by the capture distance, contains it;
the narrow phase (C++) projects the point onto each candidate and keeps the
closest. The candidates are found at the start of a load step and fix the
matrix pattern (slave point × candidate facet nodes); after the step has
converged they are searched again, and if a point has a candidate that was
not in the pattern the pattern is rebuilt and the step solved again from
where it is (:meth:`SurfaceContact.refresh_pairing`).
"""
import numpy as np
from mpi4py import MPI

from . import _cpp
from . import _dolfinx as dfx
from . import penalty
from .contact import UzawaMultipliers, nodal_areas

GAUSS_2X2 = np.array([-1.0, 1.0]) / np.sqrt(3.0)


def _vertex_to_node(V):
    """Process-local mesh vertex → process-local node of the P1 space V."""
    mesh = V.mesh
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim, 0)
    c2v = mesh.topology.connectivity(tdim, 0)
    num_cells = mesh.topology.index_map(tdim).size_local + mesh.topology.index_map(tdim).num_ghosts
    cells_v = c2v.array.reshape(num_cells, -1)
    cells_d = V.dofmap.list.array.reshape(num_cells, -1)
    out = np.full(mesh.topology.index_map(0).size_local + mesh.topology.index_map(0).num_ghosts, -1, np.int32)
    out[cells_v.ravel()] = cells_d.ravel()
    return out


def surface_facets(V, facet_tags, tag, owned_only=True):
    """The tagged boundary quadrilaterals of this rank as (f, 4) process-local
    node indices, counter-clockwise seen from outside the body (so that
    (x1 − x0) × (x3 − x0) points out of the body)."""
    mesh = V.mesh
    tdim = mesh.topology.dim
    facets = dfx.facets_with_tag(facet_tags, tag)
    mesh.topology.create_connectivity(tdim - 1, 0)
    mesh.topology.create_connectivity(tdim - 1, tdim)
    f2v = mesh.topology.connectivity(tdim - 1, 0)
    f2c = mesh.topology.connectivity(tdim - 1, tdim)
    v2n = _vertex_to_node(V)
    X = dfx.node_coordinates(V)
    num_owned_cells = mesh.topology.index_map(tdim).size_local
    mesh.topology.create_connectivity(tdim, 0)
    c2v = mesh.topology.connectivity(tdim, 0)
    out = []
    for f in facets:
        cells = f2c.links(f)
        if owned_only and cells[0] >= num_owned_cells:
            continue
        quad = v2n[f2v.links(f)][[0, 1, 3, 2]]  # dolfinx tensor-product order → cyclic
        centre = X[v2n[c2v.links(cells[0])]].mean(axis=0)
        x = X[quad]
        normal = np.cross(x[1] - x[0], x[3] - x[0])
        if np.dot(normal, x.mean(axis=0) - centre) < 0:
            quad = quad[::-1]
        out.append(quad)
    return np.array(out, dtype=np.int32).reshape(-1, 4)


def edge_neighbours(facets):
    """(f, 4): the facet across edge k (node k → k+1) of each facet, −1 if
    the edge is on the boundary of the surface."""
    f = len(facets)
    a = facets
    b = np.roll(facets, -1, axis=1)
    lo, hi = np.minimum(a, b).ravel().astype(np.int64), np.maximum(a, b).ravel().astype(np.int64)
    key = lo * (int(facets.max()) + 1) + hi
    order = np.argsort(key, kind="stable")
    sk = key[order]
    out = np.full(4 * f, -1, np.int32)
    same = np.flatnonzero(sk[1:] == sk[:-1])
    for i in same:  # an edge shared by two facets (a manifold surface)
        e1, e2 = order[i], order[i + 1]
        out[e1], out[e2] = e2 // 4, e1 // 4
    return out.reshape(f, 4)


class SurfaceContact(UzawaMultipliers):
    """One slave surface against one master surface of the same mesh
    (possibly of another body), frictionless normal penalty."""

    #: the contact adds off-process rows: Problem assembles it with global indices
    global_assembly = True

    def __init__(self, spec, V, facet_tags, slave_tags, master_tags, constrained, name=None):
        self.spec = spec
        self.name = name or spec["name"]
        self.eps_n = float(spec["eps_n"])
        self.integration = spec["integration"]
        self.comm = comm = V.mesh.comm
        self.V = V
        gidx = dfx.global_node_indices(V).astype(np.int64)
        n_owned = dfx.num_owned_nodes(V)
        X_local = dfx.node_coordinates(V)

        slave_quads = np.concatenate([surface_facets(V, facet_tags, t) for t in slave_tags])
        master_quads = np.concatenate([surface_facets(V, facet_tags, t) for t in master_tags])
        # The contact nodes: every node of either surface, known on all ranks.
        local_ids = np.unique(np.concatenate([gidx[slave_quads.ravel()], gidx[master_quads.ravel()]]))
        all_ids = np.unique(np.concatenate(comm.allgather(local_ids))) if comm.size > 1 else local_ids
        self.num_nodes = len(all_ids)
        owned_mask = np.isin(gidx[:n_owned], all_ids)
        self.owned_local = np.flatnonzero(owned_mask).astype(np.int32)  # my owned contact nodes
        owned_ids = gidx[self.owned_local]
        cflag = constrained.reshape(-1, 3)[self.owned_local]
        data = comm.allgather((owned_ids, X_local[self.owned_local], cflag))
        ids = np.concatenate([d[0] for d in data])
        order = np.argsort(ids)
        assert np.array_equal(ids[order], all_ids), "every contact node must have one owner"
        self._gather_order = order
        self.X = np.ascontiguousarray(np.concatenate([d[1] for d in data])[order])
        flags = np.concatenate([d[2] for d in data])[order]
        dofs = 3 * all_ids[:, None] + np.arange(3)
        dofs[flags] = -1  # constrained: skipped, Dirichlet rows stay exact
        self.dofs = np.ascontiguousarray(dofs.astype(np.int32))
        self.global_ids = all_ids

        def to_contact(local_nodes):
            return np.searchsorted(all_ids, gidx[local_nodes]).astype(np.int32)

        # Master facets: gathered from all ranks (each boundary facet is on one rank).
        mq = to_contact(master_quads.ravel()).reshape(-1, 4)
        self.facets = np.ascontiguousarray(np.concatenate(comm.allgather(mq))) if comm.size > 1 else mq
        if len(self.facets) == 0:
            raise ValueError(f"contact {self.name!r}: the master surface has no facets")
        self.edge_neighbour = edge_neighbours(self.facets)
        # Slave points of this rank.
        if self.integration == "nodal":
            area = sum(nodal_areas(V, facet_tags, t) for t in slave_tags)
            nodes = np.flatnonzero(area > 0.0)
            self.point_nodes = np.full((len(nodes), 4), -1, np.int32)
            self.point_nodes[:, 0] = to_contact(nodes)
            self.point_weights = np.zeros((len(nodes), 4))
            self.point_weights[:, 0] = 1.0
            self.point_area = area[nodes].copy()
            self.slave_local_nodes = nodes.astype(np.int32)
            self.nodes = self.slave_local_nodes  # the slave points are these nodes (results fields)
        else:
            sq = to_contact(slave_quads.ravel()).reshape(-1, 4)
            Xs = self.X[sq]  # (f, 4, 3)
            pts, wts, areas = [], [], []
            for s in GAUSS_2X2:
                for t in GAUSS_2X2:
                    M = 0.25 * np.array([(1 - s) * (1 - t), (1 + s) * (1 - t), (1 + s) * (1 + t), (1 - s) * (1 + t)])
                    dMs = 0.25 * np.array([-(1 - t), (1 - t), (1 + t), -(1 + t)])
                    dMt = 0.25 * np.array([-(1 - s), -(1 + s), (1 + s), (1 - s)])
                    a1 = np.einsum("a,fak->fk", dMs, Xs)
                    a2 = np.einsum("a,fak->fk", dMt, Xs)
                    pts.append(sq)
                    wts.append(np.broadcast_to(M, (len(sq), 4)))
                    areas.append(np.linalg.norm(np.cross(a1, a2), axis=1))
            self.point_nodes = np.ascontiguousarray(np.concatenate(pts).astype(np.int32)).reshape(-1, 4)
            self.point_weights = np.ascontiguousarray(np.concatenate(wts)).reshape(-1, 4)
            self.point_area = np.concatenate(areas)
            self.slave_local_nodes = self.nodes = None
        self.total_area = comm.allreduce(float(self.point_area.sum()), op=MPI.SUM)
        self.num_points = comm.allreduce(len(self.point_area), op=MPI.SUM)
        size = np.linalg.norm(self.X[self.facets[:, 2]] - self.X[self.facets[:, 0]], axis=1).max()
        self.capture = float(spec["capture"]) if spec["capture"] > 0 else 1.0 * size
        self.candidates = None  # (offsets, indices) of the current pattern
        self.state = None
        self.repairings = 0
        # Augmented Lagrangian: one pressure λ_N per slave point of this rank, held fixed in a
        # Newton solve and updated between solves (Uzawa); committed with the step, restored on a
        # cut-back. It belongs to the slave point: a new facet or a rebuilt pairing keeps it.
        self.smoothing = penalty.smoothing_band(spec, V, facet_tags, slave_tags)
        self.augmented = spec.get("enforcement", "penalty") == "augmented_lagrangian"
        self.multipliers = np.zeros(len(self.point_area)) if self.augmented else np.zeros(0)
        self.multipliers_committed = self.multipliers.copy()
        if self.augmented and not spec.get("gap_tolerance", 0.0) > 0:
            # automatic, as for rigid obstacles: 1e-3 of the first element layer's thickness
            spec["gap_tolerance"] = 1e-3 * min(penalty.layer_thickness(V, facet_tags, t) for t in slave_tags)

    def set_load_factor(self, load_factor):
        """The master moves with the solution: nothing depends on λ here."""
        self.load_factor = load_factor

    # --- coordinates ---------------------------------------------------------
    def current_coordinates(self, u):
        """Current coordinates of all contact nodes (every rank)."""
        mine = np.ascontiguousarray(u.x.array.reshape(-1, 3)[self.owned_local])
        parts = self.comm.allgather(mine) if self.comm.size > 1 else [mine]
        return np.ascontiguousarray(self.X + np.concatenate(parts)[self._gather_order])

    def slave_points(self, x):
        """Current positions of this rank's slave points."""
        nodes = np.where(self.point_nodes >= 0, self.point_nodes, 0)
        return np.ascontiguousarray(np.einsum("pa,pak->pk", self.point_weights, x[nodes]))

    # --- pairing and pattern -------------------------------------------------
    def search(self, x):
        """Broad phase at coordinates x: (offsets, indices) of candidate facets."""
        return _cpp.find_candidates(self.slave_points(x), x, self.facets, self.capture)

    def set_pairing(self, u):
        """Search at u and make the result the pairing (and the pattern)."""
        self.candidates = self.search(self.current_coordinates(u))

    def point_node_pairs(self):
        """(point, contact node) pairs: each point's slave nodes and its
        candidate facets' nodes (subclasses add more)."""
        offsets, cand = self.candidates
        n_points = len(self.point_area)
        own = np.repeat(np.arange(n_points), 4), self.point_nodes.ravel()
        per_candidate = np.repeat(np.arange(n_points), np.diff(offsets))
        facet_nodes = np.repeat(per_candidate, 4), self.facets[cand].ravel()
        return np.concatenate([own[0], facet_nodes[0]]), np.concatenate([own[1], facet_nodes[1]])

    def couplings(self):
        """Global dof pairs (rows, cols) this rank's points add to the matrix:
        every dof of a point's nodes (point_node_pairs) with every other;
        constrained dofs left out. Vectorised: a self-join per point."""
        points, nodes = self.point_node_pairs()
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

    def refresh_pairing(self, u):
        """After a converged step: search again; True (and the union of the
        old and new candidates kept, so that a point on the border of two
        facets keeps both) if some point has a candidate outside the pattern."""
        n_points, n_facets = len(self.point_area), len(self.facets)

        def keys(csr):
            offsets, idx = csr
            return np.repeat(np.arange(n_points, dtype=np.int64), np.diff(offsets)) * n_facets + idx

        old, new = keys(self.candidates), keys(self.search(self.current_coordinates(u)))
        outside = int(np.count_nonzero(~np.isin(new, old)))
        changed = self.comm.allreduce(outside, op=MPI.SUM) > 0
        if changed:
            merged = np.union1d(old, new)
            counts = np.bincount(merged // n_facets, minlength=n_points)
            offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int32)
            self.candidates = (offsets, (merged % n_facets).astype(np.int32))
            self.repairings += 1
        return changed

    # --- assembly ---------------------------------------------------------
    def _args(self, u):
        offsets, cand = self.candidates
        return (self.current_coordinates(u), self.point_nodes, self.point_weights, self.point_area, self.facets,
                self.edge_neighbour, offsets, cand, self.eps_n, self.dofs)

    def add_residual_global(self, u, b):
        self.state = _cpp.assemble_surface_residual(*self._args(u), b, multipliers=self.multipliers,
            smoothing=self.smoothing)

    def add_tangent(self, u, A):
        _cpp.assemble_surface_tangent(*self._args(u), A, multipliers=self.multipliers,
            smoothing=self.smoothing)

    def evaluate(self, u):
        return _cpp.evaluate_surface_contact(*self._args(u), multipliers=self.multipliers,
            smoothing=self.smoothing)

    # --- augmented Lagrangian ------------------------------------------------
    def max_penetration(self, u):
        """Largest penetration ⟨−g⟩ over the paired slave points (all ranks)."""
        state = self.evaluate(u)
        gap = np.asarray(state.gap)[np.asarray(state.status) == 2]  # PairingStatus::Paired
        local = float(max(0.0, -gap.min())) if len(gap) else 0.0
        return self.comm.allreduce(local, op=MPI.MAX)

    def _active(self):
        """Points active at the last residual evaluation: g ≤ 0, or (augmented) p_N > 0."""
        if self.augmented:
            return np.flatnonzero(np.asarray(self.state.pressure) > 0.0)
        return np.flatnonzero(np.asarray(self.state.gap) <= 0.0)

    def active_set_signature(self):
        closed = self._active()
        facets = np.asarray(self.state.facet)[closed]
        local = (len(closed), int(closed.sum() + facets.sum()))
        return tuple(self.comm.allreduce(np.array(local, dtype=np.int64), op=MPI.SUM).tolist())

    def point_status(self):
        """Per slave point of this rank at the last residual evaluation: 0
        open, 2 active (closed; a frictionless point slides)."""
        status = np.zeros(len(self.point_area), np.int8)
        status[self._active()] = 2
        return status

    def point_coordinates(self, u):
        """(reference, current) coordinates of this rank's slave points. Collective."""
        return self.slave_points(self.X), self.slave_points(self.current_coordinates(u))

    def force(self, u):
        """Total force the master surface exerts on the slave body."""
        return self.comm.allreduce(np.asarray(self.evaluate(u).force), op=MPI.SUM)

    def num_closed(self, u):
        return self.comm.allreduce(int(self.evaluate(u).num_closed), op=MPI.SUM)

    def commit(self, u):
        """No history; the augmented Lagrangian's multipliers are kept as the next step's start."""
        self.multipliers_committed = self.multipliers.copy()
        return None
