"""[[contact]] is a tagged union on ``obstacle``: each kind has its own keys
and refuses another kind's, naming the kinds the key belongs to."""
import pytest

from hypercontact import scene
from hypercontact.scene.contact import BoxContact, CylinderContact, PlaneContact, SphereContact, SurfaceContact

#: Keys every kind has (the laws and their enforcement), with values that are not the defaults.
COMMON = {"eps_n": 50.0, "mu": 0.2, "eps_t": 20.0, "penalty_factor": 10.0, "enforcement": "penalty",
          "gap_tolerance": 0.0, "smoothing": 0.0, "max_augmentations": 5, "active": False,
          "integration": "gauss"}  # a surface's is its own (friction against a surface needs "nodal")
KINDS = {
    "plane": {"point": [0.0, 0.0, -0.5], "normal": [0.0, 0.0, 2.0], "motion": [0.0, 0.0, 0.1],
              "rotation_axis": [1.0, 0.0, 0.0], "rotation_point": [0.5, 0.5, 0.0]},
    "box": {"lo": [-1.0, -1.0, 1.0], "hi": [2.0, 2.0, 2.0], "motion": [0.0, 0.0, -0.1], "edge_radius": 0.25,
            "edge_profile": "blended"},
    "cylinder": {"point": [0.5, 0.0, 1.5], "axis": [0.0, 1.0, 0.0], "radius": 0.5, "motion": [0.1, 0.0, 0.0],
                 "rotation_axis": [0.0, 0.0, 1.0], "rotation_point": [0.5, 0.5, 1.5], "inside": True},
    "sphere": {"center": [0.5, 0.5, 1.5], "radius": 0.6, "motion": [0.0, 0.0, -0.1],
               "rotation_axis": [0.0, 1.0, 0.0], "rotation_point": [0.5, 0.5, 2.1]},
    "surface": {"master": "top.zmin", "passes": 1, "integration": "nodal", "capture": 0.1, "master_surface": "smooth"},
}
MODELS = {"plane": PlaneContact, "box": BoxContact, "cylinder": CylinderContact, "sphere": SphereContact,
          "surface": SurfaceContact}


def two_blocks(contact):
    """A block under a second block "top", one contact of the lower block's top."""
    law = {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 2.0}}
    return {"mesh": {"size": [1.0, 1.0, 0.5], "n": 2, "m": 1}, "material": law,
            "body": [{"name": "top", "size": [1.0, 1.0, 0.5], "origin": [0.0, 0.0, 0.5], "n": 2, "m": 1,
                      "material": law}],
            "bc": [{"surface": "zmin", "fix": ["x", "y", "z"]}],
            "contact": [{"name": "c", "surface": "zmax", **contact}]}


@pytest.mark.parametrize("kind", list(KINDS))
def test_each_kind_takes_its_own_keys(kind):
    model = scene.load_model(two_blocks({"obstacle": kind, **COMMON, **KINDS[kind]}))
    [contact] = model.contact
    assert type(contact) is MODELS[kind]
    for key, value in {**COMMON, **KINDS[kind]}.items():
        assert getattr(contact, key) == value


@pytest.mark.parametrize("kind", list(KINDS))
def test_the_plain_dict_of_a_kind_has_its_keys_only(kind):
    [c] = scene.load(two_blocks({"obstacle": kind, **KINDS[kind]}))["contact"]
    assert set(c) == {"name", "surface", "obstacle", *COMMON, *KINDS[kind]}


FOREIGN = [("plane", "lo", '"box"'), ("plane", "radius", '"cylinder" or "sphere"'), ("box", "normal", '"plane"'),
           ("box", "point", '"plane" or "cylinder"'), ("cylinder", "master", '"surface"'),
           ("cylinder", "hi", '"box"'), ("surface", "point", '"plane" or "cylinder"'),
           ("surface", "motion", '"plane", "box", "cylinder" or "sphere"'), ("plane", "passes", '"surface"'),
           ("sphere", "normal", '"plane"'), ("sphere", "axis", '"cylinder"'),
           ("sphere", "point", '"plane" or "cylinder"'),
           ("cylinder", "center", '"sphere"'), ("box", "center", '"sphere"'),
           ("box", "rotation_axis", '"plane", "cylinder" or "sphere"'), ("sphere", "edge_radius", '"box"'),
           ("plane", "edge_profile", '"box"')]


