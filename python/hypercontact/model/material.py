"""The scene's material → the law ψ(F, **params) the volume forms use: a
built-in law (the scene filled its defaults), a user law from a Python file, or a
law a driver script passes."""
import importlib.util
import inspect

import ufl

from ..forms import materials
from ..scene import SceneError


def load_user_law(spec):
    """'python:FILE.py:FUNCTION' (the scene checked the form and that FILE
    exists) → the function ψ(F, **params)."""
    if not spec.startswith("python:"):
        raise SceneError(f"scene key 'material.law': expected a built-in law ({', '.join(materials.LAWS)}) "
                         f"or 'python:FILE.py:FUNCTION', found {spec!r} (any other name needs a driver "
                         "script that passes the law to Simulation)")
    _, path, func = spec.split(":")
    module_spec = importlib.util.spec_from_file_location("user_law", path)
    module = importlib.util.module_from_spec(module_spec)
    try:
        module_spec.loader.exec_module(module)
    except Exception as err:
        raise SceneError(f"scene key 'material.law': '{path}' raised on import: {err!r}") from None
    if not callable(getattr(module, func, None)):
        raise SceneError(f"scene key 'material.law': '{path}' has no function '{func}'")
    return getattr(module, func)


def resolve_material(mat, law=None):
    """(psi, params, description) of the scene's material (validated by the
    scene: a built-in law's parameters are complete); ``law`` is a Python
    function ψ(F, **params) given by a driver script."""
    params = dict(mat["parameters"])
    name = mat["law"]
    builtin = law is None and name in materials.LAWS
    if builtin:
        law = materials.LAWS[name][0]
        desc = f"Mooney–Rivlin ({params['i2']} I2)" if name == "mooney_rivlin" else name
        if params["volumetric"] != "quadratic":
            desc += f", volumetric {params['volumetric']}"
    elif law is None:
        law = load_user_law(name)
        desc = f"user law {law.__name__}"
    else:  # a driver's law gets the scene parameters it names
        accepted = inspect.signature(law).parameters.values()
        if not any(a.kind == a.VAR_KEYWORD for a in accepted):
            params = {k: v for k, v in params.items() if k in {a.name for a in accepted}}
        desc = f"user law {getattr(law, '__name__', name)}"
    # Evaluate once on a symbolic F so that a broken law fails here, clearly.
    try:
        cell = ufl.hexahedron
        F = ufl.variable(ufl.Identity(3) + ufl.grad(ufl.Coefficient(ufl.VectorElement("Lagrange", cell, 1))))
        psi = law(F, **params)
        if not isinstance(psi, ufl.core.expr.Expr) or psi.ufl_shape != ():
            raise TypeError(f"must return a scalar UFL expression, returned {type(psi).__name__}")
    except SceneError:
        raise
    except Exception as err:
        raise SceneError(f"material law '{name}' with parameters {params} raised: {err}") from None
    return law, params, desc


def body_materials(scene):
    """Region name → material entry of each [[body]]: a region of a mesh file
    is the physical volume a body claims (its ``volume``), a built body's
    region is its name. The scene's [material] is that of every other region."""
    return {b["volume"] or b["name"]: b["material"] for b in scene["body"]}
