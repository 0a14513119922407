"""[[contact]]: a tagged union on ``obstacle``. Every kind has the keys of
the normal and tangential laws and of their enforcement; the rigid
obstacles (plane, box, cylinder, sphere) move by ``motion`` × λ and have their
own geometry; a deformable body's "surface" has its master surfaces and
search. A key of another kind is refused, naming the kinds it belongs to.
"""
import difflib
from typing import ClassVar, List, Literal, Optional, Union

from pydantic import Field, root_validator, validator
from typing_extensions import Annotated

from .base import SceneModel, tables
from .builders import choices
from .errors import HIDDEN_LOCATIONS, Invalid, describe, printable
from .fields import (COORDINATES, LENGTH, Boolean, NON_NEGATIVE, NON_ZERO_VECTOR, POSITIVE, from_to, integer, number,
                     one_of, string, vector)

OBSTACLE_CHOICES = '"plane", "box", "cylinder", "sphere" (rigid) or "surface" (a deformable body\'s surface)'
#: ε_N and ε_T: 0 chooses them automatically.
AUTOMATIC_OR_MAGNITUDE = "or from 1e-100 to 1e+100"


def _penalty(zero_means):
    return number(NON_NEGATIVE, (lambda x: x == 0 or 1e-100 <= x <= 1e100, f"{zero_means} {AUTOMATIC_OR_MAGNITUDE}"))


class Contact(SceneModel):
    """The keys every kind of contact has."""

    KIND: ClassVar[str] = ""
    name: string()
    surface: string()
    obstacle: str
    eps_n: _penalty("0 (automatic: penalty_factor × M / h)") = 0.0
    penalty_factor: number(POSITIVE, from_to(1e-6, 1e12, "from 1e-6 to 1e12")) = 100.0
    enforcement: string(one_of(("penalty", "augmented_lagrangian"), '"penalty" or "augmented_lagrangian"')) = \
        "penalty"
    gap_tolerance: number(NON_NEGATIVE, LENGTH) = 0.0
    #: the normal law's kink at g = 0 smoothed over |g| < smoothing × h (h: the first element
    #: layer's thickness); 0: the paper's sharp <-g>
    smoothing: number(NON_NEGATIVE, (lambda x: x <= 0.1, "at most 0.1")) = 1e-6
    max_augmentations: integer(from_to(1, 1000)) = 20
    mu: number(NON_NEGATIVE, (lambda x: x <= 1e3, "at most 1000")) = 0.0
    eps_t: _penalty("0 (automatic: min(10 G / h, eps_n))") = 0.0
    #: false: the pair starts switched off (a phase switches it on: phase[k].contact.<name>.active)
    active: Boolean = True

    @validator("name")
    def non_empty_name(cls, name):
        if not name:
            raise Invalid("expected a non-empty name (it names the CSV columns)")
        return name

    @classmethod
    def unknown_key(cls, key):
        kinds = [kind for kind, model in CONTACT_KINDS.items() if key in model.__fields__]
        if kinds:
            return f"applies to obstacle = {choices(kinds)} only (this contact's obstacle is {cls.KIND!r})"
        return super().unknown_key(key)


class RigidContact(Contact):
    """A rigid obstacle, moved by λ × motion (with [[phase]]: moved by the phases)."""

    motion: vector(COORDINATES) = [0.0, 0.0, 0.0]
    #: "auto": nodal, except on 6-node triangles (quadratic tetrahedra), whose nodal weights do not
    #: pass the patch test (docs/method.md §3.4): Gauss points there
    #: "facet": one pressure per slave facet, that of the facet's mean gap over its Gauss points
    #: (docs/method.md §3.4), frictionless
    integration: string(one_of(("auto", "nodal", "gauss", "facet"),
                               '"auto", "nodal" (the paper: a point per slave node), "gauss" (the Gauss '
                               'points of the slave facets) or "facet" (a pressure per slave facet, '
                               'frictionless)')) = "auto"

    @root_validator(skip_on_failure=True)
    def facet_integration_is_frictionless(cls, values):
        if values.get("integration") == "facet" and values.get("mu", 0.0) > 0:
            raise Invalid('integration = "facet" is frictionless (a facet\'s mean gap has no slip of its own): '
                          'mu = 0, or integration = "nodal" or "gauss" for friction', "integration")
        return values


