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


def superellipse_gap(e, a):
    """Signed distance from e = (e1, e2) ≥ 0 in a cross-section of the blended
    rounding to its surface, by brute force: the points within a of the
    superellipse q = a (√cos t, √sin t), t ∈ [0, π/2] (q1⁴ + q2⁴ = a⁴), a dense
    sample of t and then a golden-section search round the best one. Returns
    (gap, unit normal from the surface towards e) for e outside the
    superellipse; independent of the kernel's Lagrange equations."""
    def point(t):
        return a * np.sqrt(np.clip(np.array([np.cos(t), np.sin(t)]), 0.0, None))

    ts = np.linspace(0.0, np.pi / 2, 20001)
    q = a * np.sqrt(np.clip(np.stack([np.cos(ts), np.sin(ts)], axis=1), 0.0, None))
    k = int(np.argmin(np.linalg.norm(q - e, axis=1)))
    lo, hi = ts[max(k - 1, 0)], ts[min(k + 1, len(ts) - 1)]
    golden = (np.sqrt(5.0) - 1) / 2
    for _ in range(200):
        t1, t2 = hi - golden * (hi - lo), lo + golden * (hi - lo)
        if np.linalg.norm(point(t1) - e) < np.linalg.norm(point(t2) - e):
            hi = t2
        else:
            lo = t1
    d = e - point(0.5 * (lo + hi))
    return np.linalg.norm(d) - a, d / np.linalg.norm(d)


def test_the_blended_box_presses_with_its_own_surface(tmp_path):
    """The die of test_a_box_rounded_to_a_cylinder_is_the_cylinder with
    edge_profile = "blended" (a superellipse of radius r/2 offset by r/2 in
    every plane y = const), frictionless, the plain penalty (no smoothing): the
    force it reports is ε_N Σ A_i ⟨−g_i⟩ n_i over the block's top nodes with g
    and n from an independent brute-force distance to that profile at the
    die's final place, so the scene's radius, profile and motion reach the
    kernel; and it is not the circular die's force."""
    spec = die_scene(tmp_path / "blended", "rounded box", 0.0)
    spec["contact"][0].update({"edge_profile": "blended", "smoothing": 0.0})
    sim = Simulation(scene.load(spec), MPI.COMM_SELF, log=quiet)
    sim.run()
    rows = list(csv.DictReader(open(tmp_path / "blended" / "curves.csv")))
    assert float(rows[-1]["load_factor"]) == 1.0
    geometry = sim.model.contacts[0].geometry
    x = geometry.coordinates(sim.u)
    centre = np.array([0.5 + 0.1, Z0 - 0.15])  # the die's axis at λ = 1 in (x, z)
    force, closed = np.zeros(2), 0
    for xi, area in zip(x, geometry.area):
        rel = xi[[0, 2]] - centre
        gap, n = superellipse_gap(np.abs(rel), R / 2)
        if gap < 0:
            force += 100.0 * area * (-gap) * np.sign(rel) * n
            closed += 1
    assert closed == int(rows[-1]["die_closed_nodes"]) > 3
    assert float(rows[-1]["die_fz"]) == pytest.approx(force[1], rel=1e-8)
    # the search finds the closest point's parameter to about √(machine ε) (the distance is flat
    # there): its gaps are exact to round-off, its normals to about 1e-8
    assert float(rows[-1]["die_fx"]) == pytest.approx(force[0], rel=1e-8, abs=1e-6 * abs(force[1]))
    _, circular = run(tmp_path, "rounded box", 0.0)
    assert abs(float(circular[-1]["die_fz"]) - force[1]) > 1e-3 * abs(force[1])
