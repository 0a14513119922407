"""[mesh] (the main body) and [[body]] (further bodies, each with its own
material): a built-in builder and its keys, or a mesh file (then each
[[body]] is one of its physical volumes)."""
import re
from typing import Optional

from pydantic import root_validator, validator

from .base import SceneModel
from .builders import BODY_BUILDERS, CELL_KINDS, MESH_BUILDERS, check_shape, choices
from .errors import Invalid, printable
from .fields import (ALL_POSITIVE, COORDINATES, FILE_NAME, GRADING, LENGTH, NON_NEGATIVE, POSITIVE, from_to,
                     integer, number, one_of, pair, string, vector)
from .material import Material
from .paths import existing_file

SIZE = vector(ALL_POSITIVE, COORDINATES)
#: A body's name prefixes its surfaces ("punch.zmin").
BODY_NAME = (lambda x: re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", x) is not None,
             "a name of letters, digits and _ (it prefixes the body's surfaces)")


class Mesh(SceneModel):
    builder: string(one_of(MESH_BUILDERS, choices(MESH_BUILDERS))) = "box"
    inner_radius: number(POSITIVE, LENGTH) = 95.0
    thickness: number(POSITIVE, LENGTH) = 1.0
    size: SIZE = [1.0, 1.0, 1.0]
    origin: vector(COORDINATES) = [0.0, 0.0, 0.0]
    n: integer(POSITIVE) = 4
    m: integer(POSITIVE) = 4
    grading: vector(GRADING) = [1.0, 1.0, 1.0]
    #: the box builder: the point graded axes cluster their cells towards (from both sides where it is
    #: inside the box, e.g. a punch's edge); not given: towards the side the sign of grading says
    focus: Optional[vector(COORDINATES)] = None
    #: the box builder: per axis, a length over which a graded axis keeps uniform cells on the side it
    #: clusters towards, graded beyond (0: none); e.g. a contact zone resolved evenly in a large block
    core: Optional[vector(COORDINATES)] = None
    #: the box builder's cells: hexahedra, or each hexahedron split into six tetrahedra (the oring
    #: builder's: an O-grid of hexahedra, or gmsh's Delaunay tetrahedra)
    cells: string(one_of(CELL_KINDS, choices(CELL_KINDS))) = "hexahedra"
    #: the oring builder (hypercontact/oring.py): a quarter torus about z
    mean_diameter: number(POSITIVE, LENGTH) = 24.0
    cord_diameter: number(POSITIVE, LENGTH) = 4.0
    #: "half": z >= 0 with the symmetry plane zmin (squeezed between plates); "full": the whole cord
    cross_section: string(one_of(("half", "full"), '"half" or "full"')) = "half"
    #: the oring builder's geometry: 1 (straight-sided cells) or 2 (second-order cells on the torus)
    order: integer(from_to(1, 2, "1 or 2")) = 1
    #: the tube builder (hollow cylinder about z, inner_radius and thickness as the shell's): its length
    #: along z in `layers` cells, and the polar angles in degrees (from +x towards +y) of its sector
    length: number(POSITIVE, LENGTH) = 1.0
    layers: integer(POSITIVE) = 1
    angles: pair() = [0.0, 90.0]
    #: the tube builder's initial ovality Δ0 = (D_max − D_min)/(D_max + D_min): each radius scaled by
    #: 1 + Δ0 cos 2θ, the long axis along x for Δ0 > 0 (along y for Δ0 < 0); the imperfection that
    #: turns a tube's buckling under external pressure from a bifurcation into a smooth path
    ovality: number(from_to(-0.5, 0.5)) = 0.0
    file: string(FILE_NAME) = ""
    #: random node displacements of this fraction of the smallest cell's size (fixed per node):
    #: a check that results move continuously with the data, not a modelling feature
    perturbation: number(NON_NEGATIVE, (lambda x: x <= 1e-2, "at most 0.01")) = 0.0

    @root_validator(skip_on_failure=True)
    def file_or_builder(cls, values):
        """builder = "file" reads an existing file (its path made absolute);
        the other builders make a mesh that must not degenerate."""
        if values["builder"] == "file":
            if not values["file"]:
                raise Invalid('missing: builder = "file" needs a mesh file path', "file")
            values["file"] = str(existing_file(values["file"], "mesh file", "file"))
        elif values["file"]:
            raise Invalid('given, but mesh.builder is not "file"', "file")
        check_shape(values)
        return values


class Body(SceneModel):
    name: string(BODY_NAME)
    builder: string(one_of(BODY_BUILDERS, choices(BODY_BUILDERS))) = "box"
    size: SIZE = [1.0, 1.0, 1.0]
    origin: vector(COORDINATES) = [0.0, 0.0, 0.0]
    n: integer(POSITIVE) = 4
    m: integer(POSITIVE) = 4
    inner_radius: number(POSITIVE, LENGTH) = 95.0
    thickness: number(POSITIVE, LENGTH) = 1.0
    radius: number(POSITIVE, LENGTH) = 1.0
    grading: vector(GRADING) = [1.0, 1.0, 1.0]
    focus: Optional[vector(COORDINATES)] = None
    #: the box builder: per axis, a length over which a graded axis keeps uniform cells on the side it
    #: clusters towards, graded beyond (0: none); e.g. a contact zone resolved evenly in a large block
    core: Optional[vector(COORDINATES)] = None
    #: a physical volume of the [mesh] file: the body is its cells (no builder keys); "": none
    volume: string() = ""
    material: Material

    @root_validator(pre=True)
    def volume_or_builder(cls, values):
        if values.get("volume", "") != "":  # "" (a loaded scene written back): a built body
            for key in values:
                if key not in ("name", "volume", "material"):
                    raise Invalid("given, but the body is a physical volume of the mesh file (volume = "
                                  f"{printable(repr(values['volume']), 60)}): its cells are the file's", key)
        return values

    @validator("name")
    def not_the_main_body(cls, name):
        if name == "body":
            raise Invalid("the name 'body' is taken by the [mesh] body")
        return name

    @root_validator(skip_on_failure=True)
    def sane_shape(cls, values):
        check_shape(values)
        return values

