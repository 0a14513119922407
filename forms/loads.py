"""External loads as residual contributions (R = δΠ_int − δW_ext), each
linear in its value (a number, or a Constant the load path sets).

Follower pressure p on a surface of the deformed body: the traction in the
current configuration is t = −p n (p > 0 pushes against the body's outward
normal n). Pulled back with Nanson's formula n da = J F⁻ᵀ N dA, the residual
term is ∫_Γ0 p J F⁻ᵀ N · v dA. It depends on u, so its derivative (by UFL)
adds a non-symmetric load-stiffness to the tangent.
"""
import ufl


def follower_pressure(u, v, p, ds):
    """Residual term of a follower pressure p (scalar or UFL expression) on ds."""
    dim = len(u)
    F = ufl.Identity(dim) + ufl.grad(u)
    N = ufl.FacetNormal(ds.ufl_domain())
    return p * ufl.det(F) * ufl.dot(ufl.inv(F).T * N, v) * ds


def dead_load(v, value, measure):
    """Residual term of a dead load: a traction per unit reference area (on a
    facet measure) or a body force per unit reference volume (on dx), of
    fixed direction and size: −∫ value · v."""
    if not isinstance(value, ufl.core.expr.Expr):
        value = ufl.as_vector([float(c) for c in value])
    return -ufl.dot(value, v) * measure
