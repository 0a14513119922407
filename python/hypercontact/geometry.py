"""Meshes with gmsh: built-in builders and mesh files.

Every mesh comes with named boundary surfaces (gmsh physical groups), which
scenes refer to by name (e.g. ``slave = "zmax"``, ``surface = "xmin"``).
"""
import difflib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from . import _dolfinx as dfx
from .scene import SceneError


@dataclass
class Body:
    """A meshed body: dolfinx mesh, facet tags, and surface name → tag."""

    mesh: object
    facet_tags: object
    surfaces: dict
    cell_tags: object = None  #: body (region) tag of each cell, for several bodies
    regions: dict = None  #: body name → cell tag, for several bodies


_gmsh_ready = False


def _gmsh():
    """gmsh, initialised once per process (gmsh 4.8 has no isInitialized)."""
    global _gmsh_ready
    import gmsh

    if not _gmsh_ready:
        gmsh.initialize(readConfigFiles=False)
        gmsh.option.setNumber("General.Terminal", 0)
        _gmsh_ready = True
    return gmsh


def _reset_gmsh():
    """Finalise gmsh after an error: a failed gmsh.open leaves state behind
    that makes later models mesh without volume elements."""
    global _gmsh_ready
    import gmsh

    gmsh.finalize()
    _gmsh_ready = False


def box_model(gmsh, size, n, m, origin=(0.0, 0.0, 0.0), cells="hexahedra"):
    """Structured box [origin, origin+size], n × n × m hexahedra, or (cells =
    "tetrahedra") the same grid with each hexahedron split into six
    tetrahedra (gmsh's transfinite volume without recombination).

    Physical surfaces xmin, xmax, ymin, ymax, zmin, zmax; volume "body".
    n elements along x and y, m along z (through the thickness).
    """
    gmsh.model.add("box")
    x0, y0, z0 = origin
    lx, ly, lz = size
    gmsh.model.occ.addBox(x0, y0, z0, lx, ly, lz)
    gmsh.model.occ.synchronize()
    counts = {0: n, 1: n, 2: m}
    for _, tag in gmsh.model.getEntities(1):
        b = gmsh.model.getBoundingBox(1, tag)
        axis = int(np.argmax([b[3] - b[0], b[4] - b[1], b[5] - b[2]]))
        gmsh.model.mesh.setTransfiniteCurve(tag, counts[axis] + 1)
    for _, tag in gmsh.model.getEntities(2):
        gmsh.model.mesh.setTransfiniteSurface(tag)
        if cells == "hexahedra":
            gmsh.model.mesh.setRecombine(2, tag)
    for _, tag in gmsh.model.getEntities(3):
        gmsh.model.mesh.setTransfiniteVolume(tag)
    lo = np.array(origin, dtype=float)
    tol = max(1e-5 * max(size), 1e-6)  # OCC bounding boxes are padded by ~1e-7 (absolute)
    names = {}
    for _, tag in gmsh.model.getEntities(2):
        b = np.array(gmsh.model.getBoundingBox(2, tag))
        for axis, a in enumerate("xyz"):
            if abs(b[axis] - b[axis + 3]) < tol:
                side = "min" if abs(b[axis] - lo[axis]) < tol else "max"
                names[f"{a}{side}"] = tag
    for i, (name, tag) in enumerate(sorted(names.items()), start=1):
        gmsh.model.addPhysicalGroup(2, [tag], i)
        gmsh.model.setPhysicalName(2, i, name)
    vol = gmsh.model.addPhysicalGroup(3, [e[1] for e in gmsh.model.getEntities(3)], 100)
    gmsh.model.setPhysicalName(3, vol, "body")
    gmsh.model.mesh.generate(3)


def _physical_surface_names(gmsh):
    return {gmsh.model.getPhysicalName(2, tag): tag for _, tag in gmsh.model.getPhysicalGroups(2)}


def build_box(comm, size, n, m, origin=(0.0, 0.0, 0.0), cells="hexahedra"):
    """A structured box body of hexahedra or tetrahedra (see :func:`box_model`)."""
    return _from_gmsh(comm, lambda g: box_model(g, size, n, m, origin, cells))


