"""Volume formulations: residual and tangent forms from a material law ψ(F).

Total-Lagrangian: Π(u) = ∫_Ω0 ψ(F) dV, F = I + ∇u. The residual is the
Gâteaux derivative of Π, the tangent its second derivative, both by UFL, so
the tangent is exact by construction.

The quadrature degree is always explicit: UFL's estimate for ψ with
J^(-2/3) is so high that a small hexahedral mesh would take minutes per
Newton step (docs/design.md §6.3). Degree 2 on trilinear hexahedra is the
2×2×2 Gauss rule.
"""
import math

import ufl

from .materials import volumetric_penalty


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


def selective_reduced_forms(u, psi_iso, params, K, quadrature_degree, dx=None, volumetric="quadratic"):
    """Selective reduced integration: the isochoric energy with the full rule,
    the volumetric energy Ψ0(J) (materials.VOLUMETRIC; the paper's
    K/2 (J − 1)² by default) with one point per hexahedron (the
    constant-pressure mode only), which removes volumetric locking of
    trilinear hexahedra as K grows. ``psi_iso(F, **params)`` is the
    isochoric part of the law.

    Caution (measured on the inflated sphere, docs/verification.md §5): past
    the limit point this formulation admits a spurious aspherical bifurcation
    that the plain formulation does not show.
    """
    dx_full = (dx or ufl.dx)(metadata={"quadrature_degree": int(quadrature_degree)})
    dx_one = (dx or ufl.dx)(metadata={"quadrature_degree": 1})
    return _variational_forms(
        u, lambda F: psi_iso(F, **params) * dx_full + volumetric_penalty(ufl.det(F), K, volumetric) * dx_one)


def _log_quadratic_conjugate(p, K):
    """Ψ0*(p) = sup_J p (J − 1) − K/4 (J² − 1 − 2 ln J), at J = q + √(q² + 1), q = p/K."""
    q = p / K
    J = q + ufl.sqrt(q**2 + 1.0)
    return p * (J - 1.0) - 0.25 * K * (J**2 - 1.0 - 2.0 * ufl.ln(J))


#: The mixed formulation of each volumetric energy: Π = ψ_iso + p G(J) − Ψ0*(p),
#: as (G, J G'(J), Ψ0*) with Ψ0* the conjugate of K/2 G² = Ψ0, so that
#: eliminating p gives back ψ_iso + Ψ0(J). The first Piola stress of the
#: pressure is p J G'(J) F⁻ᵀ.
MIXED_COUPLING = {
    "quadratic": (lambda J: J - 1.0, lambda J: J, lambda p, K: 0.5 / K * p**2),
    "log": (ufl.ln, lambda J: 1.0, lambda p, K: 0.5 / K * p**2),
    "log_quadratic": (lambda J: J - 1.0, lambda J: J, _log_quadratic_conjugate),
}


def mixed_coupling(K, volumetric):
    """(G, J G'(J), Ψ0*) of MIXED_COUPLING; K = inf: the constraint J = 1
    whatever the volumetric energy (Ψ0* = 0, G = J − 1)."""
    if math.isinf(K):
        return MIXED_COUPLING["quadratic"][:2] + (lambda p, K: 0.0 * p**2,)
    return MIXED_COUPLING[volumetric]


def mixed_pressure_stress(F, p, K, volumetric="quadratic"):
    """The first Piola stress p J G'(J) F⁻ᵀ of the pressure unknown p."""
    return p * mixed_coupling(K, volumetric)[1](ufl.det(F)) * ufl.inv(F).T


def mixed_up_forms(w, psi_iso, params, K, quadrature_degree, volumetric="quadratic"):
    """Mixed displacement–pressure formulation (perturbed Lagrangian) on a
    stable pair, Taylor–Hood Q2–Q1: w = (u, p),

        Π(u, p) = ∫ ψ_iso(F) + p G(J) − Ψ0*(p) dV,

    for the paper's volumetric energy G = J − 1, Ψ0* = p²/(2K)
    (MIXED_COUPLING for the others). Eliminating p (p = K (J − 1)) gives
    back ψ_iso + K/2 (J − 1)², the penalty law; K = inf gives the
    incompressible limit J = 1 with p its Lagrange multiplier. The tangent
    is a saddle-point matrix (a direct solver handles it).
    """
    W = w.function_space
    u, p = ufl.split(w)
    F = ufl.variable(ufl.Identity(len(u)) + ufl.grad(u))
    G, _, conjugate = mixed_coupling(K, volumetric)
    dx = ufl.dx(metadata={"quadrature_degree": int(quadrature_degree)})
    energy = (psi_iso(F, **params) + p * G(ufl.det(F)) - conjugate(p, K)) * dx
    R = ufl.derivative(energy, w, ufl.TestFunction(W))
    return R, ufl.derivative(R, w, ufl.TrialFunction(W))
