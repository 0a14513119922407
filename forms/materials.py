"""Hyperelastic material laws as plain UFL functions ψ(F, **parameters).

Each law returns the strain-energy density per unit reference volume.
Stress and tangent are never written by hand: the volume forms take
derivatives of ψ with UFL, so ψ is the single source of a material.

A user's own law is just another function with the same signature,
``psi(F, **params) -> UFL expression``, passed to the driver (see README.md).

Isochoric split (docs/method.md §1.2): F̂ = J^(-1/3) F, B̂ = F̂ F̂ᵀ, with the
invariants of B̂ computed from C = FᵀF (same values, and cheaper forms).

Volumetric part Ψ0(J), chosen by the parameter ``volumetric`` (VOLUMETRIC):
the paper's "quadratic" K/2 (J − 1)² (the default), or "log" K/2 (ln J)² or
"log_quadratic" K/4 (J² − 1 − 2 ln J), which grow without bound as J → 0 and
so resist the inversion of elements. All three have Ψ0(1) = Ψ0'(1) = 0 and
Ψ0''(1) = K: the same small-strain bulk modulus.
"""
import ufl

from .registry import LAWS as REGISTRY


def _isochoric_invariants(F):
    """Return (J, Ī1, Ī2_usual, Ī2_paper) of the isochoric part of F.

    Ī1 = J^(-2/3) tr C,
    Ī2 (usual) = ½ (Ī1² − tr(Ĉ²)),
    Ī2 (paper) = tr(Ĉ²) = J^(-4/3) tr(C²)   (the paper's definition,
                                            docs/method.md §1.2).
    """
    C = F.T * F
    J = ufl.det(F)
    Jm23 = J ** (-2.0 / 3.0)
    I1 = Jm23 * ufl.tr(C)
    trC2_hat = Jm23 ** 2 * ufl.tr(C * C)
    I2_usual = 0.5 * (I1 ** 2 - trC2_hat)
    return J, I1, I2_usual, trC2_hat


#: Volumetric energies Ψ0(J, K) by the name of the parameter ``volumetric``.
VOLUMETRIC = {
    # the paper's penalty on volume change (21); bounded as J → 0
    "quadratic": lambda J, K: 0.5 * K * (J - 1.0) ** 2,
    # quadratic in the logarithmic (Hencky) volume strain
    "log": lambda J, K: 0.5 * K * ufl.ln(J) ** 2,
    # Simo–Taylor / Ogden type; convex in J
    "log_quadratic": lambda J, K: 0.25 * K * (J**2 - 1.0 - 2.0 * ufl.ln(J)),
}


def volumetric_penalty(J, K, volumetric="quadratic"):
    """Ψ0(J) of the given kind (VOLUMETRIC); "quadratic" is the paper's K/2 (J − 1)² (21)."""
    if volumetric not in VOLUMETRIC:
        raise ValueError(f"volumetric must be one of {', '.join(map(repr, VOLUMETRIC))}, got {volumetric!r}")
    return VOLUMETRIC[volumetric](J, K)


def split_volumetric(params):
    """(isochoric parameters, K, volumetric) of a built-in law's parameters."""
    iso = {k: v for k, v in params.items() if k not in ("K", "volumetric")}
    return iso, params.get("K"), params.get("volumetric", "quadratic")


def mooney_rivlin_isochoric(F, alpha1, alpha2, i2="usual"):
    """Isochoric part of Mooney–Rivlin: α1 (Ī1 − 3) + α2 (Ī2 − 3).

    ``i2="usual"`` (default) uses Ī2 = ½(Ī1² − tr Ĉ²): small-strain shear
    modulus 2(α1 + α2). ``i2="paper"`` uses the paper's Ī2 = tr(Ĉ²):
    shear modulus 2α1 + 8α2. Both Ī2 equal 3 at rest.
    """
    J, I1, I2_usual, I2_paper = _isochoric_invariants(F)
    if i2 == "usual":
        I2 = I2_usual
    elif i2 == "paper":
        I2 = I2_paper
    else:
        raise ValueError(f"mooney_rivlin: i2 must be 'usual' or 'paper', got {i2!r}")
    return alpha1 * (I1 - 3.0) + alpha2 * (I2 - 3.0)


def mooney_rivlin(F, alpha1, alpha2, K, i2="usual", volumetric="quadratic"):
    """Mooney–Rivlin (the paper's (22), docs/method.md §1.2):
    α1 (Ī1 − 3) + α2 (Ī2 − 3) + Ψ0(J)."""
    return mooney_rivlin_isochoric(F, alpha1, alpha2, i2) + volumetric_penalty(ufl.det(F), K, volumetric)


def neo_hookean_isochoric(F, mu):
    """Isochoric part of neo-Hookean: μ/2 (Ī1 − 3)."""
    _, I1, _, _ = _isochoric_invariants(F)
    return 0.5 * mu * (I1 - 3.0)


def neo_hookean(F, mu, K, volumetric="quadratic"):
    """Neo-Hookean with the same split: μ/2 (Ī1 − 3) + Ψ0(J)."""
    return neo_hookean_isochoric(F, mu) + volumetric_penalty(ufl.det(F), K, volumetric)


def shear_modulus(law, params):
    """Small-strain shear modulus of a built-in law (used for reports); None
    for any other law."""
    if law not in REGISTRY:
        return None
    return REGISTRY[law].shear_modulus(REGISTRY[law].with_defaults(params))[0]


#: Built-in laws by scene name: function and its parameter names with defaults
#: (None = required), the parameters from the registry (forms/registry.py).
LAWS = {name: (law, dict(REGISTRY[name].parameters))
        for name, law in (("mooney_rivlin", mooney_rivlin), ("neo_hookean", neo_hookean))}

#: Isochoric parts of the built-in laws (their volumetric part is Ψ0(J),
#: split_volumetric): what the selective reduced integration and mixed
#: formulations need.
ISOCHORIC = {
    "mooney_rivlin": mooney_rivlin_isochoric,
    "neo_hookean": neo_hookean_isochoric,
}
