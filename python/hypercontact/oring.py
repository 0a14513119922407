"""An O-ring: a quarter of a torus, built with gmsh's OpenCASCADE kernel.

The torus has its axis on z, mean diameter D (the cord's centre line is the
circle of radius D/2 in the plane z = 0) and cord diameter d. A quarter of
it in azimuth (x, y >= 0) is modelled, with symmetry planes x = 0 ("xmin")
and y = 0 ("ymin"); with ``cross_section = "half"`` only its upper half
z >= 0, with the mid-plane z = 0 ("zmin") a third symmetry plane — the
O-ring squeezed between two plates. The torus surface is "outer".

Hexahedra: the cross-section (a disc or half disc in the plane y = 0) is an
O-grid — a core square (or rectangle) and one patch between each core edge
and a quarter of the circle — of transfinite quadrilaterals, revolved about
z by 90° in m layers. n cells across the cord's diameter (a multiple of 4:
n/4 radially in each patch, n/2 along each core edge).

Tetrahedra: the OpenCASCADE torus sector meshed by gmsh's Delaunay
algorithm at the size d/n, the cut by z = 0 a boolean intersection.

``order = 2`` makes second-order cells (27-node hexahedra, 10-node
tetrahedra) whose nodes lie on the torus: curved facets, so that quadratic
elements see the round cord and not its chords.
"""
import math

#: Core half-width over the cord radius: the O-grid's square core.
CORE = 0.5


def _check(mean_diameter, cord_diameter, n, cells, cross_section, order):
    if not cord_diameter < mean_diameter:
        raise ValueError(f"'cord_diameter': expected less than mean_diameter ({mean_diameter}) — the torus "
                         f"would cross its axis — found {cord_diameter}")
    if cells == "hexahedra" and n % 4:
        raise ValueError(f"'n': the O-ring's hexahedral O-grid needs a multiple of 4 cells across the cord "
                         f"(n/4 radially in each patch, n/2 along each core edge), found {n}")
    if cross_section not in ("half", "full"):
        raise ValueError(f"'cross_section': expected \"half\" or \"full\", found {cross_section!r}")
    if order not in (1, 2):
        raise ValueError(f"'order': expected 1 or 2, found {order!r}")


def _o_grid(gmsh, Rm, r, n, half):
    """The cross-section in the plane y = 0 as transfinite quadrilateral patches (centre (Rm, 0, 0));
    returns their surface tags."""
    occ = gmsh.model.occ
    a = CORE * r
    c = occ.addPoint(Rm, 0.0, 0.0)
    # corners of the core and the circle points facing them, counter-clockwise in (x, z) from angle -45°
    angles = [45.0, 135.0] if half else [-45.0, 45.0, 135.0, 225.0]

    def on_core(deg):
        s, t = math.cos(math.radians(deg)), math.sin(math.radians(deg))
        return occ.addPoint(Rm + a * math.copysign(1.0, s), 0.0, a * math.copysign(1.0, t))

    def on_circle(deg):
        return occ.addPoint(Rm + r * math.cos(math.radians(deg)), 0.0, r * math.sin(math.radians(deg)))

    core = [on_core(t) for t in angles]
    ring = [on_circle(t) for t in angles]
    if half:  # the core's and the patches' bottom corners on z = 0
        core = [occ.addPoint(Rm + a, 0.0, 0.0)] + core + [occ.addPoint(Rm - a, 0.0, 0.0)]
        ring = [occ.addPoint(Rm + r, 0.0, 0.0)] + ring + [occ.addPoint(Rm - r, 0.0, 0.0)]
    k, j = n // 2, n // 4  # cells along a core edge, cells radially in a patch
    spokes = [occ.addLine(p, q) for p, q in zip(core, ring)]
    count = len(core) if not half else len(core) - 1
    patches = []
    core_edges = []
    for i in range(count):
        i1 = (i + 1) % len(core)
        inner = occ.addLine(core[i], core[i1])
        outer = occ.addCircleArc(ring[i], c, ring[i1])
        core_edges.append(inner)
        loop = occ.addCurveLoop([inner, spokes[i1], -outer, -spokes[i]])
        patches.append((occ.addPlaneSurface([loop]), inner, outer))
    if half:  # the core is closed by its bottom edge on z = 0
        bottom = occ.addLine(core[-1], core[0])
        core_surface = occ.addPlaneSurface([occ.addCurveLoop([bottom] + core_edges)])
    else:
        core_surface = occ.addPlaneSurface([occ.addCurveLoop(core_edges)])
    occ.synchronize()
    mesh = gmsh.model.mesh
    for line in spokes:
        mesh.setTransfiniteCurve(line, j + 1)
    for i, (_, inner, outer) in enumerate(patches):
        along = k // 2 if half and i in (0, len(patches) - 1) else k  # the half core's sides are half as long
        mesh.setTransfiniteCurve(inner, along + 1)
        mesh.setTransfiniteCurve(outer, along + 1)
    if half:
        mesh.setTransfiniteCurve(bottom, k + 1)
        mesh.setTransfiniteSurface(core_surface, cornerTags=core[:1] + core[1:3] + core[-1:])
    else:
        mesh.setTransfiniteSurface(core_surface)
    surfaces = [s for s, _, _ in patches] + [core_surface]
    for s in surfaces:
        if s != core_surface:
            mesh.setTransfiniteSurface(s)
        mesh.setRecombine(2, s)
    return surfaces


