"""A structured hexahedral mesh of one octant of a thick spherical shell.

The octant x, y, z >= 0 of the sphere surface is split into three
quadrilateral patches (the "cube-sphere" split): each patch has as corners one
pole of the octant (on the x, y or z axis), the midpoints of the two octant
boundary arcs through that pole, and the octant's centre point (1, 1, 1)/sqrt(3).
All patch edges are great-circle arcs, so no element degenerates at a pole.
Each patch, swept radially from the inner to the outer sphere, is one
transfinite hexahedral block.
"""
import math

import numpy as np

from .geometry import _from_gmsh

# Unit directions of the patch corners: the poles A, B, C on the x, y, z axes,
# the midpoints AB, BC, CA of the octant's boundary arcs, the centre G.
_S2, _S3 = 1.0 / math.sqrt(2.0), 1.0 / math.sqrt(3.0)
_DIRECTIONS = {
    "A": (1.0, 0.0, 0.0), "B": (0.0, 1.0, 0.0), "C": (0.0, 0.0, 1.0),
    "AB": (_S2, _S2, 0.0), "BC": (0.0, _S2, _S2), "CA": (_S2, 0.0, _S2),
    "G": (_S3, _S3, _S3),
}
# Great-circle arcs between patch corners: the six halves of the octant's
# boundary arcs, then the three arcs from the boundary midpoints to the centre.
_ARCS = [("A", "AB"), ("AB", "B"), ("B", "BC"), ("BC", "C"), ("C", "CA"), ("CA", "A"),
         ("AB", "G"), ("BC", "G"), ("CA", "G")]
# The boundary planes holding the boundary arcs (a radial surface swept from
# such an arc lies in that plane).
_PLANE_OF_ARC = {("A", "AB"): "zmin", ("AB", "B"): "zmin", ("B", "BC"): "xmin",
                 ("BC", "C"): "xmin", ("C", "CA"): "ymin", ("CA", "A"): "ymin"}
# The three patches, corners in order around each (pole, midpoint, centre, midpoint).
_PATCHES = {"A": ("A", "AB", "G", "CA"), "B": ("B", "BC", "G", "AB"), "C": ("C", "CA", "G", "BC")}


def _check_arguments(inner_radius, thickness, n, m):
    for name, value in (("n", n), ("m", m)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
            raise ValueError(f"'{name}': expected an integer, found {value!r}")
        if value < 1:
            raise ValueError(f"'{name}': expected a positive number of elements, found {value}")
    if n % 2:
        raise ValueError(f"'n': expected an even number of elements along each octant edge "
                         f"(n/2 on each of the three patches' edges), found {n}")
    for name, value in (("inner_radius", inner_radius), ("thickness", thickness)):
        if not (isinstance(value, (int, float, np.integer, np.floating)) and math.isfinite(value) and value > 0):
            raise ValueError(f"'{name}': expected a finite number > 0, found {value!r}")


def shell_octant_model(gmsh, inner_radius, thickness, n, m):
    """Octant x, y, z >= 0 of the shell inner_radius <= |x| <= inner_radius + thickness.

    Structured hexahedra: n elements along each edge of the octant (n even,
    n/2 on each patch edge), m through the thickness; 3 (n/2)^2 m cells. Mesh
    nodes on the inner and outer surfaces lie on the spheres (the elements are
    first order). Physical surfaces inner, outer, xmin, ymin, zmin (the planes
    x = 0, y = 0, z = 0); volume "body".
    """
    _check_arguments(inner_radius, thickness, n, m)
    gmsh.model.add("shell_octant")
    geo = gmsh.model.geo
    radii = (float(inner_radius), float(inner_radius) + float(thickness))
    centre = geo.addPoint(0.0, 0.0, 0.0)
    point = {(k, name): geo.addPoint(*(r * np.array(d)))
             for k, r in enumerate(radii) for name, d in _DIRECTIONS.items()}

    # Great-circle arcs on both spheres (k = 0 inner, 1 outer), signed by direction.
    arc = {}
    for k in range(2):
        for a, b in _ARCS:
            tag = geo.addCircleArc(point[k, a], centre, point[k, b])
            arc[k, a, b], arc[k, b, a] = tag, -tag
    radial = {name: geo.addLine(point[0, name], point[1, name]) for name in _DIRECTIONS}

    # Radial surfaces swept from each arc: planar (the arc's plane goes through the centre).
    side = {}
    for a, b in _ARCS:
        loop = geo.addCurveLoop([arc[0, a, b], radial[b], arc[1, b, a], -radial[a]])
        side[a, b] = side[b, a] = geo.addSurfaceFilling([loop])
    # Spherical patches: transfinite interpolation on the sphere about the centre.
    cap = {}
    for k in range(2):
        for p, corners in _PATCHES.items():
            loop = geo.addCurveLoop([arc[k, corners[i], corners[(i + 1) % 4]] for i in range(4)])
            cap[k, p] = geo.addSurfaceFilling([loop], sphereCenterTag=centre)
    volume = {}
    for p, corners in _PATCHES.items():
        shell = geo.addSurfaceLoop([cap[0, p], cap[1, p]] + [side[corners[i], corners[(i + 1) % 4]] for i in range(4)])
        volume[p] = geo.addVolume([shell])
    geo.synchronize()

    mesh = gmsh.model.mesh
    for (k, a, b), tag in arc.items():
        if tag > 0:
            mesh.setTransfiniteCurve(tag, n // 2 + 1)
    for tag in radial.values():
        mesh.setTransfiniteCurve(tag, m + 1)
    for _, tag in gmsh.model.getEntities(2):
        mesh.setTransfiniteSurface(tag)
        mesh.setRecombine(2, tag)
    for p, corners in _PATCHES.items():
        mesh.setTransfiniteVolume(volume[p], [point[0, c] for c in corners] + [point[1, c] for c in corners])

    groups = {"inner": [cap[0, p] for p in _PATCHES], "outer": [cap[1, p] for p in _PATCHES],
              "xmin": [], "ymin": [], "zmin": []}
    for a_b, plane in _PLANE_OF_ARC.items():
        groups[plane].append(side[a_b])
    for i, name in enumerate(sorted(groups), start=1):
        gmsh.model.addPhysicalGroup(2, groups[name], i)
        gmsh.model.setPhysicalName(2, i, name)
    body = gmsh.model.addPhysicalGroup(3, list(volume.values()), 100)
    gmsh.model.setPhysicalName(3, body, "body")
    mesh.generate(3)


def build_shell_octant(comm, inner_radius=95.0, thickness=1.0, n=16, m=4):
    """A structured hexahedral shell-octant body (see :func:`shell_octant_model`)."""
    _check_arguments(inner_radius, thickness, n, m)  # on every rank, before any collective call
    return _from_gmsh(comm, lambda g: shell_octant_model(g, inner_radius, thickness, n, m))