def rotation_pivot(entry):
    """(axis, point) a [[contact]] entry (a plain dict) is rotated about by
    the phases: rotation_axis, or the cylinder's own axis; rotation_point, or
    the sphere's center, or the cylinder's or plane's point (None where the
    entry has neither)."""
    axis = entry["rotation_axis"] if any(entry.get("rotation_axis") or ()) else entry.get("axis")
    point = entry.get("rotation_point")
    if point is None:
        point = entry.get("center", entry.get("point"))
    return axis, point


class TurningContact(RigidContact):
    """A rigid obstacle the phases may also rotate, about rotation_axis
    through rotation_point (the point moves with the translation)."""

    #: [0, 0, 0]: the cylinder's own axis; the pivot by default the cylinder's point, the sphere's
    #: center, the plane's point
    rotation_axis: vector(COORDINATES) = [0.0, 0.0, 0.0]
    rotation_point: Optional[vector(COORDINATES)] = None

    def pivot(self):
        """(axis, point) the phases rotate the obstacle about (:func:`rotation_pivot`)."""
        return rotation_pivot(self.dict())


class PlaneContact(TurningContact):
    """The half-space behind the plane through point, normal pointing out of it."""

    KIND: ClassVar[str] = "plane"
    obstacle: Literal["plane"]
    point: vector(COORDINATES) = [0.0, 0.0, 0.0]
    normal: vector(NON_ZERO_VECTOR) = [0.0, 0.0, 1.0]


class BoxContact(RigidContact):
    """The axis-aligned box from lo to hi."""

    KIND: ClassVar[str] = "box"
    obstacle: Literal["box"]
    lo: vector(COORDINATES) = [0.0, 0.0, 0.0]
    hi: vector(COORDINATES) = [1.0, 1.0, 1.0]
    #: its edges and corners rounded with this radius (0: sharp, the paper's punch)
    edge_radius: number(NON_NEGATIVE, LENGTH) = 0.0
    #: the rounding's profile: "circular" (quarter cylinders and eighth spheres; the curvature
    #: jumps from 0 to 1/edge_radius where a face ends) or "blended" (superellipses offset by
    #: edge_radius/2; the curvature rises continuously from 0, at most about 1.43/edge_radius)
    edge_profile: Literal["circular", "blended"] = "circular"

    @root_validator(skip_on_failure=True)
    def sides_that_stay_positive(cls, values):
        """lo < hi, also at lo + λ motion < hi + λ motion in floating point;
        the rounding fits."""
        lo, hi, motion = values["lo"], values["hi"], values["motion"]
        if not all(l < h for l, h in zip(lo, hi)):
            raise Invalid(f"box needs lo < hi in every coordinate, found lo={lo} hi={hi}", "hi")
        shortest = min(h - l for l, h in zip(lo, hi))
        if 2 * values["edge_radius"] > (1 + 1e-12) * shortest:  # (2r = the side to round-off: a rounded slab)
            raise Invalid(f"edge_radius {values['edge_radius']:g} does not fit the box: at most half its shortest "
                          f"side ({shortest:g} from lo={lo} to hi={hi})", "edge_radius")
        reach = max(abs(v + f * m) for f in (0.0, 1.0) for corner in (lo, hi) for v, m in zip(corner, motion))
        if shortest < 1e-9 * reach:
            raise Invalid(f"box sides must be at least 1e-9 × the largest coordinate the box reaches ({reach:g}, "
                          f"with its motion), found lo={lo} hi={hi}", "hi")
        return values


class CylinderContact(TurningContact):
    """The infinite cylinder of radius about the axis through point."""

    KIND: ClassVar[str] = "cylinder"
    missing: ClassVar[dict] = {"radius": "missing: a cylinder needs a radius > 0 (its axis passes through point, "
                                         "along axis)"}
    obstacle: Literal["cylinder"]
    point: vector(COORDINATES) = [0.0, 0.0, 0.0]
    axis: vector(NON_ZERO_VECTOR) = [0.0, 1.0, 0.0]
    radius: number((lambda x: x > 0, "a radius > 0 (the cylinder's axis passes through point, along axis)"),
                   LENGTH)
    #: true: the body is inside the cylinder (a bore, the outer wall of a groove); false: outside (a die)
    inside: Boolean = False


