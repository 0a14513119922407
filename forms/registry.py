"""The built-in material laws by scene name: their parameters, the defaults
of those parameters and the values of the string ones, and the small-strain
shear modulus. Plain Python (no UFL): the scene checks a material with it
before any form exists, and :mod:`hypercontact.forms.materials` pairs each
name with the function ψ(F, **parameters) that it evaluates.
"""
from dataclasses import dataclass, field

#: The default of a parameter that has none: the scene must give it.
REQUIRED = None

#: Values of the parameter ``volumetric``, the volumetric energy Ψ0(J)
#: (materials.VOLUMETRIC): K/2 (J − 1)² (the paper's, the default),
#: K/2 (ln J)², K/4 (J² − 1 − 2 ln J).
VOLUMETRIC = ("quadratic", "log", "log_quadratic")

#: Values of Mooney–Rivlin's ``i2``: Ī2 = ½(Ī1² − tr Ĉ²) ("usual") or the
#: paper's Ī2 = tr Ĉ² ("paper").
I2 = ("usual", "paper")


@dataclass(frozen=True)
class Law:
    """One built-in law: ``parameters`` maps each parameter to its default
    (REQUIRED: none), ``choices`` maps the string parameters to their values."""

    name: str
    parameters: dict
    choices: dict = field(default_factory=dict)

    def with_defaults(self, params):
        """``params`` with every missing optional parameter at its default."""
        return {**params, **{k: v for k, v in self.parameters.items() if v is not REQUIRED and k not in params}}

    def shear_modulus(self, params):
        """(μ0, formula): the small-strain shear modulus of ``params`` (all
        parameters given) and how it follows from them."""
        if self.name == "neo_hookean":
            return params["mu"], "mu"
        a1, a2 = params["alpha1"], params["alpha2"]
        if params["i2"] == "usual":
            return 2 * (a1 + a2), "2(alpha1 + alpha2)"
        return 2 * a1 + 8 * a2, "2 alpha1 + 8 alpha2"


LAWS = {
    # α1 (Ī1 − 3) + α2 (Ī2 − 3) + Ψ0(J): μ0 = 2(α1 + α2) with the usual Ī2, 2α1 + 8α2 with the paper's
    "mooney_rivlin": Law("mooney_rivlin",
                         {"alpha1": REQUIRED, "alpha2": REQUIRED, "K": REQUIRED, "i2": "usual",
                          "volumetric": "quadratic"},
                         {"i2": I2, "volumetric": VOLUMETRIC}),
    # μ/2 (Ī1 − 3) + Ψ0(J): μ0 = μ
    "neo_hookean": Law("neo_hookean", {"mu": REQUIRED, "K": REQUIRED, "volumetric": "quadratic"},
                       {"volumetric": VOLUMETRIC}),
}

