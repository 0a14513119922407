"""What a refused scene says: "scene key '<path>': <what was expected>,
found <what>", the path built from pydantic's error location; strict TOML
types; defaults filled in; files found relative to the scene."""
from pathlib import Path

import pytest

from hypercontact import scene
from hypercontact.scene import SceneError

PUNCH = Path(__file__).resolve().parents[2] / "scenes" / "punch.toml"

LAW = {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 2.0}}


def message(data, **kwargs):
    with pytest.raises(SceneError) as err:
        scene.load(data, **kwargs)
    return str(err.value)


@pytest.mark.parametrize("data, expected", [
    ({"material": LAW, "stepz": {}}, "scene key 'stepz': unknown key; did you mean 'steps'?"),
    ({"material": LAW, "mesh": {"zz": 1}}, "scene key 'mesh.zz': unknown key; valid keys: builder, inner_radius, "
                                           "thickness, size, origin, n, m, grading, focus, core, cells, mean_diameter, cord_diameter, cross_section, order, length, layers, angles, ovality, file, perturbation"),
    ({"material": LAW, "mesh": 3}, "scene key 'mesh': expected a table, found 3 (int)"),
    ({"material": LAW, "bc": 3}, "scene key 'bc': expected an array of tables ([[bc]]), found 3 (int)"),
    ({"material": LAW, "mesh": {"n": "16"}}, "scene key 'mesh.n': expected an integer, found '16' (str)"),
    ({"material": LAW, "mesh": {"n": True}}, "scene key 'mesh.n': expected an integer, found True (bool)"),
    ({"material": LAW, "solver": {"atol": True}}, "scene key 'solver.atol': expected a number, found True (bool)"),
    ({"material": LAW, "solver": {"atol": float("inf")}},
     "scene key 'solver.atol': expected a finite number, found inf (float)"),
    ({"material": LAW, "mesh": {"size": [1, 2]}},
     "scene key 'mesh.size': expected a list of three numbers, found [1, 2] (list)"),
    ({"material": LAW, "output": {"xdmf": 1}}, "scene key 'output.xdmf': expected true or false, found 1 (int)"),
    ({"material": LAW, "bc": [{"surface": "zmin", "fix": ["x"]}, {"fix": ["y"]}]},
     "scene key 'bc[1].surface': expected either a surface or a point (the node a bc holds), found neither"),
    ({"material": LAW, "bc": [{"surface": "zmin", "point": [0, 0, 0], "fix": ["x"]}]},
     "scene key 'bc[0].surface': expected either a surface or a point (the node a bc holds), found both"),
    ({"material": LAW, "output": {"probes": {"p": [0.0, 0.0, float("nan")]}}},
     "scene key 'output.probes.p': expected a list of three finite numbers, found [0.0, 0.0, nan] (list)"),
    ({"material": LAW, "solver": {"petsc": {"ksp_type": "gmress"}}},
     "scene key 'solver.petsc.ksp_type': expected a PETSc ksp type, found 'gmress' (str); did you mean 'gmres'?"),
    ({"material": LAW, "body": [{"name": "b", "origin": [0.0, 0.0, 2.0],
                                 "material": {"law": "neo_hookean", "parameters": {"mu": -1.0, "K": 2.0}}}]},
     "scene key 'body[0].material.parameters.mu': expected a shear modulus > 0, found -1.0 (float)"),
    ({"material": LAW, "mesh": {"a\nb": 1}},
     "scene key 'mesh.a\\nb': unknown key; valid keys: builder, inner_radius, thickness, size, origin, n, m, grading, focus, core, "
     "cells, mean_diameter, cord_diameter, cross_section, order, length, layers, angles, ovality, file, perturbation"),
    ({"mesh": {}}, "scene key 'material': missing (required)"),
])
def test_the_message_names_the_key_path(data, expected):
    assert message(data) == expected


def test_defaults_are_filled_and_numbers_are_floats():
    sc = scene.load({"material": LAW, "mesh": {"size": [2, 2, 1]}, "bc": {"surface": "zmin", "fix": ["z"]}})
    assert sc["mesh"]["size"] == [2.0, 2.0, 1.0] and all(type(v) is float for v in sc["mesh"]["size"])
    assert sc["mesh"]["n"] == 4 and sc["steps"]["initial"] == 0.1 and sc["solver"]["petsc"] == {}
    assert sc["bc"] == [{"name": "", "surface": "zmin", "point": None, "fix": ["z"],
                         "motion": [0.0, 0.0, 0.0]}]  # an array of one
    assert sc["contact"] == [] and sc["title"] == ""


def test_the_plain_dict_is_the_typed_models_export():
    model = scene.load_model(PUNCH)
    assert isinstance(model, scene.Scene)
    assert model.mesh.n == 16 and model.contact[0].lo == [-20.0, -20.0, 10.0]
    assert scene.to_dict(model) == scene.load(PUNCH)
    assert model.surfaces()["zmax"] == 2


def test_files_are_found_relative_to_the_scene(tmp_path):
    (tmp_path / "plate.msh").write_text("")
    data = {"material": LAW, "mesh": {"builder": "file", "file": "plate.msh"}}
    assert scene.load(data, base_dir=tmp_path)["mesh"]["file"] == str(tmp_path / "plate.msh")
    elsewhere = tmp_path / "elsewhere"
    assert message(data, base_dir=elsewhere) == (f"scene key 'mesh.file': mesh file '{elsewhere / 'plate.msh'}' "
                                                 "does not exist")
    scene_file = tmp_path / "plate.toml"
    scene_file.write_text('[mesh]\nbuilder = "file"\nfile = "plate.msh"\n[material]\nlaw = "neo_hookean"\n'
                          'parameters = { mu = 1.0, K = 2.0 }\n')
    assert scene.load(scene_file)["mesh"]["file"] == str(tmp_path / "plate.msh")


def test_a_scene_file_that_is_not_toml_names_the_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[mesh\n")
    assert message(bad).startswith(f"scene file '{bad}' is not valid TOML")
    assert message(tmp_path / "none.toml") == f"scene file '{tmp_path / 'none.toml'}' does not exist"
