"""The built-in mesh builders, listed once: where each may be used, the
surfaces it names, how many hexahedra it makes, and what its keys must
satisfy for the mesh not to degenerate.

``[mesh]`` is built by "box", "shell_octant", "oring" or read from a "file";
``[[body]]`` entries by "box", "shell_octant" or "hemisphere".
"""
import math
from dataclasses import dataclass

from .errors import Invalid
from .fields import MAX_CELLS, MAX_LENGTH


@dataclass(frozen=True)
class Builder:
    """One builder. ``surfaces``: surface name → the axis of its normal if it
    is a plane x, y or z = const, None if curved; None for a mesh file
    (its surfaces are known once it is read)."""

    name: str
    surfaces: dict = None
    main: bool = False  #: may build [mesh]
    body: bool = False  #: may build a [[body]]
    graded: bool = False  #: takes grading

    def cells(self, spec):
        """Number of cells of the builder's keys ``spec`` (the O-ring's tetrahedra: an estimate)."""
        n, m = spec["n"], spec["m"]
        if self.name == "shell_octant":
            return 3 * (n // 2) ** 2 * m
        if self.name == "oring":
            share = 0.5 if spec["cross_section"] == "half" else 1.0
            if spec["cells"] == "tetrahedra":  # gmsh's Delaunay mesh: about 5.4 tetrahedra per h³, h = d/n
                volume = share * math.pi ** 3 / 16 * spec["mean_diameter"] * spec["cord_diameter"] ** 2
                return int(5.4 * volume / (spec["cord_diameter"] / n) ** 3)
            return int(share * 3 * n * n * m / 4)
        if self.name == "tube":
            return n * m * spec["layers"]
        return n * n * m * (6 if spec.get("cells") == "tetrahedra" else 1)

    def surfaces_of(self, spec):
        """The surfaces the builder makes with the keys ``spec``: a whole O-ring cross-section
        has no mid-plane zmin."""
        if self.name == "oring" and spec["cross_section"] == "full":
            return {k: v for k, v in self.surfaces.items() if k != "zmin"}
        return self.surfaces


BUILDERS = {
    "box": Builder("box", {"xmin": 0, "xmax": 0, "ymin": 1, "ymax": 1, "zmin": 2, "zmax": 2},
                   main=True, body=True, graded=True),
    "shell_octant": Builder("shell_octant", {"inner": None, "outer": None, "xmin": 0, "ymin": 1, "zmin": 2},
                            main=True, body=True),
    "hemisphere": Builder("hemisphere", {"curved": None, "flat": 2, "xmin": 0, "ymin": 1}, body=True,
                          graded=True),
    "oring": Builder("oring", {"outer": None, "xmin": 0, "ymin": 1, "zmin": 2}, main=True),
    "tube": Builder("tube", {"inner": None, "outer": None, "start": None, "end": None, "zmin": 2, "zmax": 2},
                    main=True, graded=True),
    "file": Builder("file", main=True),
}
#: What the box builder's cells may be (mesh.cells).
CELL_KINDS = ("hexahedra", "tetrahedra")
MESH_BUILDERS = tuple(name for name, b in BUILDERS.items() if b.main)
BODY_BUILDERS = tuple(name for name, b in BUILDERS.items() if b.body)
#: The surfaces of each builder that names them.
BUILDER_SURFACES = {name: b.surfaces for name, b in BUILDERS.items() if b.surfaces is not None}


def choices(names):
    """'"a", "b" or "c"'."""
    *first, last = (f'"{n}"' for n in names)
    return f"{', '.join(first)} or {last}" if first else last


def check_shape(spec):
    """Invalid (naming the key) if a built-in builder's keys ``spec`` would
    make a degenerate or oversized mesh."""
    builder = BUILDERS[spec["builder"]]
    _check_focus(spec)
    _check_core(spec)
    if builder.surfaces is None:
        return
    if not builder.graded and spec["grading"] != [1.0, 1.0, 1.0]:
        raise Invalid(f"grading applies to the {choices(n for n, b in BUILDERS.items() if b.graded).replace(chr(34), '')} "
                      f"builders, not {builder.name!r}", "grading")
    if spec.get("order", 1) != 1 and builder.name != "oring":
        raise Invalid(f"order applies to the oring builder, not {builder.name!r} (a second-order mesh of another "
                      f"shape: a gmsh file written with Mesh.ElementOrder = 2)", "order")
    if spec.get("cells", "hexahedra") != "hexahedra" and builder.name not in ("box", "oring"):
        raise Invalid(f"cells = {spec['cells']!r} applies to the box and oring builders, not {builder.name!r}",
                      "cells")
    {"box": _check_box, "shell_octant": _check_shell, "hemisphere": _check_hemisphere,
     "oring": _check_oring, "tube": _check_tube}[builder.name](spec)
    cells = builder.cells(spec)
    if cells > MAX_CELLS:
        kind = "tetrahedra" if spec.get("cells") == "tetrahedra" else "hexahedra"
        raise Invalid(f"n = {spec['n']}, m = {spec['m']} make {cells:.3g} {kind}, more than "
                      f"{MAX_CELLS:.0e}", "n")


def _check_focus(spec):
    """focus: the box builder's only, with a graded axis, inside or on the box along each graded axis."""
    focus = spec.get("focus")
    if focus is None:
        return
    if spec["builder"] != "box":
        raise Invalid(f"focus applies to the box builder, not {spec['builder']!r}", "focus")
    graded = [a for a in range(3) if abs(spec["grading"][a]) != 1.0]
    if not graded:
        raise Invalid("given, but no axis is graded (grading = [1, 1, 1]): the focus is where graded cells "
                      "cluster", "focus")
    for a in graded:
        lo, hi = spec["origin"][a], spec["origin"][a] + spec["size"][a]
        if not lo <= focus[a] <= hi:
            raise Invalid(f"the focus's {'xyz'[a]} = {focus[a]:g} is outside the box ({lo:g} to {hi:g}) on the "
                          f"graded axis {'xyz'[a]}", "focus")


def _check_core(spec):
    """core: the box builder's only; per axis a length 0 <= c < the box's, c > 0 on graded axes only and
    not where an interior focus clusters cells from both sides."""
    core = spec.get("core")
    if core is None:
        return
    if spec["builder"] != "box":
        raise Invalid(f"core applies to the box builder, not {spec['builder']!r}", "core")
    focus = spec.get("focus")
    for a, c in enumerate(core):
        axis, L = "xyz"[a], spec["size"][a]
        if c < 0.0:
            raise Invalid(f"the core's {axis} length is negative ({c:g}); expected a length >= 0", "core")
        if c == 0.0:
            continue
        if abs(spec["grading"][a]) == 1.0:
            raise Invalid(f"a core length along {axis} ({c:g}) needs that axis graded (grading[{a}] = "
                          f"{spec['grading'][a]:g}): the core is where graded cells stay uniform", "core")
        if c >= L:
            raise Invalid(f"the core's {axis} length {c:g} must be shorter than the box's ({L:g})", "core")
        if focus is not None and spec["origin"][a] < focus[a] < spec["origin"][a] + L:
            raise Invalid(f"a core along {axis} with the focus inside the box along {axis} is not supported "
                          f"(the core is measured from the side the cells cluster towards)", "core")


def _check_box(spec):
    size = spec["size"]
    if min(size) < 1e-4 * max(size):
        raise Invalid(f"the smallest length must be at least 1e-4 × the largest (the surfaces are told apart "
                      f"by a relative tolerance), found {size}", "size")
    if any(abs(o + s) > MAX_LENGTH for o, s in zip(spec["origin"], size)):
        raise Invalid(f"the box reaches beyond coordinates of {MAX_LENGTH:g} (origin {spec['origin']})", "size")


def _check_shell(spec):
    if spec["n"] % 2:
        raise Invalid(f"the shell_octant builder needs an even n (n/2 elements on each of the three patches' "
                      f"edges), found {spec['n']}", "n")
    r, t = spec["inner_radius"], spec["thickness"]
    if t < 1e-6 * r or r < 1e-6 * t:
        raise Invalid(f"expected thickness and inner_radius within a factor 1e6 of each other (the mesh "
                      f"degenerates otherwise), found thickness {t}, inner_radius {r}", "thickness")


def _check_hemisphere(spec):
    if min(spec["grading"]) < 1.0:
        raise Invalid(f"the hemisphere's grading clusters cells towards its pole only: expected numbers >= 1, "
                      f"found {spec['grading']}", "grading")


def _check_tube(spec):
    start, end = spec["angles"]
    if not 0.0 < end - start <= 180.0:
        raise Invalid(f"expected a sector of more than 0° and at most 180° (angles[1] − angles[0]; a larger "
                      f"tube is two halves joined by symmetry or contact), found {start:g}° to {end:g}°",
                      "angles")
    _check_shell(dict(spec, n=2))


def _check_oring(spec):
    d, D = spec["cord_diameter"], spec["mean_diameter"]
    if not d < D:
        raise Invalid(f"expected a cord_diameter less than mean_diameter ({D:g}): the torus would cross its axis, "
                      f"found {d:g}", "cord_diameter")
    if d < 1e-4 * D:
        raise Invalid(f"expected a cord_diameter of at least 1e-4 × mean_diameter ({D:g}), found {d:g}",
                      "cord_diameter")
    if spec["cells"] == "hexahedra" and spec["n"] % 4:
        raise Invalid(f"the O-ring's hexahedral O-grid needs a multiple of 4 cells across the cord (n/4 radially "
                      f"in each patch, n/2 along each core edge), found {spec['n']}", "n")
