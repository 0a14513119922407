"""The scene: one TOML file describing one problem, as a typed model.

Each table is validated on its own (its keys, their types and ranges, the
rules among its own keys), then the rules that tie tables together
(:mod:`.rules`) in their order. ``Scene.parse_obj(data)`` raises pydantic's
ValidationError; :func:`hypercontact.scene.load_model` turns it into a
SceneError naming the key.
"""
from types import SimpleNamespace
from typing import List

from pydantic import root_validator, validator

from .base import SceneModel, tables
from .contact import Contacts, contact_tables, duplicate_names
from .fields import string
from .material import Material
from .mesh import Body, Mesh
from .phases import Phase
from .rules import RULES, surfaces
from .sections import (BodyForce, BoundaryCondition, Discretisation, Output, Pressure, Solver, Steps,
                       Traction)

#: The arrays of tables ([[name]]) of a scene.
ARRAYS = ("body", "pressure", "traction", "body_force", "bc", "phase")


class Scene(SceneModel):
    title: string() = ""
    mesh: Mesh = Mesh()
    material: Material
    body: List[Body] = []
    discretisation: Discretisation = Discretisation()
    pressure: List[Pressure] = []
    traction: List[Traction] = []
    body_force: List[BodyForce] = []
    bc: List[BoundaryCondition] = []
    contact: Contacts = []
    steps: Steps = Steps()
    solver: Solver = Solver()
    output: Output = Output()
    phase: List[Phase] = []

    @validator(*ARRAYS, pre=True)
    def arrays_of_tables(cls, value, field):
        return tables(value, field.name)

    @validator("contact", pre=True)
    def contacts_of_known_kinds(cls, value):
        return contact_tables(value)

    @validator("contact")
    def unique_contact_names(cls, contacts):
        duplicate_names(contacts)
        return contacts

    @root_validator(skip_on_failure=True)
    def rules(cls, values):
        tables_ = SimpleNamespace(**values)
        for rule in RULES:
            rule(tables_)
        return values

    def surfaces(self):
        """Surface name → axis of its normal (None: curved) of the built
        mesh; None for a mesh file (its surfaces are known once it is read)."""
        return surfaces(self)