@pytest.mark.parametrize("kind, key, owners", FOREIGN, ids=[f"{k}+{key}" for k, key, _ in FOREIGN])
def test_a_key_of_another_kind_is_refused_naming_its_kinds(kind, key, owners):
    other = next(k for k in KINDS if key in KINDS[k]) if key != "point" else "plane"
    contact = {"obstacle": kind, **KINDS[kind], key: KINDS[other].get(key, 1)}
    with pytest.raises(scene.SceneError) as err:
        scene.load(two_blocks(contact))
    assert str(err.value) == (f"scene key 'contact[0].{key}': applies to obstacle = {owners} only "
                              f"(this contact's obstacle is '{kind}')")


def test_a_key_of_no_kind_gets_the_closest_name_of_its_own_kind():
    with pytest.raises(scene.SceneError, match=r"'contact\[0\]\.normall': unknown key; did you mean 'normal'\?"):
        scene.load(two_blocks({"obstacle": "plane", "normall": [0.0, 0.0, 1.0]}))
    with pytest.raises(scene.SceneError,
                       match=r"'contact\[0\]\.penalty_factr': unknown key; did you mean 'penalty_factor'\?"):
        scene.load(two_blocks({"penalty_factr": 1.0}))  # no obstacle yet: the closest name of any kind


@pytest.mark.parametrize("obstacle, found", [("cone", "'cone' (str)"), (["plane"], "['plane'] (list)"),
                                             ({"kind": "plane"}, "{'kind': 'plane'} (dict)"), (3, "3 (int)")])
def test_the_obstacle_picks_a_kind_or_is_refused(obstacle, found):
    with pytest.raises(scene.SceneError) as err:
        scene.load(two_blocks({"obstacle": obstacle}))
    assert str(err.value) == (f"scene key 'contact[0].obstacle': expected \"plane\", \"box\", \"cylinder\", \"sphere\" "
                              f"(rigid) or \"surface\" (a deformable body's surface), found {found}")


def test_a_missing_obstacle_is_named():
    with pytest.raises(scene.SceneError, match=r"^scene key 'contact\[0\]\.obstacle': missing \(required\)$"):
        scene.load(two_blocks({}))


def test_required_keys_of_a_kind_say_what_they_are_for():
    with pytest.raises(scene.SceneError, match=r"'contact\[0\]\.radius': missing: a cylinder needs a radius > 0"):
        scene.load(two_blocks({"obstacle": "cylinder"}))
    with pytest.raises(scene.SceneError, match=r"^scene key 'contact\[0\]\.radius': missing: a sphere needs a radius > 0"):
        scene.load(two_blocks({"obstacle": "sphere", "center": [0.5, 0.5, 1.5]}))
    with pytest.raises(scene.SceneError, match=r"'contact\[0\]\.master': obstacle = \"surface\" needs the master"):
        scene.load(two_blocks({"obstacle": "surface"}))


def test_errors_inside_a_kind_name_the_entry_and_key():
    """The kind's class name, which pydantic puts into the error location, is not part of the key path."""
    with pytest.raises(scene.SceneError, match=r"^scene key 'contact\[0\]\.radius': expected a radius > 0"):
        scene.load(two_blocks({"obstacle": "cylinder", "radius": -1.0}))
    for radius in (0.0, -1.0):
        with pytest.raises(scene.SceneError, match=r"^scene key 'contact\[0\]\.radius': expected a radius > 0 "
                                                   r"\(the sphere's"):
            scene.load(two_blocks({"obstacle": "sphere", "radius": radius}))
    with pytest.raises(scene.SceneError, match=r"^scene key 'contact\[0\]\.edge_radius': edge_radius 0.6 does not fit "
                                               r"the box: at most half its shortest side \(1 from"):
        scene.load(two_blocks({"obstacle": "box", **KINDS["box"], "edge_radius": 0.6}))
    with pytest.raises(scene.SceneError, match=r"^scene key 'contact\[0\]\.edge_radius': expected >= 0, found -0.1"):
        scene.load(two_blocks({"obstacle": "box", **KINDS["box"], "edge_radius": -0.1}))
    with pytest.raises(scene.SceneError, match=r"^scene key 'contact\[0\]\.edge_profile': unexpected value; "
                                               r"permitted: 'circular', 'blended'$"):
        scene.load(two_blocks({"obstacle": "box", **KINDS["box"], "edge_profile": "smooth"}))
    with pytest.raises(scene.SceneError, match=r"^scene key 'contact\[0\]\.normal': expected a non-zero vector"):
        scene.load(two_blocks({"obstacle": "plane", "normal": [0.0, 0.0, 0.0]}))
    with pytest.raises(scene.SceneError, match=r"^scene key 'contact\[0\]\.passes': expected 1 \(single pass"):
        scene.load(two_blocks({"obstacle": "surface", "master": "top.zmin", "passes": 3}))
