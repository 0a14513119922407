"""Every dolfinx-version-specific call of hypercontact (dolfinx 0.5.2).

A move to a newer FEniCSx should touch this file only.
"""
import functools
import logging
import time

import numpy as np
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.cpp.mesh
import dolfinx.fem.petsc as fem_petsc
import dolfinx.graph
import dolfinx.io
import dolfinx.mesh
import dolfinx.jit
import ufl
from dolfinx import fem
from dolfinx.io import gmshio


class _CompilerLog(logging.Filter):
    """FFCx's JIT builds a form, element or expression that is not in the
    cache (~/.cache/fenics, or $XDG_CACHE_HOME/fenics) with cffi and
    setuptools, which log every step and compiler command at INFO on the
    root logger, and FFCx's import gave the root logger a console handler
    (logging.basicConfig). On the root logger this filter drops those
    records (warnings pass) and, at the first one naming an FFCx module
    (libffcx_*) within a JIT call, tells the listener that a compilation
    is under way."""

    TOOLS = ("distutils", "setuptools", "cffi")

    def __init__(self):
        super().__init__()
        self.listener, self.seen = None, False

    def filter(self, record):
        if record.levelno >= logging.WARNING or not any(t in record.pathname for t in self.TOOLS):
            return True
        if not self.seen and "libffcx_" in record.getMessage():
            self.seen = True
            if self.listener is not None:
                self.listener.compiling()
        return False


_compiler_log = _CompilerLog()
logging.getLogger().addFilter(_compiler_log)


def _timed_jit(jit):
    @functools.wraps(jit)
    def timed(*args, **kwargs):
        _compiler_log.seen, start = False, time.perf_counter()
        try:
            return jit(*args, **kwargs)
        finally:
            if _compiler_log.seen and _compiler_log.listener is not None:
                _compiler_log.listener.compiled(time.perf_counter() - start)

    return timed


dolfinx.jit.ffcx_jit = _timed_jit(dolfinx.jit.ffcx_jit)


def watch_jit_compilation(listener):
    """Tell ``listener.compiling()`` when FFCx's JIT starts the C compiler
    and ``listener.compiled(seconds)`` when that JIT call returns (None:
    tell no one). The compiler's log never reaches the console."""
    _compiler_log.listener = listener


def partitioner():
    """The cell partitioner of every mesh: SCOTCH seeded afresh on each call,
    run with one thread (SCOTCH_PTHREAD_NUMBER, hypercontact/__init__.py).
    With dolfinx's default the same mesh built twice in one process was
    sometimes split differently, and a checkpoint (one file per rank) then
    did not fit the mesh it was resumed on (tests/behaviour/test_partition.py)."""
    return dolfinx.mesh.create_cell_partitioner(dolfinx.graph.partitioner_scotch(0.025, 0))


def _create_mesh(comm, cells, x, domain):
    return _gmshio_create_mesh(comm, cells, x, domain, partitioner=partitioner())


_gmshio_create_mesh = gmshio.create_mesh


def mesh_from_gmsh(model, comm):
    """Distribute the gmsh model living on rank 0; return (mesh, cell_tags,
    facet_tags), the cells tagged by their physical volume (only cells of
    physical volumes become cells). The cells are partitioned by
    :func:`partitioner` (gmshio.model_to_mesh takes no partitioner: its
    create_mesh is swapped for the call)."""
    gmshio.create_mesh = _create_mesh
    try:
        return gmshio.model_to_mesh(model, comm, 0, gdim=3)
    finally:
        gmshio.create_mesh = _gmshio_create_mesh


def vector_space(mesh, degree):
    return fem.VectorFunctionSpace(mesh, ("Lagrange", int(degree)))


def taylor_hood_space(mesh):
    """(Q2)³ × Q1: displacement and pressure, a stable pair."""
    cell = mesh.ufl_cell()
    element = ufl.MixedElement([ufl.VectorElement("Lagrange", cell, 2), ufl.FiniteElement("Lagrange", cell, 1)])
    return fem.FunctionSpace(mesh, element)


