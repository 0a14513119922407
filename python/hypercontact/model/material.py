"""The scene's material → the law ψ(F, **params) the volume forms use: a
built-in law with its defaults filled, a user law from a Python file, or a
law a driver script passes."""
import importlib.util
import inspect
from pathlib import Path

import ufl

from ..forms import materials
from ..scene import SceneError


def load_user_law(spec):
    """'python:path/to/file.py:function' → the function ψ(F, **params)."""
    try:
        _, path, func = spec.split(":")
    except ValueError:
        raise SceneError(f"scene key 'material.law': expected a built-in law ({', '.join(materials.LAWS)}) "
                         f"or 'python:FILE.py:FUNCTION', found {spec!r}") from None
    if not Path(path).is_file():
        raise SceneError(f"scene key 'material.law': file '{path}' does not exist")
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
    """(psi, params, description) of the scene's material; ``law`` is a
    Python function ψ(F, **params) given by a driver script."""
    params = dict(mat["parameters"])
    name = mat["law"]
    if law is None and name in materials.LAWS:
        law, expected = materials.LAWS[name]
        for key, default in expected.items():
            if key not in params:
                if default is None:
                    raise SceneError(f"scene key 'material.parameters.{key}': missing (required by {name})")
                params[key] = default
        unknown = set(params) - set(expected)
        if unknown:
            raise SceneError(f"scene key 'material.parameters.{sorted(unknown)[0]}': unknown parameter "
                             f"of {name} (expected {', '.join(expected)})")
    elif law is None:
        law = load_user_law(name)
    else:  # a driver's law gets the scene parameters it names (the scene fills the built-in law's defaults)
        accepted = inspect.signature(law).parameters.values()
        if not any(a.kind == a.VAR_KEYWORD for a in accepted):
            params = {k: v for k, v in params.items() if k in {a.name for a in accepted}}
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
    desc = name if name in materials.LAWS else f"user law {getattr(law, '__name__', name)}"
    if name == "mooney_rivlin":
        desc = f"Mooney–Rivlin ({params['i2']} I2)"
    if name in materials.LAWS and params.get("volumetric", "quadratic") != "quadratic":
        desc += f", volumetric {params['volumetric']}"
    return law, params, desc
