"""Each rule that ties several tables of a scene together (or several keys
of one table) accepts a built-in scene and refuses the scene edited to break
it, naming the key that breaks it. No mesh, no solve: the scene only."""
import copy
import tomllib
from pathlib import Path

import pytest

from hypercontact import scene

ROOT = Path(__file__).resolve().parents[2]
SCENES = {name: tomllib.loads((ROOT / "scenes" / f"{name}.toml").read_text(encoding="utf-8"))
          for name in ("punch", "blocks", "sphere", "sphere_incompressible")}


def edited(name, edits):
    """A built-in scene's data with ``{"a.0.b": value}`` edits (value None deletes)."""
    data = copy.deepcopy(SCENES[name])
    for dotted, value in edits.items():
        *parents, last = [int(k) if k.isdigit() else k for k in dotted.split(".")]
        node = data
        for k in parents:
            node = node.setdefault(k, {}) if isinstance(node, dict) else node[k]
        if value is None:
            del node[last]
        else:
            node[last] = value
    return data


def refused(data, key, words, base_dir=None):
    """The scene is refused naming ``key`` and saying ``words``."""
    with pytest.raises(scene.SceneError) as err:
        scene.load(data, base_dir=base_dir)
    message = str(err.value)
    assert message.startswith(f"scene key '{key}': "), message
    assert words in message, message


@pytest.mark.parametrize("name", list(SCENES))
def test_the_unedited_scenes_pass_every_rule(name):
    scene.load(SCENES[name])


SURFACE_FRICTION = {"contact.0.mu": 0.3}


def volume_body(name, volume):
    """A [[body]] of a physical volume of the mesh file (None: no volume key)."""
    body = {"name": name, "material": SCENES["blocks"]["body"][0]["material"]}
    return body if volume is None else {**body, "volume": volume}


RULES = [
    # friction against a deformable surface: single pass, nodal integration
    ("blocks", {**SURFACE_FRICTION, "contact.0.passes": 2}, "contact[0].mu", "needs passes = 1"),
    ("blocks", {**SURFACE_FRICTION, "contact.0.integration": "gauss"}, "contact[0].mu", 'integration = "nodal"'),
    # a deformable master: another surface than the slave, one surface for two passes
    ("blocks", {"contact.0.master": "top.zmin+zmax"}, "contact[0].master", "slave surface alone"),
    ("blocks", {"contact.0.master": "zmax+xmax", "contact.0.passes": 2}, "contact[0].passes",
     "single master surface"),
    ("blocks", {"contact.0.master": ""}, "contact[0].master", "needs the master surface's name"),
    ("sphere", {"mesh.cells": "tetrahedra"}, "mesh.cells", "applies to the box and oring builders"),
    ("blocks", {"mesh.cells": "tetrahedra"}, "mesh.cells", "several bodies are built of hexahedra"),
    # the incompressible limit and the mixed formulation
    ("sphere", {"material.parameters.K": float("inf")}, "material.parameters.K", "K = inf (incompressible) needs"),
    ("sphere_incompressible", {"discretisation.quadrature_degree": 3}, "discretisation.quadrature_degree",
     "degree >= 4"),
    # several bodies: one built mesh or the physical volumes of one file (each claimed once), no pressure
    # unknown, names that tell the surfaces apart
    ("blocks", {"mesh.builder": "file", "mesh.file": __file__, "body": [volume_body("top", None)]},
     "body[0].volume", "with mesh.builder = \"file\" a [[body]] is one of the file's physical volumes"),
    ("blocks", {"body": [volume_body("top", "housing")]}, "body[0].volume",
     "a physical volume of a mesh file, but mesh.builder is 'box', not \"file\""),
    ("blocks", {"mesh.builder": "file", "mesh.file": __file__, "body.0.volume": "housing"}, "body[0].builder",
     "given, but the body is a physical volume of the mesh file (volume = 'housing')"),
    ("blocks", {"mesh.builder": "file", "mesh.file": __file__,
                "body": [volume_body("seal", "housing"), volume_body("ring", "housing")]},
     "body[1].volume", "volume 'housing' is claimed by body[0] too"),
    ("blocks", {"discretisation.formulation": "mixed", "discretisation.quadrature_degree": 4},
     "discretisation.formulation", "several bodies need"),
    ("blocks", {"body": [SCENES["blocks"]["body"][0]] * 2}, "body[1].name", "duplicate body name 'top'"),
    ("blocks", {"body.0.name": "body"}, "body[0].name", "taken by the [mesh] body"),
    # the surfaces a scene names are those its builders make
    ("punch", {"bc.0.surface": "xmn"}, "bc[0].surface", "did you mean 'xmin'?"),
    ("blocks", {"contact.0.master": "top.zmaks"}, "contact[0].master", "did you mean 'top.zmax'?"),
    ("blocks", {"pressure.0.surface": "bottom"}, "pressure[0].surface", "the mesh has no surface 'bottom'"),
    # pressures that do work
    ("blocks", {"pressure": [{"surface": "top.zmax", "value": 0.05}] * 2}, "pressure[1].surface",
     "a second pressure on 'top.zmax'"),
    ("sphere", {"pressure.0.surface": "xmin"}, "pressure[0].surface", "would do no work"),
    # probes of a built box or shell lie in the body
    ("punch", {"output.probes.edge": [40.0, 0.0, 10.5]}, "output.probes.edge", "is outside the body"),
    ("sphere", {"output.probes.pole": [0.0, 0.0, 97.0]}, "output.probes.pole", "is outside the body"),
    # continuation: a stop probe and a load; nothing moved or augmented between its steps
    ("sphere", {"steps.stop_probe": "top"}, "steps.stop_probe", "arclength control needs a probe"),
    ("sphere", {"pressure": []}, "steps.control", "needs a load"),
    ("sphere", {"pressure.0.value": 0.0}, "pressure[0].value", "needs a non-zero load"),
    ("punch", {"steps.control": "displacement", "steps.stop_probe": "edge",
               "traction": [{"surface": "xmax", "value": [1.0, 0.0, 0.0]}]}, "steps.control", "moving obstacles"),
    ("sphere", {"contact": [{"name": "wall", "surface": "outer", "obstacle": "plane", "point": [116.0, 0.0, 0.0],
                             "normal": [-1.0, 0.0, 0.0], "eps_n": 10.0, "enforcement": "augmented_lagrangian"}]},
     "contact[0].enforcement", 'use "penalty"'),
    ("sphere", {"bc.0.motion": [0.1, 0.0, 0.0]}, "steps.control", "prescribed motion"),
    # rules among the keys of one table
    ("punch", {"bc.0.fix": ["x", "x"]}, "bc[0].fix", "repeated axis"),
    ("punch", {"bc.0.motion": [0.0, 1.0, 0.0]}, "bc[0].motion", "moves y"),
    ("punch", {"steps.min": 0.2}, "steps.min", "must not exceed steps.initial"),
    ("punch", {"contact.0.hi": [20.0, -30.0, 20.0]}, "contact[0].hi", "lo < hi"),
    ("punch", {"contact.1.name": "punch"}, "contact[1].name", "duplicate contact name 'punch'"),
    ("punch", {"solver.petsc": {"pc_type": "ilu"}}, "solver.petsc.pc_type", "pc_factor_mat_solver_type"),
    ("punch", {"mesh.builder": "shell_octant", "mesh.n": 5, "output.probes": {}}, "mesh.n", "even n"),
    ("punch", {"mesh.builder": "shell_octant", "mesh.grading": [2.0, 1.0, 1.0], "output.probes": {}},
     "mesh.grading", "grading applies to the box, hemisphere or tube builders"),
    ("blocks", {"body.0.builder": "hemisphere", "body.0.grading": [1.0, 1.0, -2.0]}, "body[0].grading",
     "towards its pole only"),
    ("punch", {"mesh.n": 10**4, "mesh.m": 10}, "mesh.n", "hexahedra, more than 1e+08"),
    ("punch", {"mesh.builder": "file", "mesh.file": ""}, "mesh.file", 'builder = "file" needs'),
    ("punch", {"mesh.file": "plate.msh"}, "mesh.file", 'mesh.builder is not "file"'),
]