def collapse(subspace):
    """(collapsed space, its local unrolled dofs' indices in the parent)."""
    space, parent_dofs = subspace.collapse()
    return space, np.asarray(parent_dofs, dtype=np.int32)




#: C compiler flags of the generated forms (FFCx → cffi). -fno-math-errno lets the compiler treat
#: pow() as a pure function: the Mooney tangent's kernel calls pow(J, -2/3) and its kin 196 times per
#: quadrature point with 4 distinct arguments, and without it each call is made (the C standard's
#: errno side effect). Measured on the 32 × 32 × 8 punch's hexahedra: the tangent 41 → 24 µs per cell
#: and the residual 4.0 → 1.4 µs with -O3, the assembled matrix and vector bit for bit the same
#: (docs/performance.md §3). No -march=native: the code would differ between processors (FMA
#: contraction changes the rounding), and a JIT cache shared between machines could hold
#: instructions one of them lacks.
FORM_COMPILE_ARGS = ["-O3", "-g0", "-fno-math-errno"]


def compile_form(form):
    return fem.form(form, jit_params={"cffi_extra_compile_args": FORM_COMPILE_ARGS})


def create_matrix(a):
    return fem_petsc.create_matrix(a)


def create_vector(L):
    return fem_petsc.create_vector(L)


def facets_with_tag(facet_tags, tag):
    return facet_tags.indices[facet_tags.values == tag]




def vertex_to_node(V):
    """Process-local mesh vertex → process-local node of the Lagrange space V (any degree)."""
    mesh = V.mesh
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim, 0)
    c2v = mesh.topology.connectivity(tdim, 0)
    num_cells = mesh.topology.index_map(tdim).size_local + mesh.topology.index_map(tdim).num_ghosts
    layout = V.dofmap.dof_layout
    per_cell = c2v.array.reshape(num_cells, -1).shape[1]
    vertex_dofs = [layout.entity_dofs(0, i)[0] for i in range(per_cell)]
    out = np.full(mesh.topology.index_map(0).size_local + mesh.topology.index_map(0).num_ghosts, -1, np.int32)
    cell_nodes = V.dofmap.list.array.reshape(num_cells, -1)[:, vertex_dofs]
    out[c2v.array.reshape(num_cells, -1).ravel()] = cell_nodes.ravel()
    return out


def facet_vertex_nodes(V, facets):
    """(nodes of each facet's vertices in dolfinx order (f, k), the first cell of each facet (f,))
    for process-local facets of the Lagrange space V."""
    mesh = V.mesh
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim - 1, 0)
    mesh.topology.create_connectivity(tdim - 1, tdim)
    f2v = mesh.topology.connectivity(tdim - 1, 0)
    v2n = vertex_to_node(V)
    per_facet = len(f2v.links(0)) if f2v.num_nodes > 0 else 0
    nodes = np.array([v2n[f2v.links(f)] for f in facets], dtype=np.int32).reshape(len(facets), per_facet)
    return nodes, facet_cells(mesh, facets)


def facet_higher_nodes(V, facets, corners):
    """The nodes of a degree-2 space V on process-local facets beyond their
    vertices: (edge nodes (f, k), edge j the one between corners[:, j] and
    corners[:, (j + 1) % k] (vertex nodes, in a cyclic order), face nodes (f,),
    −1 where the facet has none: a triangle)."""
    mesh = V.mesh
    tdim = mesh.topology.dim
    for a, b in ((tdim, 1), (tdim, tdim - 1), (tdim - 1, 1), (1, 0), (tdim - 1, tdim)):
        mesh.topology.create_connectivity(a, b)
    c2e, c2f = mesh.topology.connectivity(tdim, 1), mesh.topology.connectivity(tdim, tdim - 1)
    f2e, e2v = mesh.topology.connectivity(tdim - 1, 1), mesh.topology.connectivity(1, 0)
    layout, v2n = V.dofmap.dof_layout, vertex_to_node(V)
    cells = facet_cells(mesh, facets)
    f, k = corners.shape
    edges, faces = np.full((f, k), -1, np.int32), np.full(f, -1, np.int32)
    for i, (facet, cell) in enumerate(zip(facets, cells)):
        dofs = V.dofmap.cell_dofs(cell)
        cell_edges = list(c2e.links(cell))
        by_vertices = {frozenset(v2n[e2v.links(e)]): e for e in f2e.links(facet)}
        for j in range(k):
            e = by_vertices[frozenset((corners[i, j], corners[i, (j + 1) % k]))]
            edges[i, j] = dofs[layout.entity_dofs(1, cell_edges.index(e))[0]]
        face_dofs = layout.entity_dofs(tdim - 1, list(c2f.links(cell)).index(facet))
        if len(face_dofs):
            faces[i] = dofs[face_dofs[0]]
    return edges, faces


