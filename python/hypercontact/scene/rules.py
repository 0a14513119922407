"""The rules that tie several tables of a scene together, each stated once.

Each rule takes the scene's validated tables (``s.mesh``, ``s.contact``,
...) and raises :class:`Invalid` with the key path of the first entry that
breaks it; :data:`RULES` is the order in which the Scene model applies
them (after every table is valid on its own).
"""
import difflib
import math

from pydantic import ValidationError

from .builders import BUILDERS
from .contact import RigidContact, SurfaceContact, TurningContact
from .errors import HIDDEN_LOCATIONS, Invalid, describe, first_error, printable
from .sections import Solver, Steps
from ..forms.registry import LAWS
from .path import LoadPath, check_no_jumps


def several_bodies_share_one_mesh(s):
    """[[body]] entries are built into one mesh with the [mesh] body, or are
    physical volumes of its mesh file (each claimed once); a formulation
    without a pressure unknown."""
    claimed = {}
    for i, b in enumerate(s.body):
        if s.mesh.builder == "file" and not b.volume:
            raise Invalid('missing: with mesh.builder = "file" a [[body]] is one of the file\'s physical volumes '
                          '(volume = "<its name>"); built bodies need a built-in mesh.builder ("box" or '
                          '"shell_octant")', ("body", i, "volume"))
        if s.mesh.builder != "file" and b.volume:
            raise Invalid(f'a physical volume of a mesh file, but mesh.builder is {s.mesh.builder!r}, not "file"',
                          ("body", i, "volume"))
        if b.volume in claimed:
            raise Invalid(f"volume {b.volume!r} is claimed by body[{claimed[b.volume]}] too: one body per physical "
                          "volume", ("body", i, "volume"))
        if b.volume:
            claimed[b.volume] = i
    if s.body and s.mesh.cells != "hexahedra":
        raise Invalid(f'several bodies are built of hexahedra: mesh.cells = "tetrahedra" needs a single body',
                      ("mesh", "cells"))
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


def surfaces(s):
    """Surface name → axis of its normal (None: curved) of a built mesh,
    the [[body]] surfaces prefixed with the body's name; None for a file."""
    named = BUILDERS[s.mesh.builder].surfaces_of(s.mesh.dict())
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
            if section == "bc" and entry.point is not None:
                continue
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
    """(material, its key) of the body a surface belongs to; None for a mesh
    file of several bodies (known once it is read)."""
    if s.mesh.builder == "file" and s.body:
        return None, None
    prefix = surface.split(".")[0] if "." in surface else None
    for body in s.body:
        if body.name == prefix:
            return body.material, f"body.{prefix}.material"
    return s.material, "material"


def automatic_penalty_needs_builtin_law(s):
    """ε_N = 0 takes the slave body's small-strain modulus."""
    for i, c in enumerate(s.contact):
        material, key = _material_of_surface(s, c.surface)
        if c.eps_n == 0 and material is not None and not material.builtin:
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
    if control == "load" or s.phase:  # with [[phase]]: phases_have_valid_settings
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
    """The continuation drivers move neither obstacles nor bcs and update no
    multipliers between their steps (a deformable master's pairing they search
    at every converged step, as load control does)."""
    control = s.steps.control
    if control == "load":
        return
    _continuation_contacts(s, control)
    if any(any(c.motion) for c in s.contact if isinstance(c, RigidContact)):
        raise Invalid(f"{control} control with moving obstacles is not supported yet", ("steps", "control"))
    if any(any(bc.motion) for bc in s.bc):
        raise Invalid(f"{control} control with prescribed motion is not supported yet", ("steps", "control"))



def _continuation_contacts(s, control):
    for i, c in enumerate(s.contact):
        if c.enforcement == "augmented_lagrangian":
            raise Invalid(f"the augmented Lagrangian's updates run between the Newton solves of load control; with "
                          f"{control} control use \"penalty\"", ("contact", i, "enforcement"))


# --- [[phase]] ----------------------------------------------------------------------------------
LOAD_SECTIONS = ("pressure", "traction", "body_force")


