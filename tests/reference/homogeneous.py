"""Homogeneous uniaxial compression of a Mooney–Rivlin block, in closed form.

The energy is written in principal stretches, independently of the UFL
forms (which use C = FᵀF); the nominal stresses P_i = ∂ψ/∂λ_i are taken by
complex-step differentiation, exact to rounding.

Block [0, L]³ between two frictionless rigid planes with penalty ε: the
base at z = 0 and the top plane at z = L − d. Lateral faces are free, so
P_1 = P_2 = 0 and both planes carry the pressure −P_3 with the penalty gap
g = P_3/ε each; the height is λ3 L = L − d − 2 P_3/ε.
"""
import numpy as np
from scipy.optimize import fsolve


#: The volumetric energies Ψ0(J, K) (complex-safe), written independently of forms/materials.py.
VOLUMETRIC = {
    "quadratic": lambda J, K: 0.5 * K * (J - 1) ** 2,
    "log": lambda J, K: 0.5 * K * np.log(J) ** 2,
    "log_quadratic": lambda J, K: 0.25 * K * (J**2 - 1 - 2 * np.log(J)),
}


def neo_hookean_principal(l1, l2, l3, mu, K, volumetric="quadratic"):
    J = l1 * l2 * l3
    I1 = J ** (-2.0 / 3.0) * (l1**2 + l2**2 + l3**2)
    return 0.5 * mu * (I1 - 3) + VOLUMETRIC[volumetric](J, K)


def mooney_rivlin_principal(l1, l2, l3, alpha1, alpha2, K, i2="usual"):
    J = l1 * l2 * l3
    I1 = J ** (-2.0 / 3.0) * (l1**2 + l2**2 + l3**2)
    if i2 == "usual":
        I2 = J ** (-4.0 / 3.0) * (l1**2 * l2**2 + l2**2 * l3**2 + l3**2 * l1**2)
    else:
        I2 = J ** (-4.0 / 3.0) * (l1**4 + l2**4 + l3**4)
    return alpha1 * (I1 - 3) + alpha2 * (I2 - 3) + 0.5 * K * (J - 1) ** 2


def nominal_stress(psi, stretches, i, h=1e-30):
    s = np.array(stretches, dtype=complex)
    s[i] += 1j * h
    return psi(*s).imag / h


def compressed_block(psi, L, d, eps):
    """(λ_lateral, λ3, P3) of the block pressed by d between penalty planes."""

    def equations(z):
        lat, l3 = z
        s = (lat, lat, l3)
        return [nominal_stress(psi, s, 0), l3 * L + 2 * nominal_stress(psi, s, 2) / eps - (L - d)]

    lat, l3 = fsolve(equations, [1.0, 1.0 - d / L], xtol=1e-13)
    assert np.max(np.abs(equations([lat, l3]))) < 1e-13
    return lat, l3, nominal_stress(psi, (lat, lat, l3), 2)