def read_msh(comm, path):
    """A body from a gmsh .msh file with named physical surfaces; its cells
    tagged by physical volume (regions: physical volume name → tag)."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"mesh file {str(path)!r} does not exist")

    def load(g):
        try:
            g.open(str(path))
        except Exception as err:  # gmsh raises a bare Exception
            raise ValueError(f"mesh file {str(path)!r} cannot be read by gmsh: {err}") from None
        if not g.model.getEntities(3):
            raise ValueError(f"mesh file {str(path)!r} has no volume (3D) elements")
        check_volume_elements(g, path)
        return physical_volumes(g, path)

    return _from_gmsh(comm, load)


#: gmsh's volume element types a mesh may have: 4- and 10-node tetrahedra, 8- and 27-node hexahedra.
VOLUME_ELEMENTS = {4: "4-node tetrahedra", 11: "10-node tetrahedra", 5: "8-node hexahedra", 12: "27-node hexahedra"}


def check_volume_elements(gmsh, path):
    """One kind and one order of volume element in the model (dolfinx builds one cell type):
    ValueError naming what the file has otherwise."""
    types = [int(t) for t in gmsh.model.mesh.getElementTypes(3)]
    names = [VOLUME_ELEMENTS.get(t) or gmsh.model.mesh.getElementProperties(t)[0] for t in types]
    unknown = [n for t, n in zip(types, names) if t not in VOLUME_ELEMENTS]
    if unknown:
        raise ValueError(f"mesh file {str(path)!r} has volume elements {', '.join(unknown)}: expected "
                         f"{', '.join(VOLUME_ELEMENTS.values())} (second-order hexahedra with "
                         f"Mesh.SecondOrderIncomplete = 0)")
    if len(types) > 1:
        raise ValueError(f"mesh file {str(path)!r} mixes volume elements ({' and '.join(names)}): one kind and "
                         f"one order per mesh")


def physical_volumes(gmsh, path):
    """Physical volume name → tag of the model (an unnamed one is named by
    its tag, "7"). ValueError if a meshed volume is in no physical volume
    (dolfinx reads the cells of physical volumes only) or in two (its cells
    would be made twice)."""
    names, owner = {}, {}
    for _, tag in gmsh.model.getPhysicalGroups(3):
        name = gmsh.model.getPhysicalName(3, tag) or str(tag)  # gmsh gives a name to one group only
        names[name] = tag
        for entity in gmsh.model.getEntitiesForPhysicalGroup(3, tag):
            if int(entity) in owner:
                raise ValueError(f"mesh file {str(path)!r}: volume {entity} is in the physical volumes "
                                 f"{owner[int(entity)]!r} and {name!r}: a cell can be in one only")
            owner[int(entity)] = name
    orphans = [tag for _, tag in gmsh.model.getEntities(3) if tag not in owner and
               len(gmsh.model.mesh.getElementTypes(3, tag))]
    if orphans:
        raise ValueError(f"mesh file {str(path)!r}: the elements of volume {', '.join(map(str, orphans))} are "
                         f"in no physical volume (its physical volumes: {', '.join(names) or 'none'}): put "
                         "every meshed volume in one")
    return names


def _raise_everywhere(comm, error):
    """Raise rank 0's error (if any) on every rank, resetting gmsh."""
    error = comm.bcast(error, root=0)
    if error is not None:
        if comm.rank == 0:
            _reset_gmsh()
        raise error


def _from_gmsh(comm, make):
    """The Body of the gmsh model ``make(gmsh)`` makes on rank 0; its return
    value: the regions (None: one body)."""
    gmsh = _gmsh() if comm.rank == 0 else None
    error, names, regions = None, None, None
    if comm.rank == 0:
        gmsh.clear()
        gmsh.option.setNumber("Mesh.ElementOrder", 1)  # the builders mesh first order, whatever ran before
        try:
            regions = make(gmsh)
            names = _physical_surface_names(gmsh)
        except Exception as err:
            error = err
    _raise_everywhere(comm, error)
    names, regions = comm.bcast((names, regions), root=0)
    mesh, cell_tags, facet_tags = dfx.mesh_from_gmsh(gmsh.model if comm.rank == 0 else None, comm)
    if comm.rank == 0:
        gmsh.clear()
    return Body(mesh, facet_tags, names, cell_tags, regions)