def _nested(model, data, loc):
    """``model`` parsed from ``data``, or Invalid at ``loc`` + the key that is wrong."""
    try:
        return model.parse_obj(data)
    except ValidationError as err:
        inner, exc = first_error(err.raw_errors)
        message = exc.message if isinstance(exc, Invalid) else printable(exc, 300)
        inner = tuple(p for p in inner if p not in HIDDEN_LOCATIONS) + (exc.loc if isinstance(exc, Invalid) else ())
        raise Invalid(message, loc + inner) from None


def loads_have_values(s):
    """Without [[phase]] a load is λ × its value; with [[phase]] the phases give its value."""
    for section in LOAD_SECTIONS:
        for i, load in enumerate(getattr(s, section)):
            if not s.phase and load.value is None:
                raise Invalid("missing (required)", (section, i, "value"))
            if s.phase and load.value is not None:
                raise Invalid(f"with [[phase]] the phases give a load's value (phase[k].{section}.<its name>), "
                              "found one here: remove it and give it in the phases", (section, i, "value"))


def _names(entries, section):
    """{name: index} of the named entries of a section; Invalid on a repeated name."""
    names = {}
    for i, e in enumerate(entries):
        if e.name and e.name in names:
            raise Invalid(f"duplicate {section} name {e.name!r} ({section}[{names[e.name]}] has it)",
                          (section, i, "name"))
        if e.name:
            names[e.name] = i
    return names


def _unknown_name(name, names, section, loc):
    close = difflib.get_close_matches(name, list(names), n=1)
    hint = f"; did you mean '{close[0]}'?" if close else ""
    known = ", ".join(sorted(names)) or f"none: give a [[{section}]] entry a name"
    raise Invalid(f"no [[{section}]] entry is named {printable(repr(name), 60)} (named entries: {known}){hint}",
                  loc)


def phases_name_what_exists(s):
    """Every entry a phase names exists; a phase moves only the axes a bc
    fixes and only rigid obstacles; μ changes only where friction is possible."""
    if not s.phase:
        return
    for i, bc in enumerate(s.bc):
        if any(bc.motion):
            raise Invalid("with [[phase]] the phases move the bcs (phase[k].bc.<its name>), found a motion here: "
                          "remove it and give it in the phases", ("bc", i, "motion"))
    for j, c in enumerate(s.contact):
        if isinstance(c, RigidContact) and any(c.motion):
            raise Invalid("with [[phase]] the phases move the obstacles (phase[k].contact.<its name>.motion), "
                          "found a motion here: remove it and give it in the phases", ("contact", j, "motion"))
    bcs = _names(s.bc, "bc")
    loads = {section: _names(getattr(s, section), section) for section in LOAD_SECTIONS}
    contacts = {c.name: j for j, c in enumerate(s.contact)}
    for k, ph in enumerate(s.phase):
        for name, points in ph.bc.items():
            loc = ("phase", k, "bc", name)
            if name not in bcs:
                _unknown_name(name, bcs, "bc", loc)
            bc = s.bc[bcs[name]]
            for _, v in points:
                free = [a for a, m in zip("xyz", v) if m != 0 and a not in bc.fix]
                if free:
                    raise Invalid(f"moves {', '.join(free)}, which bc {name!r} does not fix (fix = {bc.fix})", loc)
        for section in LOAD_SECTIONS:
            for name in getattr(ph, section):
                if name not in loads[section]:
                    _unknown_name(name, loads[section], section, ("phase", k, section, name))
        for name, change in ph.contact.items():
            loc = ("phase", k, "contact", name)
            if name not in contacts:
                close = difflib.get_close_matches(name, list(contacts), n=1)
                hint = f"; did you mean '{close[0]}'?" if close else ""
                raise Invalid(f"no [[contact]] is named {printable(repr(name), 60)} (contacts: "
                              f"{', '.join(contacts) or 'none'}){hint}", loc)
            j = contacts[name]
            c = s.contact[j]
            if not isinstance(c, RigidContact) and (change.motion or change.rotation):
                key = "motion" if change.motion else "rotation"
                raise Invalid(f"contact {name!r} has a deformable master (obstacle = \"surface\"): move its body "
                              "with a bc instead", loc + (key,))
            if change.rotation and any(v != 0 for _, v in change.rotation):
                if not isinstance(c, TurningContact):
                    raise Invalid("a box stays axis-aligned: it cannot rotate (use a plane or a cylinder)",
                                  loc + ("rotation",))
                axis, point = c.pivot()
                if axis is None:
                    raise Invalid(f"rotating a {c.obstacle} needs its rotation_axis (the axis turns about "
                                  "rotation_point, by default its " + ("center" if c.obstacle == "sphere" else
                                                                       "point") + ")",
                                  ("contact", j, "rotation_axis"))
            if change.mu and any(v > 0 for _, v in change.mu) and isinstance(c, SurfaceContact) and \
                    (c.passes == 2 or c.integration == "gauss"):
                raise Invalid('friction against a deformable surface needs passes = 1 and integration = "nodal"',
                              loc + ("mu",))


