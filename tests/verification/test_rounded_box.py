"""A box with rounded edges (``edge_radius``) through the whole scene path.

Reference independent of the box's code: a box whose sides along x and z are
both 2r, rounded with r, is in every plane y = const inside its rounded ends
the disc of radius r — the rigid cylinder of radius r along y, which has its
own projection (docs/method.md §3.2). A block pressed by the two, with and
without friction, must give the same forces and the same displacements to
round-off (the box also has to pass its radius from the scene to the kernel:
with r = 0 the sharp box gives another answer)."""
import csv

import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

R = 0.375             # the die's radius
Z0 = 1.0 + R + 1 / 64  # its axis: 1/64 above the block's top at rest (the block is 1 × 1 × 1)


def die_scene(out, obstacle, mu):
    die = ({"obstacle": "cylinder", "point": [0.5, 0.0, Z0], "axis": [0.0, 1.0, 0.0], "radius": R}
           if obstacle == "cylinder" else
           {"obstacle": "box", "lo": [0.5 - R, -3.0, Z0 - R], "hi": [0.5 + R, 4.0, Z0 + R],
            "edge_radius": R if obstacle == "rounded box" else 0.0})
    return {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 4, "m": 4},
        "material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 5.0}},
        "bc": [{"surface": "zmin", "fix": ["x", "y", "z"]}],
        "contact": [{"name": "die", "surface": "zmax", **die, "motion": [0.1, 0.0, -0.15],
                     "eps_n": 100.0, "mu": mu, "eps_t": 50.0}],
        "steps": {"initial": 0.25, "max": 0.25},
        "output": {"dir": str(out), "xdmf": False, "symmetry_factor": 1.0},
    }


def run(tmp_path, obstacle, mu):
    out = tmp_path / f"{obstacle.replace(' ', '_')}_{mu}"
    sim = Simulation(scene.load(die_scene(out, obstacle, mu)), MPI.COMM_SELF, log=quiet)
    sim.run()
    rows = list(csv.DictReader(open(out / "curves.csv")))
    return sim.u.x.array.copy(), rows


@pytest.mark.parametrize("mu", [0.0, 0.3])
def test_a_box_rounded_to_a_cylinder_is_the_cylinder(tmp_path, mu):
    u_cyl, cyl = run(tmp_path, "cylinder", mu)
    u_box, box = run(tmp_path, "rounded box", mu)
    assert len(cyl) == len(box) >= 4
    for a, b in zip(cyl, box):
        assert float(b["load_factor"]) == float(a["load_factor"])
        assert int(b["die_closed_nodes"]) == int(a["die_closed_nodes"]) > 0
        for k in ("die_fx", "die_fz"):
            assert float(b[k]) == pytest.approx(float(a[k]), rel=1e-9, abs=1e-12 * abs(float(a["die_fz"])))
    assert abs(float(cyl[-1]["die_fx"])) > 1e-3 * abs(float(cyl[-1]["die_fz"]))  # the die drags the top
    assert np.abs(u_box - u_cyl).max() <= 1e-9 * np.abs(u_cyl).max()
    # the sharp box of the same size is another obstacle: its bottom face is flat
    _, sharp = run(tmp_path, "sharp box", mu)
    assert abs(float(sharp[-1]["die_fz"]) - float(cyl[-1]["die_fz"])) > 0.05 * abs(float(cyl[-1]["die_fz"]))
