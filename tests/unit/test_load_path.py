"""The load path (hypercontact.scene.path) of scenes with and without
[[phase]], and the phases' bad input. No mesh, no solve: the scene only."""
import math

import numpy as np
import pytest

from hypercontact import scene
from hypercontact.contact.rigid import Pose
from hypercontact.scene.path import LoadPath, rotation_matrix

LAW = {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 2.0}}


def base(**extra):
    """A block with a named bc (its top), a named pressure, a cylinder and a plane."""
    data = {"material": LAW, "mesh": {"size": [1.0, 1.0, 1.0]},
            "bc": [{"surface": "zmin", "fix": ["x", "y", "z"]},
                   {"name": "lid", "surface": "zmax", "fix": ["x", "z"]}],
            "pressure": [{"name": "p", "surface": "xmax"}],
            "contact": [{"name": "roller", "surface": "zmax", "obstacle": "cylinder", "point": [0.5, 0.5, 2.0],
                         "axis": [0.0, 1.0, 0.0], "radius": 1.0, "mu": 0.5},
                        {"name": "wall", "surface": "xmin", "obstacle": "plane", "point": [-0.1, 0.0, 0.0],
                         "normal": [1.0, 0.0, 0.0]},
                        {"name": "box", "surface": "ymin", "obstacle": "box", "lo": [0, -2, 0], "hi": [1, -1, 1]}],
            "phase": [{"name": "press", "bc": {"lid": [0.1, 0.0, -0.2]}, "pressure": {"p": 2.0}},
                      {"name": "roll", "length": 2.0, "steps": {"max": 0.05},
                       "pressure": {"p": [[0.5, 4.0], [0.75, 1.0]]},
                       "contact": {"roller": {"motion": [1.0, 0.0, 0.0], "rotation": 1.0, "mu": [[1.0, 0.0]]}}}]}
    data.update(extra)
    return data


def refused(data, key, words):
    with pytest.raises(scene.SceneError) as err:
        scene.load(data)
    message = str(err.value)
    assert message.startswith(f"scene key '{key}': "), message
    assert words in message, message


def test_without_phases_every_value_is_the_load_factor_times_the_scene_value():
    data = base()
    del data["phase"]
    data["bc"][1]["motion"] = [0.3, 0.0, -0.2]
    data["pressure"][0]["value"] = 5.0
    data["contact"][1]["motion"] = [0.0, 0.0, 0.7]
    path = LoadPath(scene.load(data))
    assert path.implicit and len(path.phases) == 1
    for s in (0.0, 0.1, 0.37, 1.0, 2.5):  # beyond 1: continuation's λ
        v = path.values(0, s)
        assert v[("bc", 1, "x")] == s * 0.3 and v[("bc", 1, "z")] == s * -0.2 and v[("bc", 0, "y")] == 0.0
        assert v[("pressure", 0)] == s * 5.0
        assert v[("motion", 1)] == [0.0, 0.0, s * 0.7]
        assert v[("rotation", 0)] == 0.0 and v[("mu", 0)] == 0.5


def test_phases_start_where_the_previous_one_ended_and_hold_what_they_do_not_name():
    path = LoadPath(scene.load(base()))
    assert [p.name for p in path.phases] == ["press", "roll"]
    assert [(p.start, p.length) for p in path.phases] == [(0.0, 1.0), (1.0, 2.0)]
    assert path.time(1, 0.5) == 2.0 and path.progress(1, 1.0) == 1.0
    assert path.phases[1].steps["max"] == 0.05 and path.phases[0].steps["max"] == 0.25
    v = path.values(0, 0.5)
    assert v[("bc", 1, "x")] == pytest.approx(0.05) and v[("bc", 1, "z")] == pytest.approx(-0.1)
    assert v[("pressure", 0)] == 1.0 and v[("mu", 0)] == 0.5 and v[("motion", 0)] == [0.0, 0.0, 0.0]
    # phase 2 holds the lid where phase 1 left it; the pressure goes 2 → 4 (s = 0.5) → 1 (s = 0.75), then holds
    for s, p in ((0.0, 2.0), (0.25, 3.0), (0.5, 4.0), (0.625, 2.5), (0.75, 1.0), (1.0, 1.0)):
        v = path.values(1, s)
        assert v[("pressure", 0)] == pytest.approx(p) and v[("bc", 1, "z")] == pytest.approx(-0.2)
    v = path.values(1, 0.25)
    assert v[("motion", 0)] == pytest.approx([0.25, 0.0, 0.0]) and v[("rotation", 0)] == pytest.approx(0.25)
    assert v[("mu", 0)] == pytest.approx(0.375)  # 0.5 → 0 over the phase
    assert path.max_mu(0) == 0.5 and path.max_mu(1) == 0.0 and path.rotates(0) and not path.rotates(1)


