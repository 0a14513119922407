"""One registry of the built-in laws (forms/registry.py), shared by the
scene and forms/materials.py: it matches what materials.py evaluates."""
import inspect

import pytest
import ufl

from hypercontact import scene
from hypercontact.forms import materials, registry

PARAMETERS = {"mooney_rivlin": {"alpha1": 0.3, "alpha2": 0.1, "K": 5.0},
              "neo_hookean": {"mu": 0.7, "K": 5.0}}


def test_every_law_of_the_registry_is_evaluated_by_materials():
    assert set(registry.LAWS) == set(materials.LAWS) == set(materials.ISOCHORIC) == set(PARAMETERS)


@pytest.mark.parametrize("name", list(registry.LAWS))
def test_parameters_and_defaults_are_those_of_the_law_function(name):
    """The function's signature ψ(F, ...) is what materials.py evaluates."""
    psi, _ = materials.LAWS[name]
    _, *params = inspect.signature(psi).parameters.values()
    expected = {p.name: registry.REQUIRED if p.default is inspect.Parameter.empty else p.default for p in params}
    assert registry.LAWS[name].parameters == expected
    assert materials.LAWS[name][1] == expected


def _simple_shear_energy(name, params, gamma=1e-3):
    F = ufl.as_matrix([[1.0, gamma, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    return float(materials.LAWS[name][0](F, **params))


@pytest.mark.parametrize("name, extra", [("mooney_rivlin", {}), ("mooney_rivlin", {"i2": "paper"}),
                                         ("neo_hookean", {"volumetric": "log"})])
def test_the_shear_modulus_is_that_of_the_energy(name, extra):
    """ψ(simple shear γ) = μ0 γ²/2 + O(γ⁴): μ0 from the energy materials.py evaluates."""
    params = {**PARAMETERS[name], **extra}
    gamma = 1e-3
    measured = 2.0 * _simple_shear_energy(name, params, gamma) / gamma**2
    law = registry.LAWS[name]
    assert law.shear_modulus(law.with_defaults(params))[0] == pytest.approx(measured, rel=1e-5)


@pytest.mark.parametrize("name", list(registry.LAWS))
def test_string_parameters_take_exactly_the_registered_values(name):
    law = registry.LAWS[name]
    for key, values in law.choices.items():
        for value in values:
            _simple_shear_energy(name, {**PARAMETERS[name], key: value})
        with pytest.raises(ValueError):
            _simple_shear_energy(name, {**PARAMETERS[name], key: "other"})
    assert law.choices["volumetric"] == registry.VOLUMETRIC == tuple(materials.VOLUMETRIC)


def test_the_scene_fills_the_defaults_and_checks_the_registered_modulus():
    base = {"mesh": {"n": 2, "m": 1}}
    sc = scene.load({**base, "material": {"law": "mooney_rivlin", "parameters": {"alpha1": 1.0, "alpha2": 0.0,
                                                                                 "K": 1.0}}})
    assert sc["material"]["parameters"] == {"alpha1": 1.0, "alpha2": 0.0, "K": 1.0, "i2": "usual",
                                            "volumetric": "quadratic"}
    # alpha1 = -1, alpha2 = 0.5: mu0 = 2(alpha1 + alpha2) = -1 with the usual I2,
    # 2 alpha1 + 8 alpha2 = 2 with the paper's
    soft = {"alpha1": -1.0, "alpha2": 0.5, "K": 1.0}
    with pytest.raises(scene.SceneError, match=r"'material\.parameters': the small-strain shear modulus "
                                               r"2\(alpha1 \+ alpha2\) must be > 0, found -1"):
        scene.load({**base, "material": {"law": "mooney_rivlin", "parameters": soft}})
    scene.load({**base, "material": {"law": "mooney_rivlin", "parameters": {**soft, "i2": "paper"}}})
    with pytest.raises(scene.SceneError, match=r"'material\.parameters\.K': missing \(required by neo_hookean\)"):
        scene.load({**base, "material": {"law": "neo_hookean", "parameters": {"mu": 1.0}}})
    with pytest.raises(scene.SceneError, match=r"'material\.parameters\.muu': unknown parameter of neo_hookean "
                                               r"\(expected mu, K, volumetric\); did you mean 'mu'\?"):
        scene.load({**base, "material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 1.0, "muu": 0.3}}})
