"""Volume formulations: residual and tangent forms from a material law ψ(F).

Total-Lagrangian: Π(u) = ∫_Ω0 ψ(F) dV, F = I + ∇u. The residual is the
Gâteaux derivative of Π, the tangent its second derivative, both by UFL, so
the tangent is exact by construction.

The quadrature degree is always explicit: UFL's estimate for ψ with
J^(-2/3) is so high that a small hexahedral mesh would take minutes per
Newton step (see DESIGN.md). Degree 2 on trilinear hexahedra is the 2×2×2
Gauss rule.
"""
import ufl


def displacement_forms(u, psi, params, quadrature_degree):
    """Plain displacement formulation.

    Returns (R, J): the residual δΠ[v] and its tangent D(δΠ)[du] as UFL forms
    in the displacement Function ``u``.
    """
    V = u.function_space
    v = ufl.TestFunction(V)
    du = ufl.TrialFunction(V)
    dim = len(u)
    F = ufl.variable(ufl.Identity(dim) + ufl.grad(u))
    dx = ufl.dx(metadata={"quadrature_degree": int(quadrature_degree)})
    energy = psi(F, **params) * dx
    R = ufl.derivative(energy, u, v)
    J = ufl.derivative(R, u, du)
    return R, J


def selective_reduced_forms(u, psi_iso, params, K, quadrature_degree):
    """Selective reduced integration: the isochoric energy with the full rule,
    the volumetric penalty K/2 (J − 1)² with one point per hexahedron (the
    constant-pressure mode only), which removes volumetric locking of
    trilinear hexahedra as K grows.

    ``psi_iso(F, **params)`` is the isochoric part of the law.
    """
    V = u.function_space
    v = ufl.TestFunction(V)
    du = ufl.TrialFunction(V)
    dim = len(u)
    F = ufl.variable(ufl.Identity(dim) + ufl.grad(u))
    dx_full = ufl.dx(metadata={"quadrature_degree": int(quadrature_degree)})
    dx_one = ufl.dx(metadata={"quadrature_degree": 1})
    J = ufl.det(F)
    energy = psi_iso(F, **params) * dx_full + 0.5 * K * (J - 1.0) ** 2 * dx_one
    R = ufl.derivative(energy, u, v)
    return R, ufl.derivative(R, u, du)