class SphereContact(TurningContact):
    """The ball of radius about center."""

    KIND: ClassVar[str] = "sphere"
    missing: ClassVar[dict] = {"radius": "missing: a sphere needs a radius > 0 (about its center)"}
    obstacle: Literal["sphere"]
    center: vector(COORDINATES) = [0.0, 0.0, 0.0]
    radius: number((lambda x: x > 0, "a radius > 0 (the sphere's, about its center)"), LENGTH)


class SurfaceContact(Contact):
    """The slave surface against the master surfaces of a deformable body."""

    KIND: ClassVar[str] = "surface"
    missing: ClassVar[dict] = {"master": 'obstacle = "surface" needs the master surface\'s name (e.g. "punch.zmin")'}
    obstacle: Literal["surface"]
    master: string()  # a surface name, or several joined by "+"
    passes: integer(one_of((1, 2), "1 (single pass, the paper) or 2 (two-pass)")) = 1
    integration: string(one_of(("nodal", "gauss"), '"nodal" (the paper) or "gauss" (Gauss points of the slave '
                                                   'facets)')) = "nodal"
    capture: number(NON_NEGATIVE, LENGTH) = 0.0
    #: "smooth": the master's facets carry averaged nodal normals; slave points are projected along
    #: them and pressed along them (no force jump where a point crosses a facet edge; linear and
    #: quadratic facets)
    master_surface: string(one_of(("faceted", "smooth"), '"faceted" (closest point on the facets, the paper) '
                                                         'or "smooth" (along averaged nodal normals)')) = "faceted"

    @root_validator(skip_on_failure=True)
    def supported_pairing(cls, values):
        master, slave = values["master"], values["surface"]
        if not master:
            raise Invalid(cls.missing["master"], "master")
        if slave in master.split("+"):
            if master != slave:
                raise Invalid(f"self-contact takes the slave surface alone as its master (master = {slave!r}), "
                              f"found {master!r}", "master")
            if values["passes"] == 2:
                raise Invalid("self-contact is two-sided already (every node of the surface is a slave point "
                              "against the surface's other facets): passes = 1", "passes")
            if values["integration"] != "nodal":
                raise Invalid('self-contact excludes each slave node\'s own facets and their neighbours: it needs '
                              'integration = "nodal"', "integration")
            if values["mu"] > 0:
                raise Invalid("self-contact is frictionless for now (mu = 0)", "mu")
        if values["passes"] == 2 and "+" in master:
            raise Invalid("two-pass contact needs a single master surface (one name, no '+')", "passes")
        if values["mu"] > 0 and (values["passes"] == 2 or values["integration"] == "gauss"):
            raise Invalid('friction against a deformable surface needs passes = 1 and integration = "nodal"', "mu")
        return values

    def masters(self):
        """The master surface names."""
        return self.master.split("+")


CONTACT_KINDS = {model.KIND: model for model in (PlaneContact, BoxContact, CylinderContact, SphereContact, SurfaceContact)}
HIDDEN_LOCATIONS.update(model.__name__ for model in CONTACT_KINDS.values())
#: One [[contact]] entry, of the kind its obstacle names.
AnyContact = Annotated[Union[PlaneContact, BoxContact, CylinderContact, SphereContact, SurfaceContact],
                       Field(discriminator="obstacle")]
Contacts = List[AnyContact]


def contact_tables(value):
    """The [[contact]] entries, each with a known obstacle (pydantic picks
    the kind from it)."""
    entries = tables(value, "contact")
    every_key = list(dict.fromkeys(key for model in CONTACT_KINDS.values() for key in model.__fields__))
    for i, entry in enumerate(entries):
        if "obstacle" not in entry:
            unknown = [key for key in entry if key not in every_key]
            if unknown:
                close = difflib.get_close_matches(unknown[0], every_key, n=1)
                hint = f"; did you mean '{close[0]}'?" if close else f"; valid keys: {', '.join(every_key)}"
                raise Invalid(f"unknown key{hint}", (i, unknown[0]))
            raise Invalid("missing (required)", (i, "obstacle"))
        obstacle = entry["obstacle"]
        if not (isinstance(obstacle, str) and obstacle in CONTACT_KINDS):
            raise Invalid(f"expected {OBSTACLE_CHOICES}, found {describe(obstacle)}", (i, "obstacle"))
    return entries


def duplicate_names(contacts):
    """Invalid naming the first contact whose name an earlier one has."""
    names = [c.name for c in contacts]
    for i, name in enumerate(names):
        if name in names[:i]:
            raise Invalid(f"duplicate contact name {printable(repr(name), 60)}", (i, "name"))