def hemisphere_arrays(radius, n, m, center=(0.0, 0.0, 0.0), grading=(1.0, 1.0)):
    """A quarter of a solid hemisphere, structured hexahedra: the part
    x, y >= 0, z <= 0 of the ball |X − center| <= radius (its flat face on
    top, its pole at center − (0, 0, radius)). The cube [0,1]² × [−1,0]
    with n × n × m cells is mapped onto it by the smooth cube-to-ball map
        x = a √(1 − b²/2 − c²/2 + b²c²/3)  (and cyclically),
    which maps the cube faces a = 1, b = 1, c = −1 onto the sphere and the
    planes a = 0, b = 0, c = 0 onto x = 0, y = 0, z = 0. ``grading`` =
    (g_ab, g_c) >= 1 clusters the cells towards the pole (a, b → 0 and
    c → −1), where a Hertz contact is.

    Returns (x, hexes, hex names, quads, quad names) in gmsh node order, the
    quads named "curved" (the sphere), "flat" (z = 0), "xmin", "ymin".
    """
    for name, value in (("n", n), ("m", m)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
            raise ValueError(f"'{name}': expected a positive integer, found {value!r}")
    if not (np.isfinite(radius) and radius > 0):
        raise ValueError(f"'radius': expected a finite number > 0, found {radius!r}")
    g_ab, g_c = (grading, grading) if np.isscalar(grading) else grading
    a1 = np.linspace(0.0, 1.0, n + 1) ** g_ab
    c1 = -1.0 + np.linspace(0.0, 1.0, m + 1) ** g_c
    a, b, c = np.meshgrid(a1, a1, c1, indexing="ij")
    x = a * np.sqrt(1 - b**2 / 2 - c**2 / 2 + b**2 * c**2 / 3)
    y = b * np.sqrt(1 - a**2 / 2 - c**2 / 2 + a**2 * c**2 / 3)
    z = c * np.sqrt(1 - a**2 / 2 - b**2 / 2 + a**2 * b**2 / 3)
    X = radius * np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1) + np.asarray(center, dtype=float)

    def node(i, j, k):
        return (i * (n + 1) + j) * (m + 1) + k

    i, j, k = (g.ravel() for g in np.meshgrid(np.arange(n), np.arange(n), np.arange(m), indexing="ij"))
    hexes = np.stack([node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                      node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)],
                     axis=1)
    quads, names = [], []

    def face(fixed_axis, index, name):
        p, q = np.meshgrid(np.arange(n if fixed_axis != 2 else n), np.arange(m if fixed_axis != 2 else n),
                           indexing="ij")
        p, q = p.ravel(), q.ravel()
        if fixed_axis == 0:
            corners = [node(index, p, q), node(index, p + 1, q), node(index, p + 1, q + 1), node(index, p, q + 1)]
        elif fixed_axis == 1:
            corners = [node(p, index, q), node(p + 1, index, q), node(p + 1, index, q + 1), node(p, index, q + 1)]
        else:
            corners = [node(p, q, index), node(p + 1, q, index), node(p + 1, q + 1, index), node(p, q + 1, index)]
        quads.append(np.stack(corners, axis=1))
        names.extend([name] * len(p))

    face(0, 0, "xmin")
    face(0, n, "curved")
    face(1, 0, "ymin")
    face(1, n, "curved")
    face(2, 0, "curved")
    face(2, m, "flat")
    return X, hexes, ["body"] * len(hexes), np.concatenate(quads), names


