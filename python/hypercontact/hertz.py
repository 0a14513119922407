"""Hertz's solution for a sphere on a half-space, and the measurements of an
FE run it is compared with (used by ``hypercontact study`` with
``reference = "hertz:a" | "hertz:p0" | "hertz:delta"`` and by bench/hertz.py).

Closed form (small strain, frictionless, a ≪ R), sphere of radius R pressed
by the force F on a half-space:

    1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2        (a rigid body: its term is 0)
    a = (3 F R / (4 E*))^(1/3),  p0 = 3 F / (2 π a²),  δ = a² / R

with a the contact radius, p0 the peak pressure and δ the approach of
distant points of the two bodies.

The FE side (``measure``): the slave points' current radial distance r from
the sphere's axis and their pressure p; the Hertz profile
p = p0 √(1 − r²/a²) fitted to the closed points by least squares on
p² = p0² − (p0²/a²) r² (linear in r²) gives ``a_fit`` and ``p0_fit``; F is
the contact force times the scene's symmetry factor; the FE approach is the
change of distance, along the axis, between the point of the sphere's body
farthest from the contact (the centre of a hemisphere's flat face) and the
master body's point on the axis farthest from the contact.
"""
import math

import numpy as np
from mpi4py import MPI

from .scene import SceneError


def closed_form(F, R, E_star):
    """(a, p0, δ) of Hertz's solution for the force F, sphere radius R and
    contact modulus E*."""
    if not (F > 0 and R > 0 and E_star > 0):
        raise ValueError(f"Hertz: needs F, R, E* > 0, found F = {F}, R = {R}, E* = {E_star}")
    a = (3.0 * F * R / (4.0 * E_star)) ** (1.0 / 3.0)
    return a, 3.0 * F / (2.0 * math.pi * a * a), a * a / R


def contact_modulus(*bodies):
    """E* from (E, ν) pairs (None for a rigid body)."""
    compliance = sum((1.0 - nu * nu) / E for E, nu in (b for b in bodies if b is not None))
    if compliance <= 0:
        raise ValueError("Hertz: at least one body must be deformable")
    return 1.0 / compliance


def young_poisson(material):
    """(E, ν) at small strain of a scene material of a built-in law."""
    from .contact.penalty import small_strain_moduli

    law, params = material["law"], material["parameters"]
    try:
        K, mu = small_strain_moduli(law, params)
    except (ValueError, KeyError):
        raise SceneError(f"reference 'hertz': no small-strain moduli for the material law {law!r} "
                         "(needs a built-in law with K: neo_hookean, mooney_rivlin)") from None
    return 9.0 * K * mu / (3.0 * K + mu), (3.0 * K - 2.0 * mu) / (2.0 * (3.0 * K + mu))


def geometry(scene):
    """What Hertz needs from a scene: dict(contact index, R, centre, E*,
    symmetry factor, sphere body name, master body name or None). The sphere
    is a body with builder = "hemisphere" whose surface is the slave of a
    contact; its partner (the master surface's body, or a rigid plane/box)
    is the half-space."""
    bodies = {b["name"]: b for b in scene["body"]}
    for i, c in enumerate(scene["contact"]):
        owner = c["surface"].split(".", 1)[0] if "." in c["surface"] else None
        if owner in bodies and bodies[owner]["builder"] == "hemisphere":
            ball = bodies[owner]
            break
    else:
        raise SceneError("reference 'hertz': the scene has no contact whose slave surface belongs to a body "
                         "with builder = \"hemisphere\" (the sphere of Hertz's problem)")
    if c["mu"] > 0:
        raise SceneError(f"reference 'hertz': contact {c['name']!r} has friction (mu = {c['mu']}); "
                         "Hertz's solution is frictionless")
    moduli = [young_poisson(ball["material"])]
    master = None
    if c["obstacle"] == "surface":
        master = c["master"].split(".", 1)[0] if "." in c["master"] else None
        moduli.append(young_poisson(bodies[master]["material"] if master else scene["material"]))
    return dict(contact=i, name=c["name"], obstacle=c["obstacle"], R=float(ball["radius"]), centre=np.asarray(ball["origin"], float),
                E_star=contact_modulus(*moduli), symmetry_factor=float(scene["output"]["symmetry_factor"]),
                ball=ball["name"], master=master)


def slave_points(contact, u):
    """Gathered on every rank: reference and current positions, gap and
    pressure of the contact's slave points (nodes with nodal integration,
    Gauss points with Gauss-point integration)."""
    state = contact.evaluate(u)
    X, x = contact.point_coordinates(u)  # collective for surfaces
    parts = contact.comm.allgather((X, x, np.asarray(state.gap), np.asarray(state.pressure)))
    return tuple(np.concatenate([q[i] for q in parts]) for i in range(4))


