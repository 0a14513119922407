"""Scenes: TOML files describing one problem, validated against a typed
schema (pydantic models, :mod:`.schema`).

:func:`load` returns plain dicts with every default filled in (what the
rest of the code indexes); :func:`load_model` the typed :class:`Scene`.
Both raise :class:`SceneError` naming the key path, what was expected and
what was found; an unknown key is refused with the closest valid name.
"""
from ..forms.registry import LAWS, VOLUMETRIC
from .builders import BUILDER_SURFACES
from .builtin import SCENES, STUDIES, scene_path, study_path
from .errors import SceneError
from .fields import MAX_CELLS, MAX_LENGTH, MAX_QUADRATURE_DEGREE
from .load import load, load_model, to_dict
from .overrides import apply_override, parse_value
from .schema import Scene

#: The built-in laws and their parameters (None = required): forms/registry.py.
BUILTIN_LAWS = {name: dict(law.parameters) for name, law in LAWS.items()}
#: The string parameters of the built-in laws and their values.
STRING_PARAMETERS = {key: values for law in LAWS.values() for key, values in law.choices.items()}

__all__ = ["BUILDER_SURFACES", "BUILTIN_LAWS", "MAX_CELLS", "MAX_LENGTH", "MAX_QUADRATURE_DEGREE", "SCENES",
           "STRING_PARAMETERS", "STUDIES", "Scene", "SceneError", "VOLUMETRIC", "apply_override", "load",
           "load_model", "parse_value", "scene_path", "study_path", "to_dict"]