def phases_have_valid_settings(s):
    """A phase's [steps] and [solver] keys are those of the scene's tables
    (checked with the scene's other keys); a continuation phase (arc length,
    displacement control) drives loads only, each linearly to its end value,
    until its stop probe reaches stop_value."""
    for k, ph in enumerate(s.phase):
        steps = _nested(Steps, {**s.steps.dict(), **ph.steps}, ("phase", k, "steps"))
        _nested(Solver, {**s.solver.dict(), **ph.solver}, ("phase", k, "solver"))
        if steps.control != "load":
            _continuation_phase(s, k, ph, steps)


def _continuation_phase(s, k, ph, steps):
    control = steps.control
    here = lambda key: ("phase", k, "steps", key) if key in ph.steps else ("steps", key)  # noqa: E731
    if steps.stop_probe not in s.output.probes:
        raise Invalid(f"phase[{k}] runs under {control} control, which needs a probe of output.probes as its "
                      f"stop_probe (found {printable(repr(steps.stop_probe), 60)}; probes: "
                      f"{printable(', '.join(s.output.probes) or 'none', 200)})", here("stop_probe"))
    for key in ("bc", "contact"):
        if getattr(ph, key):
            raise Invalid(f"a phase under {control} control drives loads only: move the bcs and obstacles, "
                          f"change μ or switch contacts in a load-control phase", ("phase", k, key))
    driven = [(section, name, points) for section in LOAD_SECTIONS for name, points in getattr(ph, section).items()]
    if not driven:
        raise Invalid(f"a phase under {control} control needs a load it drives (phase[{k}].pressure, .traction "
                      "or .body_force)", here("control"))
    for section, name, points in driven:
        if len(points) != 1 or points[0][0] != 1.0:
            raise Invalid(f"a phase under {control} control drives its loads linearly: give the value at the "
                          "phase's end, not a curve", ("phase", k, section, name))
    _continuation_contacts(s, control)


def phase_curves_do_not_jump(s):
    """A curve's point at s = 0 is where its value is when the phase starts."""
    if not s.phase:
        return
    data = {"bc": [b.dict() for b in s.bc], "contact": [c.dict() for c in s.contact],
            "phase": [p.dict() for p in s.phase], "steps": s.steps.dict(), "solver": s.solver.dict(),
            **{section: [e.dict() for e in getattr(s, section)] for section in LOAD_SECTIONS}}
    check_no_jumps(LoadPath(data))


RULES = (several_bodies_share_one_mesh, split_formulations_need_builtin_laws, incompressible_needs_mixed,
         surfaces_exist, pressures_do_work,
         automatic_penalty_needs_builtin_law, probes_in_body, loads_have_values, phases_name_what_exists,
         phases_have_valid_settings, phase_curves_do_not_jump, continuation_needs_a_stop_probe_and_a_load,
         continuation_needs_fixed_contacts)