@pytest.mark.parametrize("name, edits, key, words", RULES, ids=[f"{k}:{w}" for _, _, k, w in RULES])
def test_a_broken_rule_names_its_key(name, edits, key, words):
    refused(edited(name, edits), key, words)


def test_rules_accept_what_they_allow():
    """The edge of each rule: what it does not refuse."""
    scene.load(edited("blocks", {**SURFACE_FRICTION}))  # single pass, nodal: friction allowed
    scene.load(edited("blocks", {"contact.0.master": "zmax+xmax"}))  # several masters, one pass
    scene.load(edited("punch", {"discretisation.formulation": "sri"}))  # contact with sri
    # rigid obstacles with quadratic elements, the mixed formulation, tetrahedra
    scene.load(edited("punch", {"discretisation.degree": 2, "discretisation.quadrature_degree": 4}))
    scene.load(edited("punch", {"discretisation.formulation": "mixed", "discretisation.quadrature_degree": 4,
                                "mesh.cells": "tetrahedra"}))
    scene.load(edited("punch", {"mesh.cells": "tetrahedra", "mesh.grading": [2.0, 1.0, 1.0]}))  # graded tetrahedra
    scene.load(edited("punch", {"output.probes.edge": [40.0, 0.0, 10.0]}))  # on the surface
    scene.load(edited("blocks", {"bc": SCENES["blocks"]["bc"] + [{"surface": "top.zmax", "fix": ["x"]}]}))
    scene.load(edited("sphere_incompressible", {"discretisation.quadrature_degree": 4}))


def test_automatic_penalty_needs_a_built_in_law(tmp_path):
    (tmp_path / "law.py").write_text("def psi(F, c=1.0):\n    return c\n")
    user_law = {"material": {"law": "python:law.py:psi", "parameters": {}}}
    refused(edited("punch", {**user_law, "contact.0.eps_n": 0.0}), "contact[0].eps_n", "automatic penalty",
            base_dir=tmp_path)
    sc = scene.load(edited("punch", user_law), base_dir=tmp_path)  # eps_n given: no modulus needed
    assert sc["material"]["law"] == f"python:{tmp_path / 'law.py'}:psi"  # resolved against base_dir
    refused(edited("punch", {**user_law, "discretisation.formulation": "sri"}), "discretisation.formulation",
            "'sri' needs a built-in law", base_dir=tmp_path)


def test_a_body_of_a_user_law_needs_the_displacement_formulation(tmp_path):
    (tmp_path / "law.py").write_text("def psi(F):\n    return 0\n")
    data = edited("blocks", {"body.0.material": {"law": "python:law.py:psi"}, "discretisation.formulation": "sri"})
    refused(data, "body[0].material.law", "'sri' needs a built-in law", base_dir=tmp_path)