def graded_box_arrays(size, n, m, origin, grading, focus=None, core=None):
    """A structured box like :func:`box_model` (n × n × m cells, surfaces
    xmin … zmax) with graded spacing: per axis, grading g > 1 clusters the
    cells towards the min side (coordinates ∝ t^g), g < −1 towards the max
    side, ±1 is uniform. With ``focus`` (a point), an axis with |g| > 1
    clusters them towards the focus's coordinate instead: from both sides if
    it lies inside the box (round(k c / L) of the k cells on the side below,
    c its distance from the min side), else towards the side it lies on.
    With ``core`` (a length per axis, 0 for none), a graded axis has uniform
    cells over that length on the side it clusters towards and graded cells
    beyond (:func:`_cored`)."""
    axes = []
    core = [0.0, 0.0, 0.0] if core is None else core
    for axis, (L, o, k, g, cl) in enumerate(zip(size, origin, (n, n, m), grading, core)):
        c = None if focus is None or abs(g) == 1.0 else focus[axis] - o
        if c is None:
            axes.append(o + L * _cored(k, g, cl / L))
        elif c <= 0.0 or c >= L:
            axes.append(o + L * _cored(k, abs(g) if c <= 0.0 else -abs(g), cl / L))
        else:
            below = int(min(max(round(k * c / L), 1), k - 1))
            axes.append(o + np.concatenate([c * _graded(below, -abs(g)),
                                            c + (L - c) * _graded(k - below, abs(g))[1:]]))
    return structured_arrays(axes)


def structured_arrays(axes):
    """Hexahedra of the tensor grid of the coordinate arrays ``axes`` (x, y, z),
    gmsh node order, boundary quadrilaterals named xmin … zmax: (x, hexes,
    hex names, quads, quad names)."""
    n0, n1, n2 = (len(a) - 1 for a in axes)
    ny, nz = n1 + 1, n2 + 1
    X, Y, Z = np.meshgrid(*axes, indexing="ij")
    x = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)

    def node(i, j, k):
        return (i * ny + j) * nz + k

    i, j, k = (g.ravel() for g in np.meshgrid(np.arange(n0), np.arange(n1), np.arange(n2), indexing="ij"))
    hexes = np.stack([node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                      node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)],
                     axis=1)
    quads, names = [], []
    counts = (n0, n1, n2)
    for axis, (a, b) in enumerate([(1, 2), (0, 2), (0, 1)]):
        p, q = (g.ravel() for g in np.meshgrid(np.arange(counts[a]), np.arange(counts[b]), indexing="ij"))
        for side, index in (("min", 0), ("max", counts[axis])):
            def at(pp, qq):
                ijk = [None, None, None]
                ijk[axis], ijk[a], ijk[b] = index, pp, qq
                return node(*ijk)
            quads.append(np.stack([at(p, q), at(p + 1, q), at(p + 1, q + 1), at(p, q + 1)], axis=1))
            names.extend([f"{'xyz'[axis]}{side}"] * len(p))
    return x, hexes, ["body"] * len(hexes), np.concatenate(quads), names


#: The tube builder's surfaces: the box's faces in (r, θ, z) and what they become.
TUBE_SURFACES = {"xmin": "inner", "xmax": "outer", "ymin": "start", "ymax": "end", "zmin": "zmin", "zmax": "zmax"}


#: the largest ratio of neighbouring cells' sizes a core split accepts
CORE_GROWTH = 2.5