def owned_node_sums(V, values):
    """Per process-local node of the vector space V: each node's owner gets
    the sum of every rank's values at it (ghosts' values moved to their owner),
    ghosts get 0."""
    f = fem.Function(V)
    with f.vector.localForm() as local:
        local.set(0.0)
        local.array[0::3] = values
    f.vector.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    with f.vector.localForm() as local:
        out = local.array_r[0::3].copy()
    out[num_owned_nodes(V):] = 0.0
    return out


def facet_type(mesh):
    """"triangle" or "quadrilateral": the boundary facets of a tetrahedral or hexahedral mesh."""
    return {"tetrahedron": "triangle", "hexahedron": "quadrilateral"}[mesh.topology.cell_type.name]


def element_description(V):
    """"27-node hexahedra", "4-node tetrahedra", …: the cells of the Lagrange space V."""
    cell = V.mesh.topology.cell_type.name
    return f"{V.dofmap.dof_layout.num_dofs}-node {'tetrahedra' if cell == 'tetrahedron' else 'hexahedra'}"


def degree_of(V):
    return V.ufl_element().degree()


def facet_cells(mesh, facets):
    """The first cell of each process-local facet."""
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim - 1, tdim)
    f2c = mesh.topology.connectivity(tdim - 1, tdim)
    return np.array([f2c.links(f)[0] for f in facets], dtype=np.int32)


def cell_node_centres(V, cells):
    """Mean reference coordinate of the vertex nodes of each process-local cell."""
    mesh = V.mesh
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim, 0)
    c2v = mesh.topology.connectivity(tdim, 0)
    v2n, X = vertex_to_node(V), node_coordinates(V)
    return np.array([X[v2n[c2v.links(c)]].mean(axis=0) for c in cells]).reshape(len(cells), 3)


def dirichlet_component(V, component, entities, value=None, dim=None):
    """Condition u_component = value (a Constant, or 0) on the mesh entities
    of dimension dim (default: facets)."""
    Vc = V.sub(component)
    dofs = fem.locate_dofs_topological(Vc, V.mesh.topology.dim - 1 if dim is None else dim, entities)
    return fem.dirichletbc(value if value is not None else PETSc.ScalarType(0), dofs, Vc)


def vertices_at(mesh, point, tol_factor=1e-8):
    """(process-local mesh vertices at ``point``, distance from ``point`` to
    the nearest vertex of any process): within tol_factor × the mesh's extent
    (no vertex: an empty array)."""
    x = mesh.geometry.x
    lo = [mesh.comm.allreduce(float(x[:, a].min()) if len(x) else np.inf, MPI.MIN) for a in range(3)]
    hi = [mesh.comm.allreduce(float(x[:, a].max()) if len(x) else -np.inf, MPI.MAX) for a in range(3)]
    tol = tol_factor * max(max(h - l for l, h in zip(lo, hi)), 1e-300)
    p = np.asarray(point, dtype=float).reshape(3, 1)
    vertices = dolfinx.mesh.locate_entities(mesh, 0, lambda y: np.linalg.norm(y - p, axis=0) <= tol)
    nearest = float(np.linalg.norm(x.T - p, axis=0).min()) if len(x) else np.inf
    return vertices, mesh.comm.allreduce(nearest, MPI.MIN)


def bc_dofs(bc):
    """Process-local unrolled dof indices constrained by a DirichletBC."""
    return bc.dof_indices()[0]


