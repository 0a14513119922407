"""The rigid cylinder obstacle (a smooth curved die) end to end: its scene
keys and their errors, the flat limit (a cylinder of huge radius presses
like a plane), and rigid-obstacle phases (press, then slide the cylinder
along the block: the rest position of each phase is where the last one
ended, and full sliding transmits Fx = μ Fz).

References independent of the code: the plane obstacle (another projection
and kernel path) and, for a stiff block, the rigid-block closed forms
N = ε_N A δ and T = μ N."""
import csv

import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import _cpp, scene
from hypercontact.phases import run_phase
from hypercontact.results import ResultsWriter
from hypercontact.simulation import Simulation

G = 1.0e6   # stiff block: the rigid-block closed forms hold to ~ε h / G
EPS = 10.0
MU = 0.3
DELTA = 0.01
R = 1.0e4


@pytest.fixture(autouse=True)
def no_pictures(monkeypatch):
    monkeypatch.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})


def block(out, contact, mu=0.0):
    """A 1 × 1 × 1 block, bottom clamped, its top (the slave) under a rigid obstacle."""
    return {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 2, "m": 1},
        "material": {"law": "neo_hookean", "parameters": {"mu": G, "K": G}},
        "bc": [{"surface": "zmin", "fix": ["x", "y", "z"]}],
        "contact": [dict(name="die", surface="zmax", eps_n=EPS, eps_t=EPS, mu=mu, **contact)],
        "steps": {"initial": 0.5, "max": 0.5},
        "solver": {"rtol": 1e-10, "atol": 1e-9, "max_it": 30},  # N = 0.1: round-off of |R| ~1e-10
        "output": {"dir": str(out), "xdmf": False, "symmetry_factor": 1.0},
    }


def cylinder(motion):
    return {"obstacle": "cylinder", "point": [0.5, 0.0, 1.0 + R], "axis": [0.0, 1.0, 0.0], "radius": R,
            "motion": motion}


def run(data):
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet)
    sim.run(out_dir=data["output"]["dir"])
    return sim, sim.contacts[0].force(sim.u)


def test_a_cylinder_of_huge_radius_presses_like_a_plane(out_dir):
    _, f_cyl = run(block(out_dir / "cyl", cylinder([0.0, 0.0, -DELTA])))
    sim, f_plane = run(block(out_dir / "plane", {"obstacle": "plane", "point": [0.0, 0.0, 1.0],
                                                "normal": [0.0, 0.0, -1.0], "motion": [0.0, 0.0, -DELTA]}))
    # the plane loads the whole top: its reference area, 1, and so does the results' die_area column
    assert sim.contacts[0].contact_area() == pytest.approx(1.0, rel=1e-12)
    with open(out_dir / "plane" / "curves.csv") as f:
        assert float(list(csv.DictReader(f))[-1]["die_area"]) == pytest.approx(1.0, rel=1e-12)
    # the top's corners sit (0.5² + 0.5²)/(2R) = 2.5e-5 below the cylinder: ~1e-3 of δ
    assert f_cyl[2] == pytest.approx(f_plane[2], rel=2e-3)
    assert f_plane[2] == pytest.approx(-EPS * 1.0 * DELTA, rel=1e-3)  # N = ε_N A δ, pushes down
    assert abs(f_cyl[0]) < 1e-6 * abs(f_cyl[2])  # symmetric about the axis line x = 0.5


def test_phases_press_then_slide_the_cylinder_with_friction(out_dir):
    """Press δ, then slide 0.05 along x (≫ the elastic slip μN/ε_T = 0.003):
    the second phase starts where the first ended (Fz stays N) and the block
    is dragged along +x with T = μ N."""
    sim = Simulation(scene.load(block(out_dir, cylinder([0.0, 0.0, 0.0]), mu=MU)), MPI.COMM_WORLD, log=quiet)
    run_phase(sim, {}, out_dir / "press", obstacle_motions={0: [0.0, 0.0, -DELTA]})
    f_press = sim.contacts[0].force(sim.u)
    run_phase(sim, {}, out_dir / "slide", obstacle_motions={0: [0.05, 0.0, 0.0]})
    f_slide = sim.contacts[0].force(sim.u)
    N = EPS * 1.0 * DELTA
    assert f_press[2] == pytest.approx(-N, rel=2e-3)
    assert abs(f_press[0]) < 1e-6 * N
    assert f_slide[2] == pytest.approx(-N, rel=2e-3)  # the die did not jump back to its first rest position
    assert f_slide[0] == pytest.approx(MU * abs(f_slide[2]), rel=1e-3)  # dragged along +x, full slip
    assert np.all(np.asarray(sim.contacts[0].law.committed.state)[np.asarray(sim.contacts[0].geometry.area) > 0] == 2)


def test_cylinder_keys_and_errors(tmp_path):
    ok = scene.load(block(tmp_path, cylinder([0.0, 0.0, -DELTA])))
    assert ok["contact"][0]["radius"] == R
    bad = block(tmp_path, cylinder([0.0, 0.0, -DELTA]))
    del bad["contact"][0]["radius"]
    with pytest.raises(scene.SceneError, match=r"contact\[0\]\.radius.*radius > 0"):
        scene.load(bad)
    bad = block(tmp_path, {"obstacle": "plane", "radius": 2.0})
    with pytest.raises(scene.SceneError, match=r"contact\[0\]\.radius.*cylinder"):
        scene.load(bad)
    with pytest.raises(ValueError, match="radius"):
        _cpp.RigidCylinder([0, 0, 0], [0, 1, 0], -1.0)
    with pytest.raises(ValueError, match="axis"):
        _cpp.RigidCylinder([0, 0, 0], [0, 0, 0], 1.0)