def _cored(k, g, core):
    """k + 1 points on [0, 1]: uniform cells over the fraction ``core`` of the
    length on the side g clusters towards (0 for g > 1, 1 for g < −1), graded
    beyond it by a shifted power law, (s + s0)^|g| rescaled, whose shift s0
    makes its first cell as large as a core cell (the spacing grows without a
    jump). The core gets as many of the k cells as it can while no cell is
    more than CORE_GROWTH times its neighbour (else the smoothest split).
    core = 0, |g| = 1 or k = 1: plain :func:`_graded`."""
    if core <= 0.0 or abs(g) == 1.0 or k < 2:
        return _graded(k, g)
    if g < 0:
        return 1.0 - _cored(k, -g, core)[::-1]

    def graded(m, h):
        s = np.linspace(0.0, 1.0, m + 1)

        def first(s0):  # the first graded cell's size for shift s0
            return (1.0 - core) * ((s[1] + s0) ** g - s0 ** g) / ((1.0 + s0) ** g - s0 ** g)

        lo, hi = 0.0, 1e6
        if first(lo) >= h:  # even unshifted the first cell is larger than a core cell
            s0 = 0.0
        else:
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if first(mid) < h else (lo, mid)
            s0 = 0.5 * (lo + hi)
        return core + (1.0 - core) * ((s + s0) ** g - s0 ** g) / ((1.0 + s0) ** g - s0 ** g)

    def points(j):
        return np.concatenate([np.linspace(0.0, core, j + 1), graded(k - j, core / j)[1:]])

    def roughness(t):
        h = np.diff(t)
        return float(np.max(np.maximum(h[1:] / h[:-1], h[:-1] / h[1:])))

    candidates = [points(j) for j in range(1, k)]
    smooth = [t for t in candidates if roughness(t) <= CORE_GROWTH]
    return smooth[-1] if smooth else min(candidates, key=roughness)


def _graded(k, g):
    """k + 1 points on [0, 1]: uniform for g = 1, clustered towards 0 for g > 1 (t^g), towards 1 for g < −1."""
    t = np.linspace(0.0, 1.0, k + 1)
    return t ** g if g > 0 else 1.0 - (1.0 - t) ** (-g)


def tube_arrays(inner_radius, thickness, length, n, m, layers, angles, grading=(1.0, 1.0, 1.0), ovality=0.0):
    """A sector of a hollow circular cylinder about the z axis, structured
    hexahedra: radius inner_radius … inner_radius + thickness (m cells), polar
    angle angles[0] … angles[1] in degrees from +x towards +y (n cells), z
    from 0 to length (layers cells). The box [r_i, r_o] × [θ0, θ1] × [0, L]
    mapped by (r, θ, z) → (r cos θ, r sin θ, z), which keeps the hexahedra's
    orientation. Surfaces "inner", "outer", "start" (θ0), "end" (θ1), "zmin",
    "zmax". An ovality Δ0 scales each radius by 1 + Δ0 cos 2θ (the diameters
    along x and y 1 ± Δ0 times the round tube's)."""
    axes = [inner_radius + thickness * _graded(m, grading[0]),
            np.radians(angles[0] + (angles[1] - angles[0]) * _graded(n, grading[1])),
            length * _graded(layers, grading[2])]
    rtz, hexes, hex_names, quads, quad_names = structured_arrays(axes)
    r, t, z = rtz.T
    r = r * (1.0 + ovality * np.cos(2.0 * t))
    x = np.stack([r * np.cos(t), r * np.sin(t), z], axis=1)
    # sin and cos of multiples of 90° to the last bit: nodes on x = 0 or y = 0 lie on the plane
    x[np.abs(x) < 1e-14 * (inner_radius + thickness)] = 0.0
    return x, hexes, hex_names, quads, [TUBE_SURFACES[q] for q in quad_names]


#: The six tetrahedra of a hexahedron (gmsh node order) around its main diagonal 0–6 (Kuhn's split):
#: the paths 0 → 6 along the edges, one per order of the axes, odd orders reversed to positive volume.
KUHN_TETRAHEDRA = np.array([[0, 1, 2, 6], [0, 5, 1, 6], [0, 2, 3, 6], [0, 3, 7, 6], [0, 4, 5, 6], [0, 7, 4, 6]])
#: The two triangles of a boundary quadrilateral along its diagonal 0–2, the one Kuhn's split takes.
KUHN_TRIANGLES = np.array([[0, 1, 2], [0, 2, 3]])