def vertical_tractions(sim, name):
    """Gathered on every rank: the reference and current coordinates of the first pass's
    slave points of contact ``name`` (nodal integration) and the vertical traction on each,
    t_i = −R_z,i / A_i: the z component of the force all passes of the contact put on the
    slave node (its own penalty force and, two-pass, the second pass's reactions on the
    facets it belongs to) over the node's reference area. Single pass, t_i = p_i n_z at a
    closed node; with two passes it is the traction of both, which no pass's pressure is
    alone. Collective."""
    from petsc4py import PETSc

    passes = [c for c in sim.contacts if c.name == name or c.name.startswith(name + "_pass")]
    first = passes[0]
    g = first.geometry
    if g.nodes is None:
        raise ValueError(f"contact {name!r}: tractions at slave nodes need nodal integration")
    b = sim.problem.b.duplicate()
    b.zeroEntries()
    for c in passes:
        c.prepare(sim.u)
        c.add_residual(b)
    b.assemblyBegin()
    b.assemblyEnd()
    scatter, whole = PETSc.Scatter.toAll(b)
    scatter.scatter(b, whole, PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
    values = whole.getArray(readonly=True)
    dof = g.dofs[g.point_nodes[:, 0], 2]
    force_z = np.where(dof >= 0, -values[np.maximum(dof, 0)], np.nan)
    X, x = first.point_coordinates(sim.u)
    parts = first.comm.allgather((X, x, force_z / g.point_area))
    for obj in (b, whole, scatter):
        obj.destroy()
    return tuple(np.concatenate([q[i] for q in parts]) for i in range(3))


def fit_profile(r, p, closed):
    """(a_fit, p0_fit): least squares of p² = p0² − (p0²/a²) r² over the
    closed points."""
    r, p = np.asarray(r)[closed], np.asarray(p)[closed]
    if len(r) < 2 or np.ptp(r) == 0:
        return float("nan"), float("nan")
    A = np.stack([np.ones(len(r)), -r ** 2], axis=1)
    c0, c1 = np.linalg.lstsq(A, p ** 2, rcond=None)[0]
    if not (c0 > 0 and c1 > 0):
        return float("nan"), float("nan")
    return float(np.sqrt(c0 / c1)), float(np.sqrt(c0))


def _axis_extreme(sim, centre, sign):
    """u_z and z of the node nearest the axis through centre, at the extreme
    z (sign = +1: highest, −1: lowest) among the nodes within a small
    distance of the axis (every rank)."""
    from . import _dolfinx as dfx

    X = dfx.node_coordinates(sim.V)[: dfx.num_owned_nodes(sim.V)]
    d = np.hypot(X[:, 0] - centre[0], X[:, 1] - centre[1])
    dmin = sim.comm.allreduce(float(d.min()) if len(d) else math.inf, op=MPI.MIN)
    on = np.flatnonzero(d <= dmin + 1e-9 * (1.0 + abs(dmin)))
    z = sign * X[on, 2]
    best = sim.comm.allreduce(float(z.max()) if len(z) else -math.inf, op=MPI.MAX)
    mine = on[np.flatnonzero(z >= best - 1e-12 * (1.0 + abs(best)))] if len(z) else on
    uz = sim.u.x.array.reshape(-1, 3)[mine[:1], 2]
    vals = [v for v in sim.comm.allgather(uz.tolist()) for v in v]
    return vals[0], sign * best


def contact_named(sim, name):
    """The simulation's contact of that scene name (the first pass of a
    two-pass contact)."""
    for exact in (True, False):
        for c in sim.contacts:
            if (c.name == name) if exact else c.name.startswith(name):
                return c
    raise ValueError(f"no contact named {name!r} in the simulation")


def measure(sim, geo):
    """The FE quantities of a finished run: dict(F, a_fit, p0_fit, delta,
    r, p, closed) (see the module text)."""
    contact = contact_named(sim, geo["name"])
    X, x, gap, p = slave_points(contact, sim.u)
    F = geo["symmetry_factor"] * abs(float(contact.force(sim.u)[2]))
    c = geo["centre"]
    r = np.hypot(x[:, 0] - c[0], x[:, 1] - c[1])
    closed = gap < 0.0
    a_fit, p0_fit = fit_profile(r, p, closed)
    # approach: the sphere's top (centre of the flat face) against the bottom of everything on the axis
    uz_top, _ = _axis_extreme(sim, c, +1)
    if geo["master"] is None and geo["obstacle"] != "surface":  # a rigid obstacle: where it has moved
        uz_bottom = float(contact.geometry.pose.t[2])
    else:
        uz_bottom, _ = _axis_extreme(sim, c, -1)
    return dict(F=F, a_fit=a_fit, p0_fit=p0_fit, delta=uz_bottom - uz_top, r=r, p=p, closed=closed)
