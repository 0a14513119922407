"""The rules that tie several tables of a scene together, each stated once.

Each rule takes the scene's validated tables (``s.mesh``, ``s.contact``,
...) and raises :class:`Invalid` with the key path of the first entry that
breaks it; :data:`RULES` is the order in which the Scene model applies
them (after every table is valid on its own).
"""
import difflib
import math

from .builders import BUILDERS
from .contact import RigidContact, SurfaceContact
from .errors import Invalid, describe, printable
from ..forms.registry import LAWS


def several_bodies_need_one_built_mesh(s):
    """[[body]] entries are built into one mesh with the [mesh] body: no
    mesh file, and a formulation without a pressure unknown."""
    if s.body and s.mesh.builder == "file":
        raise Invalid('several bodies need a built-in mesh.builder ("box" or "shell_octant"), found "file"', "body")
    if s.body and s.discretisation.formulation == "mixed":
        raise Invalid('several bodies need the "displacement" or "sri" formulation, found "mixed"',
                      ("discretisation", "formulation"))
    names = [b.name for b in s.body]
    for i, name in enumerate(names):
        if name in names[:i]:
            raise Invalid(f"duplicate body name {name!r}", ("body", i, "name"))


def _materials(s):
    """(location, material) of the [mesh] body and of each [[body]]."""
    return [(("material",), s.material)] + [(("body", i, "material"), b.material) for i, b in enumerate(s.body)]


def split_formulations_need_builtin_laws(s):
    """sri and mixed take the isochoric part of the law apart: only the
    built-in laws have one."""
    formulation = s.discretisation.formulation
    if formulation == "displacement":
        return
    for loc, material in _materials(s):
        if not material.builtin:
            where = ("discretisation", "formulation") if loc == ("material",) else loc + ("law",)
            raise Invalid(f"{formulation!r} needs a built-in law ({', '.join(LAWS)}), found "
                          f"{describe(material.law)}", where)


def incompressible_needs_mixed(s):
    for loc, material in _materials(s):
        if material.incompressible and s.discretisation.formulation != "mixed":
            raise Invalid('K = inf (incompressible) needs discretisation.formulation = "mixed"',
                          loc + ("parameters", "K"))


def contact_needs_linear_displacements(s):
    """The contact kernels take the nodes of trilinear hexahedra as the
    displacement unknowns."""
    if not s.contact:
        return
    if s.discretisation.formulation == "mixed":
        raise Invalid('contact needs the displacement or sri formulation with degree 1, found "mixed"',
                      ("discretisation", "formulation"))
    if s.discretisation.degree != 1:
        raise Invalid(f"contact needs the displacement or sri formulation with degree 1, found "
                      f"{s.discretisation.degree}", ("discretisation", "degree"))


def surfaces(s):
    """Surface name → axis of its normal (None: curved) of a built mesh,
    the [[body]] surfaces prefixed with the body's name; None for a file."""
    named = BUILDERS[s.mesh.builder].surfaces
    if named is None:
        return None
    named = dict(named)
    for body in s.body:
        named.update({f"{body.name}.{k}": v for k, v in BUILDERS[body.builder].surfaces.items()})
    return named


def _known_surface(loc, name, named):
    if name not in named:
        close = difflib.get_close_matches(name, list(named), n=1)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        raise Invalid(f"the mesh has no surface {printable(repr(name), 60)} (it has {', '.join(sorted(named))})"
                      f"{hint}", loc)


def surfaces_exist(s):
    """Every surface a bc, load or contact names is one the builders make
    (a mesh file's are checked once it is read)."""
    named = surfaces(s)
    if named is None:
        return
    for section in ("bc", "pressure", "traction", "contact"):
        for i, entry in enumerate(getattr(s, section)):
            _known_surface((section, i, "surface"), entry.surface, named)
            if isinstance(entry, SurfaceContact):
                for master in entry.masters():
                    _known_surface((section, i, "master"), master, named)


def pressures_do_work(s):
    """One pressure per surface, and none along a direction a bc fixes."""
    named = surfaces(s)
    if named is None:
        return
    seen = {}
    for i, pressure in enumerate(s.pressure):
        name = pressure.surface
        if name in seen:
            raise Invalid(f"a second pressure on {name!r} (pressure[{seen[name]}]): give one [[pressure]] per "
                          "surface, with the sum of the values", ("pressure", i, "surface"))
        seen[name] = i
        axis = named[name]
        for j, bc in enumerate(s.bc):
            fixed = set(bc.fix)
            if bc.surface == name and (fixed == {"x", "y", "z"} or (axis is not None and "xyz"[axis] in fixed)):
                raise Invalid(f"the pressure on {name!r} acts along a direction that bc[{j}] fixes ({bc.fix}): it "
                              "would do no work", ("pressure", i, "surface"))