def num_global_dofs(V):
    im = V.dofmap.index_map
    return im.size_global * V.dofmap.index_map_bs


def num_owned_nodes(V):
    return V.dofmap.index_map.size_local


def num_local_nodes(V):
    im = V.dofmap.index_map
    return im.size_local + im.num_ghosts


def global_node_indices(V):
    """Global node (block) index of each process-local node."""
    im = V.dofmap.index_map
    return im.local_to_global(np.arange(im.size_local + im.num_ghosts, dtype=np.int32))


def global_dofs(space, local):
    """Global (PETSc) index of each of the process-local dofs ``local`` of ``space``."""
    im, bs = space.dofmap.index_map, space.dofmap.index_map_bs
    local = np.asarray(local, dtype=np.int64)
    return im.local_to_global((local // bs).astype(np.int32)).astype(np.int64) * bs + local % bs


def node_coordinates(V):
    """Reference coordinates of each process-local node, (n, 3)."""
    return V.tabulate_dof_coordinates()[:, :3]


def perturb_coordinates(mesh, amplitude):
    """Move every mesh node by a pseudo-random vector in [−a, a]³, a = amplitude × the
    smallest cell's smallest side; the vector depends on the node's input (gmsh) index only,
    so it is the same on any number of ranks and on every run."""
    x = mesh.geometry.x
    dofmap = mesh.geometry.dofmap
    local = np.inf
    if num_owned_cells(mesh):
        extent = np.ptp(x[dofmap.array.reshape(-1, len(dofmap.links(0)))], axis=1)
        local = float(np.where(extent > 0, extent, np.inf).min())
    a = amplitude * mesh.comm.allreduce(local, op=MPI.MIN)
    index = np.asarray(mesh.geometry.input_global_indices, dtype=np.float64)[:, None]
    phase = index * np.array([12.9898, 78.233, 37.719]) + np.array([0.5, 1.5, 2.5])
    unit = np.modf(np.abs(np.sin(phase)) * 43758.5453)[0]  # in [0, 1), a fixed function of the index
    x[:, :3] += a * (2.0 * unit - 1.0)


def facet_integration_measure(mesh, facet_tags, quadrature_degree=None, rule=None):
    md = {}
    if quadrature_degree is not None:
        md["quadrature_degree"] = int(quadrature_degree)
    if rule is not None:
        md["quadrature_rule"] = rule
    return ufl.Measure("ds", domain=mesh, subdomain_data=facet_tags, metadata=md)


def assemble_volume_residual(b, L):
    """b ← L(u) in b's local (owned + ghost) form, ghosts not yet summed.

    Contact terms are added to the local form next, then
    :func:`finish_residual` sums ghosts and applies the Dirichlet rows."""
    with b.localForm() as bl:
        bl.set(0.0)
    fem_petsc.assemble_vector(b, L)


def finish_residual(b, a, bcs, x):
    fem_petsc.apply_lifting(b, [a], bcs=[bcs], x0=[x], scale=-1.0)
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    fem_petsc.set_bc(b, bcs, x, -1.0)


def assemble_tangent(A, a, bcs):
    """A ← a(u) with the Dirichlet rows/columns replaced by the identity.
    Left un-finalised (flushed) so that contact terms can be added."""
    A.zeroEntries()
    fem_petsc.assemble_matrix(A, a, bcs=bcs)
    A.assemblyBegin(PETSc.Mat.AssemblyType.FLUSH)
    A.assemblyEnd(PETSc.Mat.AssemblyType.FLUSH)


def assemble_scalar(form, comm):
    return comm.allreduce(fem.assemble_scalar(form), op=MPI.SUM)


def assemble_vector_owned(L):
    """Assemble a linear form, sum ghost contributions; return the Vec."""
    b = fem_petsc.assemble_vector(L)
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    return b


def assemble_vector_into(b, L):
    """b += L, ghost contributions summed onto owners."""
    fem_petsc.assemble_vector(b, L)
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)


def zero_bc_rows(b, bcs):
    """b[dofs of bcs] = 0."""
    fem_petsc.set_bc(b, bcs, scale=0.0)


def constant(mesh, value):
    return fem.Constant(mesh, PETSc.ScalarType(value))


def update_ghosts(u):
    u.x.scatter_forward()




class XDMFWriter:
    """Time series of functions on one mesh, readable by ParaView."""

    def __init__(self, comm, path, mesh, append=False):
        self._file = dolfinx.io.XDMFFile(comm, str(path), "a" if append else "w")
        if not append:
            self._file.write_mesh(mesh)

    def write(self, functions, t):
        for f in functions:
            self._file.write_function(f, t)

    def close(self):
        self._file.close()


#: Linear cells by their number of vertices: (gmsh element type, dolfinx cell type, its facets' type
#: and number of vertices).
_LINEAR_CELLS = {8: (5, dolfinx.mesh.CellType.hexahedron, dolfinx.mesh.CellType.quadrilateral, 4),
                 4: (4, dolfinx.mesh.CellType.tetrahedron, dolfinx.mesh.CellType.triangle, 3)}


def mesh_from_arrays(comm, x, cells, cell_values, facets, facet_values):
    """A mesh of 8-node hexahedra (cells (c, 8), facets quadrilaterals (f, 4))
    or 4-node tetrahedra (cells (c, 4), facets triangles (f, 3)) from arrays on
    rank 0 (gmsh node order; other ranks pass empty arrays of the same widths):
    (mesh, cell_tags, facet_tags). What gmshio.model_to_mesh does, for meshes
    built as arrays (merged bodies, graded boxes)."""
    corners = np.shape(cells)[1]
    if corners not in _LINEAR_CELLS:
        raise ValueError(f"mesh_from_arrays: cells of 8 (hexahedra) or 4 (tetrahedra) nodes, found {corners}")
    gmsh_type, cell_type, facet_cell_type, per_facet = _LINEAR_CELLS[corners]
    ufl_domain = gmshio.ufl_mesh(gmsh_type, 3)
    cells = np.asarray(cells, dtype=np.int64).reshape(-1, corners)
    cells = cells[:, gmshio.cell_perm_array(cell_type, corners)]
    x = np.asarray(x, dtype=np.float64).reshape(-1, 3)
    mesh = _create_mesh(comm, cells, x, ufl_domain)
    tdim = mesh.topology.dim
    entities, values = dolfinx.cpp.io.distribute_entity_data(
        mesh._mesh, tdim, cells, np.asarray(cell_values, dtype=np.int32))
    mesh.topology.create_connectivity(tdim, 0)
    cell_tags = dolfinx.mesh.meshtags_from_entities(
        mesh, tdim, dolfinx.cpp.graph.AdjacencyList_int32(entities), values.astype(np.int32))
    facets = np.asarray(facets, dtype=np.int64).reshape(-1, per_facet)
    facets = facets[:, gmshio.cell_perm_array(facet_cell_type, per_facet)]
    entities, values = dolfinx.cpp.io.distribute_entity_data(
        mesh._mesh, tdim - 1, facets, np.asarray(facet_values, dtype=np.int32))
    mesh.topology.create_connectivity(tdim - 1, tdim)
    facet_tags = dolfinx.mesh.meshtags_from_entities(
        mesh, tdim - 1, dolfinx.cpp.graph.AdjacencyList_int32(entities), values.astype(np.int32))
    return mesh, cell_tags, facet_tags


def gmsh_arrays(model):
    """(x, hexes, hex physical tags, quads, quad physical tags) of a gmsh
    model with 8-node hexahedra; node indices from 0, gmsh node order."""
    x = gmshio.extract_geometry(model)
    topologies = gmshio.extract_topology_and_markers(model)
    hexes = topologies.get(5, {"topology": np.zeros((0, 8)), "cell_data": np.zeros(0)})
    quads = topologies.get(3, {"topology": np.zeros((0, 4)), "cell_data": np.zeros(0)})
    return (x, np.asarray(hexes["topology"], dtype=np.int64), np.asarray(hexes["cell_data"], dtype=np.int32),
            np.asarray(quads["topology"], dtype=np.int64), np.asarray(quads["cell_data"], dtype=np.int32))


def geometry_to_dofs(mesh, V):
    """Process-local dof (block) index of a first-order Lagrange space V at
    each process-local geometry node of a first-order mesh."""
    g = mesh.geometry.dofmap.array.reshape(-1, len(mesh.geometry.dofmap.links(0)))
    d = V.dofmap.list.array.reshape(-1, V.dofmap.dof_layout.num_dofs)
    if g.shape != d.shape:
        raise ValueError("deformed_shape: needs a first-order mesh geometry")
    out = np.full(mesh.geometry.x.shape[0], -1, dtype=np.int64)
    out[g.ravel()] = d.ravel()
    return out


def first_order(f, mesh, name):
    """f itself if it is first-order Lagrange, else its interpolant into the
    first-order Lagrange space of the same shape."""
    element = f.function_space.ufl_element()
    if element.degree() == 1 and element.family() in ("Q", "Lagrange", "P"):
        return f
    shape = f.ufl_shape
    if shape == ():
        space = fem.FunctionSpace(mesh, ("Lagrange", 1))
    elif len(shape) == 1:
        space = fem.VectorFunctionSpace(mesh, ("Lagrange", 1), dim=shape[0])
    else:
        raise ValueError(f"deformed_shape: {name} must be a scalar or vector field, has shape {shape}")
    g = fem.Function(space)
    g.interpolate(f)
    return g


def owned_exterior_facets(mesh):
    """(geometry nodes of this rank's owned exterior facets (f, k), the cell of each)."""
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim - 1, tdim)
    mesh.topology.create_connectivity(tdim - 1, 0)
    facets = dolfinx.mesh.exterior_facet_indices(mesh.topology)
    facets = facets[facets < mesh.topology.index_map(tdim - 1).size_local].astype(np.int32)
    nodes = dolfinx.cpp.mesh.entities_to_geometry(getattr(mesh, "_mesh", mesh), tdim - 1, facets, False)
    f2c = mesh.topology.connectivity(tdim - 1, tdim)
    cells = f2c.array[f2c.offsets[facets]] if len(facets) else facets  # an exterior facet has one cell
    return nodes, cells


