"""The scene's contact entries → :class:`~.pair.Contact` objects.

Values derived from the scene — the automatic penalty ε_N, the automatic gap
tolerance of the augmented Lagrangian, the smoothing band δ — are returned in
:class:`ContactSettings` beside the contacts; the scene is not changed."""
from dataclasses import dataclass

import numpy as np

from .. import _dolfinx as dfx
from . import penalty
from .kernels import evaluate
from .enforcement import AugmentedLagrangian, Penalty
from .law import Coulomb, Frictionless
from .pair import Contact
from .rigid import RigidFrictionHistory, RigidObstacle
from .surface import SurfaceFrictionHistory, SurfacePairing


@dataclass(frozen=True)
class ContactSettings:
    """What a contact entry became: its penalties, gap tolerance (augmented
    Lagrangian, else None) and smoothing band δ, and how ε_N was found."""

    name: str
    eps_n: float
    eps_t: float
    gap_tolerance: float | None
    smoothing: float
    penalty_note: str | None


def _penalty(entry, slave_tag, material_of, V, facet_tags):
    """(ε_N, note): the scene's ε_N, or penalty_factor × M / h when it is 0 (penalty.py)
    with the material ``material_of(slave surface)``."""
    if entry["eps_n"] != 0:
        return float(entry["eps_n"]), None
    material = material_of(entry["surface"])
    eps, M, h = penalty.automatic_penalty(entry["penalty_factor"], material["law"], material["parameters"],
                                          V, facet_tags, slave_tag)
    return eps, f"{entry['name']}: ε_N = {eps:.4g} = {entry['penalty_factor']:g} × M {M:.4g} / h {h:.4g}"


def _tangential_penalty(entry, slave_tag, material_of, V, facet_tags, eps_n, mu_max):
    """(ε_T, note): the scene's ε_T, or min(10 G / h, ε_N) when it is 0 and the contact has friction
    somewhere on its path (penalty.py); ε_N for a law without a known small-strain shear modulus."""
    if entry["eps_t"] != 0:
        return float(entry["eps_t"]), None
    if mu_max == 0:
        return eps_n, None
    material = material_of(entry["surface"])
    try:
        eps, G, h = penalty.automatic_tangential_penalty(material["law"], material["parameters"], V,
                                                         facet_tags, slave_tag)
    except ValueError:
        return eps_n, f"{entry['name']}: ε_T = ε_N (no small-strain shear modulus for this law: set eps_t)"
    if eps >= eps_n:
        return eps_n, f"{entry['name']}: ε_T = ε_N = {eps_n:.4g} (≤ {penalty.TANGENTIAL_FACTOR:g} × G / h)"
    return eps, f"{entry['name']}: ε_T = {eps:.4g} = {penalty.TANGENTIAL_FACTOR:g} × G {G:.4g} / h {h:.4g}"


def _gap_tolerance(entry, V, facet_tags, slave_tags):
    """The augmented Lagrangian's tolerance: the scene's, or 1e-3 of the first element layer."""
    if entry["enforcement"] != "augmented_lagrangian":
        return None
    if entry["gap_tolerance"] > 0:
        return float(entry["gap_tolerance"])
    return 1e-3 * min(penalty.layer_thickness(V, facet_tags, t) for t in slave_tags)


def _enforcement(settings, entry, num_points):
    if settings.gap_tolerance is None:
        return Penalty(num_points)
    return AugmentedLagrangian(num_points, settings.gap_tolerance, entry["max_augmentations"])


def _surface_law(entry, settings, geometry, comm, mu_max):
    if mu_max == 0:
        return Frictionless()
    if geometry.nodes is None:
        raise ValueError(f"contact {settings.name!r}: friction against a surface needs nodal integration")
    law = Coulomb(entry["mu"], settings.eps_t, SurfaceFrictionHistory(geometry), comm)
    # the history before any load: where each point is paired in the reference configuration
    geometry.candidates = geometry.search(geometry.X)
    law.history.store(evaluate(geometry, law, np.zeros(0), settings.eps_n, settings.smoothing, geometry.X).state)
    geometry.candidates = None
    return law


