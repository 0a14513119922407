"""The contact patch test's measure (``hypercontact study`` with
``reference = "patch:sigma_zz" | "patch:pressure"``): under a uniform load
through a contact interface the exact solution is homogeneous, so the
quantity must be uniform; its relative spread (max − min)/|mean| is the
error (reference 0).

- ``sigma_zz``: the Cauchy stress σ_zz = (P Fᵀ / J)_zz at every cell's
  midpoint (a DG0 interpolation), over all cells of all bodies;
- ``pressure``: the contact pressure at the closed slave points (nodes with
  nodal integration, Gauss points with Gauss-point integration) of the
  scene's first contact (the first pass of a two-pass contact).
"""
import numpy as np
import ufl

from . import _dolfinx as dfx


def sigma_zz_cells(sim):
    """σ_zz at the midpoint of every owned cell (this rank's)."""
    Q = dfx.fem.FunctionSpace(sim.body.mesh, ("DG", 0))
    s = dfx.fem.Function(Q)
    F = ufl.Identity(3) + ufl.grad(sim.u)
    sigma = sim.stress(sim.u) * F.T / ufl.det(F)
    s.interpolate(dfx.fem.Expression(sigma[2, 2], Q.element.interpolation_points()))
    return np.array(s.x.array[: dfx.num_owned_cells(sim.body.mesh)])


def closed_pressures(contact, u):
    """The pressures of the closed slave points (this rank's)."""
    st = contact.evaluate(u)
    gap, p = np.asarray(st.gap), np.asarray(st.pressure)
    return np.array(p[gap < 0.0])


def values(sim, what):
    """All values (every rank) whose spread is the patch test's error."""
    if what == "sigma_zz":
        v = sigma_zz_cells(sim)
    else:
        v = closed_pressures(sim.contacts[0], sim.u)
    return np.concatenate(sim.comm.allgather(v)) if sim.comm.size > 1 else v


def spread(v):
    """(max − min) / |mean|."""
    v = np.asarray(v, float)
    if len(v) == 0:
        return float("nan")
    return float((v.max() - v.min()) / abs(v.mean()))
