"""``--set key.path=value``: TOML values, tables made on the way, array
entries by index, and a message naming the override when it cannot apply."""
import math

from pathlib import Path

import pytest

from hypercontact import scene
from hypercontact.scene import SceneError, apply_override, parse_value

PUNCH = Path(__file__).resolve().parents[2] / "scenes" / "punch.toml"


@pytest.mark.parametrize("text, value", [("3", 3), ("2.5", 2.5), ("inf", math.inf), ("true", True),
                                         ("[1, 2.0]", [1, 2.0]), ('"gmres"', "gmres"), ("gmres", "gmres"),
                                         ("{ mu = 1 }", {"mu": 1}), ("", "")])
def test_values_are_toml_or_else_strings(text, value):
    assert parse_value(text) == value


def test_overrides_reach_nested_tables_array_entries_and_vector_components():
    data = {"mesh": {"size": [1.0, 1.0, 1.0]}, "contact": [{"eps_n": 1.0}, {"eps_n": 2.0}]}
    for assignment in ["mesh.n=8", "mesh.size.2=0.5", "contact.1.eps_n=30", "solver.petsc.ksp_type=gmres",
                       " title = a b "]:
        apply_override(data, assignment)
    assert data == {"mesh": {"size": [1.0, 1.0, 0.5], "n": 8}, "contact": [{"eps_n": 1.0}, {"eps_n": 30}],
                    "solver": {"petsc": {"ksp_type": "gmres"}}, "title": "a b"}


@pytest.mark.parametrize("assignment, message", [
    ("mesh.n", "--set 'mesh.n': expected key=value"),
    ("mesh..n=2", "--set mesh..n: empty key in the key path"),
    ("contact.2.eps_n=1", "--set contact.2.eps_n: '2' is not an index of 'contact' (0..0)"),
    ("contact.x.eps_n=1", "--set contact.x.eps_n: 'x' is not an index of 'contact' (0..0)"),
    ("bc.0.fix=[]", "--set bc.0.fix: '0' is not an index of 'bc' (it is empty)"),
    ("mesh.n.x=1", "--set mesh.n.x: 'mesh.n' is 4 (int), not a table"),
    ("contact.0=1", "--set contact.0: cannot assign a whole array entry"),
    ("mesh.size.3=1", "--set mesh.size.3: '3' is not an index of 'mesh.size' (0..2)"),
])
def test_an_override_that_cannot_apply_names_itself(assignment, message):
    data = {"mesh": {"n": 4, "size": [1.0, 1.0, 1.0]}, "contact": [{"eps_n": 1.0}], "bc": []}
    with pytest.raises(SceneError) as err:
        apply_override(data, assignment)
    assert str(err.value) == message


def test_load_applies_overrides_before_validating_them():
    sc = scene.load(PUNCH, ["mesh.n=8", "contact.0.eps_n=10", "mesh.size.2=5"])
    assert sc["mesh"]["n"] == 8 and sc["contact"][0]["eps_n"] == 10.0 and sc["mesh"]["size"] == [40.0, 40.0, 5.0]
    with pytest.raises(SceneError, match=r"^scene key 'contact\[0\]\.eps_n': expected >= 0, found -1.0 \(float\)$"):
        scene.load(PUNCH, ["contact.0.eps_n=-1"])
    with pytest.raises(SceneError, match=r"^scene key 'mesh\.q': unknown key"):
        scene.load(PUNCH, ["mesh.q=3"])