def build_contacts(scene, V, facet_tags, tag_of, constrained, material_of, path, u_dofs=None, u_global=None):
    """(contacts, settings) of the scene's [[contact]] entries, in order (a
    two-pass surface contact gives two, the second named <name>_pass2).
    ``tag_of(surface, key)``: the facet tag of a named surface (raising a
    SceneError naming ``key``); ``material_of(surface)``: the material entry
    of the body a slave surface belongs to (for the automatic ε_N); ``path``:
    the scene's :class:`~hypercontact.scene.path.LoadPath` (a contact whose μ
    is > 0 anywhere on it gets the Coulomb law); ``u_dofs``, ``u_global``:
    where V's process-local dofs sit in the unknown, locally and globally
    (mixed formulation), else None."""
    contacts, settings = [], []
    for i, entry in enumerate(scene["contact"]):
        slave = tag_of(entry["surface"], f"contact[{i}].surface")
        _refuse_interior_facets(V.mesh, facet_tags, slave, entry["surface"], f"contact[{i}].surface")
        eps_n, note = _penalty(entry, slave, material_of, V, facet_tags)
        if entry["obstacle"] != "surface":
            pairs = [(entry["name"], [slave], None)]
        else:
            masters = [tag_of(m, f"contact[{i}].master") for m in entry["master"].split("+")]
            for name, tag in zip(entry["master"].split("+"), masters):
                _refuse_interior_facets(V.mesh, facet_tags, tag, name, f"contact[{i}].master")
            pairs = [(entry["name"], [slave], masters)]
            if entry["passes"] == 2:  # two-pass: each surface is slave once (frictionless)
                pairs.append((f"{entry['name']}_pass2", masters, [slave]))
        gap_tolerance = _gap_tolerance(entry, V, facet_tags, [slave])
        eps_t, note_t = _tangential_penalty(entry, slave, material_of, V, facet_tags, eps_n, path.max_mu(i))
        note = "; ".join(x for x in (note, note_t) if x) or None
        for k, (name, slaves, masters) in enumerate(pairs):
            s = ContactSettings(name, eps_n, eps_t, gap_tolerance,
                                penalty.smoothing_band(entry, V, facet_tags, slaves), note if k == 0 else None)
            contact = _make(entry, s, V, facet_tags, slaves, masters, constrained, k > 0, path.max_mu(i), u_dofs,
                            u_global)
            contact.index = i
            contacts.append(contact)
            settings.append(s)
    return contacts, settings


def _refuse_interior_facets(mesh, facet_tags, tag, name, key):
    """A contact surface is a boundary: facets between two cells (a mesh file whose surface group also
    holds internal faces) would become slave points that never touch and weights that are not the
    surface's."""
    inside = dfx.interior_facets_with_tag(mesh, facet_tags, tag)
    if inside:
        from ..scene.errors import SceneError

        raise SceneError(f"{key}: surface {name!r} has {inside} facets inside the body (between two cells); "
                         "a contact surface must be on the body's boundary: take the internal faces out of its "
                         "physical group")


def _make(entry, s, V, facet_tags, slaves, masters, constrained, second, mu_max, u_dofs, u_global):
    comm = V.mesh.comm
    if masters is None:
        geometry = RigidObstacle(entry, V, facet_tags, slaves[0], constrained, u_dofs)
        law = (Coulomb(entry["mu"], s.eps_t, RigidFrictionHistory(geometry), comm) if mu_max > 0
               else Frictionless())
    else:
        smooth = entry.get("master_surface", "faceted") == "smooth"
        geometry = SurfacePairing(V, facet_tags, slaves, masters, constrained, entry["integration"],
                                  entry["capture"], s.name, u_dofs, u_global, smooth=smooth)
        law = Frictionless() if second else _surface_law(entry, s, geometry, comm, mu_max)
    enforcement = _enforcement(s, entry, len(geometry.point_area))
    return Contact(s.name, geometry, law, enforcement, s.eps_n, s.smoothing, entry)