def _material_of_surface(s, surface):
    """(material, its key) of the body a surface belongs to."""
    prefix = surface.split(".")[0] if "." in surface else None
    for body in s.body:
        if body.name == prefix:
            return body.material, f"body.{prefix}.material"
    return s.material, "material"


def automatic_penalty_needs_builtin_law(s):
    """ε_N = 0 takes the slave body's small-strain modulus."""
    for i, c in enumerate(s.contact):
        material, key = _material_of_surface(s, c.surface)
        if c.eps_n == 0 and not material.builtin:
            raise Invalid(f"0 (automatic penalty) needs the slave body's small-strain modulus, but its law "
                          f"({describe(material.law)}, {key}) is not built in: give eps_n", ("contact", i, "eps_n"))


def probes_in_body(s):
    """A probe of a single built box or shell lies in the body (whether a
    mesh node is there is known once the mesh is built)."""
    if s.body:
        return
    mesh = s.mesh
    for name, point in s.output.probes.items():
        loc = ("output", "probes", name)
        if mesh.builder == "box":
            lo, size = mesh.origin, mesh.size
            tol = 1e-6 * max(size)
            if any(not (l - tol <= p <= l + w + tol) for p, l, w in zip(point, lo, size)):
                hi = [l + w for l, w in zip(lo, size)]
                raise Invalid(f"{point} is outside the body, the box from {lo} to {hi} (mesh.origin, mesh.size)",
                              loc)
        elif mesh.builder == "shell_octant":
            r, t = mesh.inner_radius, mesh.thickness
            tol = 1e-6 * (r + t)
            radius = math.sqrt(sum(p * p for p in point))
            if min(point) < -tol or not (r - tol <= radius <= r + t + tol):
                raise Invalid(f"{point} is outside the body, the octant x, y, z >= 0 of the shell {r:g} <= |x| <= "
                              f"{r + t:g} (mesh.inner_radius, mesh.thickness)", loc)


def continuation_needs_a_stop_probe_and_a_load(s):
    """Arc-length and displacement control follow the load λ × (pressures,
    tractions, body forces) until a probe reaches stop_value."""
    control, probes = s.steps.control, s.output.probes
    if control == "load":
        return
    if s.steps.stop_probe not in probes:
        raise Invalid(f"{control} control needs a probe of output.probes (found "
                      f"{printable(repr(s.steps.stop_probe), 60)}; probes: "
                      f"{printable(', '.join(probes) or 'none', 200)})", ("steps", "stop_probe"))
    loads = ([p.value != 0 for p in s.pressure] + [any(t.value) for t in s.traction]
             + [any(b.value) for b in s.body_force])
    if not loads:
        raise Invalid(f"{control} control needs a load: a [[pressure]], [[traction]] or [[body_force]] entry",
                      ("steps", "control"))
    if not any(loads):
        first = next(section for section in ("pressure", "traction", "body_force") if getattr(s, section))
        raise Invalid(f"{control} control needs a non-zero load, found only zero loads", (first, 0, "value"))


def continuation_needs_fixed_contacts(s):
    """The continuation drivers move neither obstacles nor bcs, search no
    deformable pairing and update no multipliers between their steps."""
    control = s.steps.control
    if control == "load":
        return
    if any(any(c.motion) for c in s.contact if isinstance(c, RigidContact)):
        raise Invalid(f"{control} control with moving obstacles is not supported yet", ("steps", "control"))
    for i, c in enumerate(s.contact):
        if isinstance(c, SurfaceContact):
            raise Invalid(f"{control} control with a deformable master (obstacle = \"surface\") is not supported "
                          "yet (its contact search runs between the load steps of load control); use load control "
                          "or a rigid obstacle", ("contact", i, "obstacle"))
        if c.enforcement == "augmented_lagrangian":
            raise Invalid(f"the augmented Lagrangian's updates run between the Newton solves of load control; with "
                          f"{control} control use \"penalty\"", ("contact", i, "enforcement"))
    if any(any(bc.motion) for bc in s.bc):
        raise Invalid(f"{control} control with prescribed motion is not supported yet", ("steps", "control"))


RULES = (several_bodies_need_one_built_mesh, split_formulations_need_builtin_laws, incompressible_needs_mixed,
         contact_needs_linear_displacements, surfaces_exist, pressures_do_work,
         automatic_penalty_needs_builtin_law, probes_in_body, continuation_needs_a_stop_probe_and_a_load,
         continuation_needs_fixed_contacts)
