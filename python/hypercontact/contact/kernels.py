"""One evaluation of a contact at one iterate, over the C++ kernels.

:func:`evaluate` takes a contact's geometry, law and enforcement at the
current coordinates and makes one C++ ``evaluate_*`` call: per slave point
the pairing, projection, normal law and (with friction) return map, and each
closed point's element residual and tangent. The :class:`Evaluation`'s
``state`` (per point: gap, pressure, pairing, stick/slip, traction, slip,
dissipation; totals: force, closed points) is what the Newton monitor, the
Uzawa update, the commit and the results read; :meth:`Evaluation.add_residual`
and :meth:`Evaluation.add_tangent` insert the stored elements (C++
``add_residual`` / ``add_tangent``). This is the only module that calls the
contact kernels.
"""
from types import SimpleNamespace

import numpy as np

from .. import _cpp

#: Friction state of a slave point (the C++ StickSlip values).
OPEN, STICK, SLIP = 0, 1, 2

SURFACE_ARRAYS = ("facet", "feature", "status", "xi", "gap", "pressure", "normal")
FRICTION_ARRAYS = ("traction", "slip_increment", "dissipation", "state")


def state_of(evaluation, names):
    """The arrays and totals of a C++ state as numpy, once; ``normal_force`` is
    the normal part of ``force`` (all of it without friction)."""
    out = {k: np.asarray(getattr(evaluation, k)) for k in names}
    force = np.asarray(evaluation.force, dtype=float)
    normal = np.asarray(getattr(evaluation, "normal_force", force), dtype=float)
    return SimpleNamespace(**out, force=force, normal_force=normal, num_closed=int(evaluation.num_closed))


def surface_arrays(evaluation, frictional):
    """The state of a surface evaluation."""
    return state_of(evaluation, SURFACE_ARRAYS + (FRICTION_ARRAYS if frictional else ()))


class Evaluation:
    """A contact at one iterate: ``state``, and the assembly of its residual and tangent."""

    def __init__(self, evaluation, names, x):
        self._evaluation, self.x = evaluation, x
        self.state = state_of(evaluation, names)

    def add_residual(self, b):
        """Into the process-local array (rigid obstacles) or the global Vec (surfaces)."""
        _cpp.add_residual(self._evaluation, b)

    def add_tangent(self, A):
        _cpp.add_tangent(self._evaluation, A)


def _rigid(geometry, law, multipliers, eps_n, smoothing, x):
    weights = geometry.kernel_weights  # facet integration: x, kernel_area and the weights are the Gauss points'
    contact = _cpp.RigidContactInput(obstacle=geometry.obstacle, x=x, area=geometry.kernel_area,
                                     dofs=geometry.dofs, eps_n=eps_n, multipliers=multipliers, smoothing=smoothing,
                                     point_weights=weights if weights is not None else np.zeros((0, 0)),
                                     points_per_facet=geometry.points_per_facet)
    if not law.frictional:
        return Evaluation(_cpp.evaluate_rigid_contact(contact), ("gap", "pressure"), x)
    h = law.history
    friction = _cpp.RigidFrictionInput(contact=contact, xi_old=h.anchors(), t_old=h.traction,
                                       eps_t=law.eps_t, mu=law.mu)
    return Evaluation(_cpp.evaluate_rigid_friction(friction), ("gap", "pressure") + FRICTION_ARRAYS, x)


def _surface(geometry, law, multipliers, eps_n, smoothing, x):
    g = geometry
    offsets, candidates = g.candidates
    contact = _cpp.SurfaceContactInput(
        x=x, point_nodes=g.point_nodes, point_weights=g.point_weights, point_area=g.point_area, facets=g.facets,
        edge_neighbour=g.edge_neighbour, offsets=offsets, candidates=candidates, dofs=g.dofs, eps_n=eps_n,
        multipliers=multipliers, smoothing=smoothing, smooth_master=g.smooth)
    if not law.frictional:
        return Evaluation(_cpp.evaluate_surface_contact(contact), SURFACE_ARRAYS, x)
    h = law.history
    friction = _cpp.SurfaceFrictionInput(contact=contact, old_facet=h.facet, xi_old=h.xi, t_old=h.traction,
                                         eps_t=law.eps_t, mu=law.mu)
    return Evaluation(_cpp.evaluate_surface_friction(friction), SURFACE_ARRAYS + FRICTION_ARRAYS, x)


def evaluate(geometry, law, multipliers, eps_n, smoothing, x):
    """The :class:`Evaluation` of a contact at coordinates x (its geometry's layout)."""
    return (_rigid if geometry.assembly == "local" else _surface)(geometry, law, multipliers, eps_n, smoothing, x)