def _hexahedra(gmsh, Rm, r, n, m, half):
    sections = _o_grid(gmsh, Rm, r, n, half)
    gmsh.model.occ.revolve([(2, s) for s in sections], 0, 0, 0, 0, 0, 1, math.pi / 2, numElements=[m],
                           recombine=True)
    gmsh.model.occ.synchronize()


def _tetrahedra(gmsh, Rm, r, n, half):
    occ = gmsh.model.occ
    torus = occ.addTorus(0.0, 0.0, 0.0, Rm, r, angle=math.pi / 2)
    if half:
        box = occ.addBox(0.0, 0.0, 0.0, Rm + 2 * r, Rm + 2 * r, 2 * r)
        occ.intersect([(3, torus)], [(3, box)])
    occ.synchronize()
    return 2 * r / n


def _name_surfaces(gmsh, tol):
    """Physical surfaces: planes x = 0, y = 0, z = 0 are xmin, ymin, zmin, the rest of the body's boundary is
    the torus, outer. The surfaces inside the body (the revolved spokes and seams of the hexahedral O-grid)
    are in no group: a surface group holds boundary facets only."""
    groups = {}
    volumes = gmsh.model.getEntities(3)
    boundary = {tag for _, tag in gmsh.model.getBoundary(volumes, combined=True, oriented=False)}
    for _, tag in gmsh.model.getEntities(2):
        if tag not in boundary:
            continue
        b = gmsh.model.getBoundingBox(2, tag)
        name = "outer"
        for axis, a in enumerate("xyz"):
            if abs(b[axis]) < tol and abs(b[axis + 3]) < tol:
                name = f"{a}min"
        groups.setdefault(name, []).append(tag)
    for i, (name, tags) in enumerate(sorted(groups.items()), start=1):
        gmsh.model.addPhysicalGroup(2, tags, i)
        gmsh.model.setPhysicalName(2, i, name)
    vol = gmsh.model.addPhysicalGroup(3, [e[1] for e in gmsh.model.getEntities(3)], 100)
    gmsh.model.setPhysicalName(3, vol, "body")


def oring_model(gmsh, mean_diameter, cord_diameter, n, m, cells="hexahedra", cross_section="half", order=1):
    """The quarter O-ring (module docstring) as a meshed gmsh model: n cells across the cord's diameter,
    m hexahedral layers along the quarter circle (tetrahedra: size d/n everywhere, m unused)."""
    _check(mean_diameter, cord_diameter, n, cells, cross_section, order)
    gmsh.model.add("oring")
    Rm, r, half = mean_diameter / 2.0, cord_diameter / 2.0, cross_section == "half"
    sizes = {}
    if cells == "hexahedra":
        _hexahedra(gmsh, Rm, r, n, m, half)
    else:
        h = _tetrahedra(gmsh, Rm, r, n, half)
        sizes = {"Mesh.CharacteristicLengthMin": h, "Mesh.CharacteristicLengthMax": h}
    _name_surfaces(gmsh, 1e-6 * mean_diameter + 1e-6)
    # gmsh's options outlive the model in the session: each is set for this mesh and restored after it,
    # or it would size (or order) every mesh built after it in the process
    saved = {k: gmsh.option.getNumber(k) for k in sizes}
    try:
        for k, v in sizes.items():
            gmsh.option.setNumber(k, v)
        gmsh.model.mesh.generate(3)
    finally:
        for k, v in saved.items():
            gmsh.option.setNumber(k, v)
    if order == 2:
        incomplete = gmsh.option.getNumber("Mesh.SecondOrderIncomplete")
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 0)  # 27-node hexahedra, not 20-node
        try:
            gmsh.model.mesh.setOrder(2)
        finally:
            gmsh.option.setNumber("Mesh.SecondOrderIncomplete", incomplete)