def kuhn_tetrahedra(hexes, quads):
    """(tetrahedra (6 h, 4), triangles (2 q, 3)): each hexahedron split into
    six tetrahedra around its diagonal from node 0 to node 6, each boundary
    quadrilateral into the two triangles along its diagonal from node 0 to
    node 2. Conforming on a structured grid whose cells and boundary faces
    are numbered alike (node 0 the corner of lowest i, j, k, node 6 of the
    highest, as graded_box_arrays makes them): every face is cut along its
    diagonal from the lowest to the highest corner, the same seen from either
    cell. The cells and faces of the split keep their parent's order (cell c
    gives 6c … 6c + 5), so a parent's tag repeats (np.repeat)."""
    tets = np.asarray(hexes)[:, KUHN_TETRAHEDRA].reshape(-1, 4)
    triangles = np.asarray(quads)[:, KUHN_TRIANGLES].reshape(-1, 3)
    return tets, triangles


def _builder_arrays(spec):
    """(x, cells, cell names, facets, facet names) of one body's mesh spec
    (the keys of a scene's [mesh] or [[body]] entry): hexahedra and
    quadrilaterals, or (a graded box of cells = "tetrahedra") tetrahedra and
    triangles."""
    grading = spec.get("grading", (1.0, 1.0, 1.0))
    if spec["builder"] == "box" and any(g != 1.0 for g in grading):
        x, hexes, hex_names, quads, quad_names = graded_box_arrays(spec["size"], spec["n"], spec["m"],
                                                                   spec["origin"], grading, spec.get("focus"),
                                                                   spec.get("core"))
        if spec.get("cells", "hexahedra") == "hexahedra":
            return x, hexes, hex_names, quads, quad_names
        tets, triangles = kuhn_tetrahedra(hexes, quads)
        return x, tets, list(np.repeat(hex_names, 6)), triangles, list(np.repeat(quad_names, 2))
    if spec["builder"] == "tube":
        return tube_arrays(spec["inner_radius"], spec["thickness"], spec["length"], spec["n"], spec["m"],
                           spec["layers"], spec["angles"], spec.get("grading", (1.0, 1.0, 1.0)),
                           spec.get("ovality", 0.0))
    if spec["builder"] == "hemisphere":
        if min(grading) < 1.0:
            raise ValueError(f"hemisphere: grading must be >= 1 (towards the pole), found {grading}")
        return hemisphere_arrays(spec["radius"], spec["n"], spec["m"], spec["origin"], (grading[0], grading[2]))
    gmsh = _gmsh()
    gmsh.clear()
    try:
        if spec["builder"] == "box":
            box_model(gmsh, spec["size"], spec["n"], spec["m"], spec["origin"])
        elif spec["builder"] == "shell_octant":
            from .shell import shell_octant_model

            shell_octant_model(gmsh, spec["inner_radius"], spec["thickness"], spec["n"], spec["m"])
        else:
            raise ValueError(f"builder {spec['builder']!r} cannot be one of several bodies "
                             "(use box, shell_octant or hemisphere)")
        x, hexes, hex_tags, quads, quad_tags = dfx.gmsh_arrays(gmsh.model)
        names = {tag: gmsh.model.getPhysicalName(2, tag) for _, tag in gmsh.model.getPhysicalGroups(2)}
    finally:
        gmsh.clear()
    if len(hexes) == 0:
        raise ValueError("the mesh has no hexahedra")
    return x, hexes, ["body"] * len(hexes), quads, [names[t] for t in quad_tags]


def _drop_unused_nodes(x, cells, facets):
    """The nodes no cell uses (gmsh keeps the geometry's points, e.g. the shell
    octant's centre) removed and the others renumbered: dolfinx's
    distribution of the facet tags fails (std::bad_alloc) on a mesh of several
    bodies when one leaves a node unused before the next body's nodes."""
    used = np.zeros(len(x), dtype=bool)
    used[np.asarray(cells).ravel()] = True
    if used.all():
        return x, cells, facets
    new = np.cumsum(used) - 1
    return x[used], new[cells], new[facets]


