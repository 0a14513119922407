"""One evaluation of a contact at one iterate, over the C++ kernels.

:func:`evaluate` takes a contact's geometry, law and enforcement at the
current coordinates and returns an :class:`Evaluation`: its ``state`` (per
slave point: gap, pressure, pairing, stick/slip, traction, slip, dissipation;
totals: force, number of closed points) is what the residual, the tangent, the
Newton monitor, the Uzawa update, the commit and the results all read. The
state is computed once — by the residual assembly when the residual is
assembled first, without assembly otherwise — and the tangent reuses the same
coordinates, history and multipliers.
"""
from types import SimpleNamespace

import numpy as np

from .. import _cpp

#: Friction state of a slave point (the C++ StickSlip values).
OPEN, STICK, SLIP = 0, 1, 2


def surface_arrays(s, frictional):
    """The arrays of a C++ surface state, as numpy, once."""
    out = {k: np.asarray(getattr(s, k)) for k in ("facet", "feature", "status", "xi", "gap", "pressure", "normal")}
    if frictional:
        out.update({k: np.asarray(getattr(s, k)) for k in ("traction", "slip_increment", "dissipation", "state")})
    force = np.asarray(s.force, dtype=float)
    normal = np.asarray(s.normal_force, dtype=float) if frictional else force
    return SimpleNamespace(**out, force=force, normal_force=normal, num_closed=int(s.num_closed))


def _rigid_arrays(normal, friction=None):
    """The rigid normal (and friction) C++ states as one, in numpy."""
    out = SimpleNamespace(gap=np.asarray(normal.gap), pressure=np.asarray(normal.pressure),
                          force=np.asarray(normal.force, dtype=float), num_closed=int(normal.num_closed))
    out.normal_force = out.force
    if friction is not None:
        for k in ("traction", "slip_increment", "dissipation", "state"):
            setattr(out, k, np.asarray(getattr(friction, k)))
        out.force = out.force + np.asarray(friction.force, dtype=float)
    return out


class Evaluation:
    """A contact at one iterate: ``state`` and the assembly of its residual and tangent."""

    def __init__(self, call, x, scratch_size):
        self._call, self.x, self._scratch_size, self._state = call, x, scratch_size, None

    @property
    def state(self):
        if self._state is None:
            self._state = self._call.evaluate(self.x, self._scratch_size)
        return self._state

    def add_residual(self, b):
        """Into the process-local array (rigid obstacles) or the global Vec (surfaces)."""
        self._state = self._call.residual(self.x, b)

    def add_tangent(self, A):
        self._call.tangent(self.x, A)


class RigidCall:
    """The rigid-obstacle kernels, normal and (with a Coulomb law) friction."""

    def __init__(self, geometry, law, multipliers, eps_n, smoothing):
        self.g, self.law, self.mult, self.eps_n, self.delta = geometry, law, multipliers, eps_n, smoothing

    def _normal(self, x, b):
        g = self.g
        return _cpp.assemble_rigid_residual(g.obstacle, x, g.area, self.eps_n, g.dofs, b, self.mult, self.delta)

    def _friction(self, x, b):
        g, h = self.g, self.law.history
        return _cpp.assemble_rigid_friction_residual(
            g.obstacle, x, g.area, self.eps_n, self.law.eps_t, self.law.mu, h.anchors(g.load_factor), h.traction,
            g.dofs, b, self.mult, self.delta)

    def residual(self, x, b):
        normal = self._normal(x, b)
        return _rigid_arrays(normal, self._friction(x, b) if self.law.frictional else None)

    def evaluate(self, x, size):
        return self.residual(x, np.zeros(size))

    def tangent(self, x, A):
        g = self.g
        _cpp.assemble_rigid_tangent(g.obstacle, x, g.area, self.eps_n, g.dofs, A, self.mult, self.delta)
        if self.law.frictional:
            h = self.law.history
            _cpp.assemble_rigid_friction_tangent(
                g.obstacle, x, g.area, self.eps_n, self.law.eps_t, self.law.mu, h.anchors(g.load_factor),
                h.traction, g.dofs, A, self.mult, self.delta)


class SurfaceCall:
    """The node-to-surface kernels, frictionless or Coulomb, at the current pairing."""

    def __init__(self, geometry, law, multipliers, eps_n, smoothing):
        self.g, self.law, self.mult, self.eps_n, self.delta = geometry, law, multipliers, eps_n, smoothing

    def _args(self, x):
        g = self.g
        offsets, cand = g.candidates
        args = (x, g.point_nodes, g.point_weights, g.point_area, g.facets, g.edge_neighbour, offsets, cand,
                self.eps_n, g.dofs)
        if self.law.frictional:
            h = self.law.history
            args += (h.facet, h.xi, h.traction, self.law.eps_t, self.law.mu)
        return args

    def residual(self, x, b):
        f = _cpp.assemble_surface_friction_residual if self.law.frictional else _cpp.assemble_surface_residual
        return surface_arrays(f(*self._args(x), b, multipliers=self.mult, smoothing=self.delta), self.law.frictional)

    def evaluate(self, x, size=None):
        f = _cpp.evaluate_surface_friction if self.law.frictional else _cpp.evaluate_surface_contact
        return surface_arrays(f(*self._args(x), multipliers=self.mult, smoothing=self.delta), self.law.frictional)

    def tangent(self, x, A):
        f = _cpp.assemble_surface_friction_tangent if self.law.frictional else _cpp.assemble_surface_tangent
        f(*self._args(x), A, multipliers=self.mult, smoothing=self.delta)


def evaluate(geometry, law, multipliers, eps_n, smoothing, x):
    """The :class:`Evaluation` of a contact at coordinates x (its geometry's layout)."""
    kind = RigidCall if geometry.assembly == "local" else SurfaceCall
    return Evaluation(kind(geometry, law, multipliers, eps_n, smoothing), x, geometry.scratch_size)