def test_a_rotation_turns_points_about_the_pivot_and_carries_anchors():
    R = rotation_matrix([0.0, 1.0, 0.0], math.pi / 2)  # right-handed about +y: z → x
    assert np.allclose(R @ [0.0, 0.0, 1.0], [1.0, 0.0, 0.0])
    pivot = np.array([0.5, 0.5, 2.0])
    pose = Pose([1.0, 0.0, 0.0], math.pi / 2, [0.0, 1.0, 0.0], pivot)
    assert np.allclose(pose.point([0.5, 0.5, 1.0]), [0.5, 0.5, 2.0] + np.array([1.0, 0.0, 0.0]) + [-1.0, 0, 0])
    rest = Pose([0.0, 0.0, 0.0], 0.0, [0.0, 1.0, 0.0], pivot)
    x = np.array([[0.5, 0.2, 1.0], [0.7, 0.0, 2.0]])
    assert np.allclose(pose.relative_to(rest, x), [pose.point(p) for p in x])  # from rest: the pose itself
    # carried in two steps = in one
    half = Pose([0.5, 0.0, 0.0], math.pi / 4, [0.0, 1.0, 0.0], pivot)
    assert np.allclose(pose.relative_to(half, half.relative_to(rest, x)), pose.relative_to(rest, x))
    # without rotation: a translation
    assert np.allclose(Pose([0.0, 1.0, 0.0]).relative_to(Pose([0.0, 0.25, 0.0]), x), x + [0.0, 0.75, 0.0])


@pytest.mark.parametrize("edit, key, words", [
    (lambda d: d["phase"][1]["pressure"].update(p=[[0.5, 1.0], [0.5, 2.0]]), "phase[1].pressure.p[1]",
     "the abscissae must increase: s = 0.5 follows s = 0.5"),
    (lambda d: d["phase"][1]["pressure"].update(p=[[0.7, 1.0], [0.2, 2.0]]), "phase[1].pressure.p[1]",
     "the abscissae must increase"),
    (lambda d: d["phase"][1]["pressure"].update(p=[[1.5, 1.0]]), "phase[1].pressure.p[0]",
     "expected an abscissa s from 0 to 1"),
    (lambda d: d["phase"][1]["pressure"].update(p=[[0.5, 1.0, 2.0]]), "phase[1].pressure.p[0]",
     "expected a point [s, value]"),
    (lambda d: d["phase"][0]["bc"].update(lid=[1.0, 2.0]), "phase[0].bc.lid", "expected a list of three numbers"),
    (lambda d: d["phase"][0]["bc"].update(lidd=[0.0, 0.0, 1.0]), "phase[0].bc.lidd",
     "no [[bc]] entry is named 'lidd' (named entries: lid); did you mean 'lid'?"),
    (lambda d: d["phase"][0]["bc"].update(lid=[0.0, 0.3, 0.0]), "phase[0].bc.lid",
     "moves y, which bc 'lid' does not fix"),
    (lambda d: d["phase"][0].update(contact={"rolller": {"mu": 0.1}}), "phase[0].contact.rolller",
     "no [[contact]] is named 'rolller'"),
    (lambda d: d["phase"][0].update(contact={"box": {"rotation": 0.1}}), "phase[0].contact.box.rotation",
     "a box stays axis-aligned"),
    (lambda d: d["phase"][0].update(contact={"wall": {"rotation": 0.1}}), "contact[1].rotation_axis",
     "rotating a plane needs its rotation_axis"),
    (lambda d: d["phase"][0].update(contact={"roller": {"mu": -0.1}}), "phase[0].contact.roller.mu[0]",
     "expected μ from 0 to 1000"),
    # a curve that starts elsewhere than where the previous phase left the value
    (lambda d: d["phase"][1]["contact"]["roller"].update(motion=[[0.0, 0.0, 0.0, 0.5], [1.0, 1.0, 0.0, 0.0]]),
     "phase[1].contact.roller.motion[0]", "it would jump"),
    (lambda d: d["phase"][1].update(bc={"lid": [[0.0, 0.0, 0.0, 0.0]]}), "phase[1].bc.lid[0]", "it would jump"),
    (lambda d: d["pressure"][0].update(value=1.0), "pressure[0].value", "with [[phase]] the phases give"),
    (lambda d: d["bc"][1].update(motion=[0.0, 0.0, 1.0]), "bc[1].motion", "with [[phase]] the phases move"),
    (lambda d: d["contact"][1].update(motion=[0.0, 0.0, 1.0]), "contact[1].motion", "with [[phase]] the phases move"),
    (lambda d: d["phase"][1]["steps"].update(maxx=0.1), "phase[1].steps.maxx", "unknown key; did you mean 'max'?"),
    (lambda d: d["phase"][1]["steps"].update(initial=0.01, min=0.1), "phase[1].steps.min",
     "must not exceed steps.initial"),
    (lambda d: d["phase"][1].update(solver={"linesearch": "wolfe"}), "phase[1].solver.linesearch", "expected auto"),
    (lambda d: d["phase"][1]["steps"].update(control="arclength"), "steps.stop_probe",
     "phase[1] runs under arclength control, which needs a probe"),
    (lambda d: (d["phase"][1]["steps"].update(control="arclength", stop_probe="top"),
                d.update(output={"probes": {"top": [0.5, 0.5, 1.0]}})), "phase[1].contact",
     "a phase under arclength control drives loads only"),
    (lambda d: (d["phase"][1]["steps"].update(control="displacement", stop_probe="top"), d["phase"][1].pop("contact"),
                d.update(output={"probes": {"top": [0.5, 0.5, 1.0]}})), "phase[1].pressure.p",
     "a phase under displacement control drives its loads linearly"),
    (lambda d: (d["phase"][0].update(steps={"control": "arclength", "stop_probe": "top"}), d["phase"][0].pop("bc"),
                d["phase"][0].pop("pressure"), d.update(output={"probes": {"top": [0.5, 0.5, 1.0]}})),
     "phase[0].steps.control", "a phase under arclength control needs a load it drives"),
    (lambda d: d["phase"][0].update(length=0.0), "phase[0].length", "expected > 0"),
    (lambda d: d["phase"][0].update(lenght=1.0), "phase[0].lenght", "unknown key; did you mean 'length'?"),
    (lambda d: d["bc"][0].update(name="lid"), "bc[1].name", "duplicate bc name 'lid'"),
    (lambda d: d["phase"][0].update(contact={"wall": {"active": 0}}), "phase[0].contact.wall.active",
     "expected true or false"),
    (lambda d: d["phase"][0].update(contact={"wal": {"active": False}}), "phase[0].contact.wal",
     "no [[contact]] is named 'wal' (contacts: roller, wall, box); did you mean 'wall'?"),
])
def test_bad_phases_are_refused_naming_the_key(edit, key, words):
    data = base()
    edit(data)
    refused(data, key, words)