def build_bodies(comm, parts):
    """Several bodies in one mesh, sharing no node: ``parts`` is a list of
    (name, mesh spec); the first body's surfaces keep their plain names
    (xmin, zmax, ...), the others' are prefixed "NAME." (punch.zmin). Cells
    are tagged by body (regions: name → tag, 1, 2, ...). One body may be a
    graded box of tetrahedra; several bodies are hexahedra."""
    error, surfaces, regions, widths = None, None, None, None
    x = cells = cell_values = facets = facet_values = None
    if comm.rank == 0:
        try:
            xs, cs, cvs, fs, fvs, surfaces = [], [], [], [], [], {}
            offset = 0
            for k, (name, spec) in enumerate(parts):
                xb, cb, _, fb, fnames = _builder_arrays(spec)
                xb, cb, fb = _drop_unused_nodes(xb, cb, fb)
                prefix = "" if k == 0 else f"{name}."
                for fn in fnames:
                    surfaces.setdefault(prefix + fn, len(surfaces) + 1)
                xs.append(xb)
                cs.append(cb + offset)
                fs.append(fb + offset)
                cvs.append(np.full(len(cb), k + 1, dtype=np.int32))
                fvs.append(np.array([surfaces[prefix + fn] for fn in fnames], dtype=np.int32))
                offset += len(xb)
            x, cells, cell_values = np.concatenate(xs), np.concatenate(cs), np.concatenate(cvs)
            facets, facet_values = np.concatenate(fs), np.concatenate(fvs)
            regions = {name: k + 1 for k, (name, _) in enumerate(parts)}
            widths = cells.shape[1], facets.shape[1]
        except Exception as err:
            error = err
    _raise_everywhere(comm, error)
    surfaces, regions, widths = comm.bcast((surfaces, regions, widths), root=0)
    if comm.rank != 0:
        x, cells, cell_values = np.zeros((0, 3)), np.zeros((0, widths[0]), dtype=np.int64), np.zeros(0, np.int32)
        facets, facet_values = np.zeros((0, widths[1]), dtype=np.int64), np.zeros(0, dtype=np.int32)
    mesh, cell_tags, facet_tags = dfx.mesh_from_arrays(comm, x, cells, cell_values, facets, facet_values)
    return Body(mesh, facet_tags, surfaces, cell_tags, regions)


def build_mesh(comm, mesh, bodies=()):
    """The Body of a scene's [mesh] spec and its [[body]] entries: the one
    place a builder name becomes a mesh. A file is read through gmsh, its
    [[body]] entries physical volumes of it; several built bodies, or a graded
    box, are built as arrays into one mesh (build_bodies); one body, the
    shell octant or a box, through gmsh."""
    if mesh["builder"] == "file":
        body = read_msh(comm, mesh["file"])
        for i, b in enumerate(bodies):
            if b["volume"] not in body.regions:
                close = difflib.get_close_matches(b["volume"], list(body.regions), n=1)
                raise SceneError(f"scene key 'body[{i}].volume': mesh file {mesh['file']!r} has no physical "
                                 f"volume {b['volume']!r} (it has {', '.join(body.regions)})"
                                 + (f"; did you mean '{close[0]}'?" if close else ""))
        return body
    if bodies or any(g != 1.0 for g in mesh["grading"]) or mesh["builder"] == "tube":
        return build_bodies(comm, [("body", mesh)] + [(b["name"], b) for b in bodies])
    if mesh["builder"] == "oring":
        from .oring import oring_model

        keys = ("mean_diameter", "cord_diameter", "n", "m", "cells", "cross_section", "order")
        return _from_gmsh(comm, lambda g: oring_model(g, *(mesh[k] for k in keys)))
    if mesh["builder"] == "shell_octant":
        from .shell import build_shell_octant

        return build_shell_octant(comm, mesh["inner_radius"], mesh["thickness"], mesh["n"], mesh["m"])
    return build_box(comm, mesh["size"], mesh["n"], mesh["m"], mesh["origin"], mesh.get("cells", "hexahedra"))


def surface_regions(body, tag):
    """The regions (sorted names) whose cells the facets with ``tag`` bound, on every rank."""
    cells = dfx.facet_cells(body.mesh, dfx.facets_with_tag(body.facet_tags, tag))
    tags = set(body.cell_tags.values[np.isin(body.cell_tags.indices, cells)].tolist())
    tags = set().union(*body.mesh.comm.allgather(tags))
    return sorted(name for name, t in body.regions.items() if t in tags)