def interior_facets_with_tag(mesh, facet_tags, tag):
    """How many facets with ``tag`` lie inside the mesh (between two cells), over all ranks: each facet
    counted once, by the rank that owns it."""
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim - 1, tdim)
    n_owned = mesh.topology.index_map(tdim - 1).size_local
    tagged = facets_with_tag(facet_tags, tag)
    tagged = tagged[tagged < n_owned]
    exterior = dolfinx.mesh.exterior_facet_indices(mesh.topology)
    return mesh.comm.allreduce(int(np.count_nonzero(~np.isin(tagged, exterior))), op=MPI.SUM)


def cell_dofs(S, cells):
    """The dof of each process-local cell in a one-dof-per-cell (DG0) space S."""
    return S.dofmap.list.array.reshape(-1, 1)[cells, 0] if len(cells) else cells


def num_owned_cells(mesh):
    return mesh.topology.index_map(mesh.topology.dim).size_local


def quadrature_points(mesh, degree):
    """Reference points of the default quadrature rule of degree ``degree``
    on the mesh's cells (the rule FFCx takes for ``quadrature_degree``)."""
    import basix

    cell = basix.cell.string_to_type(mesh.topology.cell_type.name)
    return basix.make_quadrature(cell, int(degree))[0]


def eval_on_owned_cells(expression, mesh):
    """Values of a compiled fem.Expression on this rank's owned cells:
    (owned cells, points × value size)."""
    return expression.eval(np.arange(num_owned_cells(mesh), dtype=np.int32))


def cell_description(mesh, cell):
    """(input index, reference midpoint) of a process-local cell: the index
    the cell had in the mesh as built or read, the same on any number of ranks."""
    tdim = mesh.topology.dim
    midpoint = dolfinx.mesh.compute_midpoints(mesh, tdim, np.array([cell], dtype=np.int32))[0]
    return int(mesh.topology.original_cell_index[cell]), midpoint