def test_a_load_needs_its_value_without_phases():
    data = base()
    del data["phase"]
    refused(data, "pressure[0].value", "missing (required)")


def test_a_curve_that_starts_where_the_value_is_is_accepted():
    data = base()
    data["phase"][1]["pressure"]["p"] = [[0.0, 2.0], [1.0, 3.0]]  # phase 1 left it at 2
    assert scene.load(data)["phase"][1]["pressure"]["p"] == [[0.0, 2.0], [1.0, 3.0]]


def test_a_contact_is_switched_on_or_off_from_a_phase_start_until_another_phase_says_otherwise():
    data = base()
    data["contact"][2]["active"] = False  # the box starts off
    data["phase"].append({"name": "lift", "contact": {"wall": {"active": False}, "box": {"active": True}}})
    data["phase"].append({"name": "hold"})
    path = LoadPath(scene.load(data))
    wall, box = 1, 2
    # phases: press, roll, lift, hold
    assert [path.active(k, wall) for k in range(4)] == [True, True, False, False]
    assert [path.active(k, box) for k in range(4)] == [False, False, True, True]
    data["phase"].append({"name": "back", "contact": {"wall": {"active": True}}})
    path = LoadPath(scene.load(data))
    assert [path.active(k, wall) for k in range(5)] == [True, True, False, False, True]
    # switched off: from the phase's start; switched on: the penalty's share ramps in over the phase
    assert [path.values(2, s)[("active", wall)] for s in (0.0, 0.3, 1.0)] == [0.0, 0.0, 0.0]
    assert [path.values(4, s)[("active", wall)] for s in (0.0, 0.3, 1.0)] == pytest.approx([0.0, 0.3, 1.0])
    assert [path.values(1, s)[("active", wall)] for s in (0.0, 1.0)] == [1.0, 1.0]
    assert [path.switch(k, wall) for k in range(5)] == [None, None, "off", None, "on"]
    assert [path.switch(k, box) for k in range(5)] == [None, None, "on", None, None]
