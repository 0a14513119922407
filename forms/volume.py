"""Volume formulations: residual and tangent forms from a material law ψ(F).

Total-Lagrangian: Π(u) = ∫_Ω0 ψ(F) dV, F = I + ∇u. The residual is the
Gâteaux derivative of Π, the tangent its second derivative, both by UFL, so
the tangent is exact by construction.

The quadrature degree is always explicit: UFL's estimate for ψ with
J^(-2/3) is so high that a small hexahedral mesh would take minutes per
Newton step (see DESIGN.md). Degree 2 on trilinear hexahedra is the 2×2×2
Gauss rule.
"""
import math

import ufl


def _variational_forms(u, energy):
    """(R, J) of the potential Π = energy(F), a UFL form built from
    F = I + ∇u: the residual δΠ[v] and its tangent D(δΠ)[du]."""
    V = u.function_space
    F = ufl.variable(ufl.Identity(len(u)) + ufl.grad(u))
    R = ufl.derivative(energy(F), u, ufl.TestFunction(V))
    return R, ufl.derivative(R, u, ufl.TrialFunction(V))


def displacement_forms(u, psi, params, quadrature_degree, dx=None):
    """Plain displacement formulation: Π = ∫ ψ(F) dV with the given rule
    (over the measure ``dx``, e.g. one body's cells, if given)."""
    dx = (dx or ufl.dx)(metadata={"quadrature_degree": int(quadrature_degree)})
    return _variational_forms(u, lambda F: psi(F, **params) * dx)


def selective_reduced_forms(u, psi_iso, params, K, quadrature_degree, dx=None):
    """Selective reduced integration: the isochoric energy with the full rule,
    the volumetric penalty K/2 (J − 1)² with one point per hexahedron (the
    constant-pressure mode only), which removes volumetric locking of
    trilinear hexahedra as K grows. ``psi_iso(F, **params)`` is the
    isochoric part of the law.

    Caution (measured on the inflated sphere, README): past the limit point
    this formulation admits a spurious aspherical bifurcation that the plain
    formulation does not show.
    """
    dx_full = (dx or ufl.dx)(metadata={"quadrature_degree": int(quadrature_degree)})
    dx_one = (dx or ufl.dx)(metadata={"quadrature_degree": 1})
    return _variational_forms(
        u, lambda F: psi_iso(F, **params) * dx_full + 0.5 * K * (ufl.det(F) - 1.0) ** 2 * dx_one)


def mixed_up_forms(w, psi_iso, params, K, quadrature_degree):
    """Mixed displacement–pressure formulation (perturbed Lagrangian) on a
    stable pair, Taylor–Hood Q2–Q1: w = (u, p),

        Π(u, p) = ∫ ψ_iso(F) + p (J − 1) − p²/(2K) dV.

    Eliminating p (p = K (J − 1)) gives back ψ_iso + K/2 (J − 1)², the
    penalty law; K = inf gives the incompressible limit J = 1 with p its
    Lagrange multiplier. The tangent is a saddle-point matrix (a direct
    solver handles it).
    """
    W = w.function_space
    u, p = ufl.split(w)
    F = ufl.variable(ufl.Identity(len(u)) + ufl.grad(u))
    J = ufl.det(F)
    compliance = 0.0 if math.isinf(K) else 1.0 / K
    dx = ufl.dx(metadata={"quadrature_degree": int(quadrature_degree)})
    energy = (psi_iso(F, **params) + p * (J - 1.0) - 0.5 * compliance * p**2) * dx
    R = ufl.derivative(energy, w, ufl.TestFunction(W))
    return R, ufl.derivative(R, w, ufl.TrialFunction(W))
