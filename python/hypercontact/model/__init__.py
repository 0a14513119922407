"""The model: a scene built into a body, forms, constraints, loads, contacts and probes (:class:`Model`)."""
from .build import Model

__all__ = ["Model"]
