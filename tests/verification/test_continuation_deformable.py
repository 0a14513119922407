"""Arc-length continuation with a deformable master (docs/method.md §8): the
inflated sphere of scenes/sphere_plane.toml (coarse 8 × 8 × 1 octant) pressed
against a block meshed as a second body, a thousand times stiffer than the
shell, instead of the rigid plane x = 116 mm. The contact search runs at every
converged step and the matrix pattern follows the pairing.

Reference: the same scene against the rigid plane (rigid contact code, no
search): the block's face is flat and hardly moves, so the two must follow the
same curve through the limit point."""
import tomllib

import numpy as np
import pytest
from conftest import ROOT
from mpi4py import MPI

from reference.runs import column, run

STIFF = 1000.0


def sphere_plane(block, mu=0.0):
    data = tomllib.loads((ROOT / "scenes" / "sphere_plane.toml").read_text())
    data["mesh"].update(n=8, m=1)
    data["output"]["xdmf"] = False
    data["contact"][0]["mu"] = mu
    if not block:
        return data
    par = data["material"]["parameters"]
    stiff = dict(par, alpha1=STIFF * par["alpha1"], alpha2=STIFF * par["alpha2"], K=STIFF * par["K"])
    # x from 116 to 120, y and z from 0 to 120 (the contact patch stays inside 60 mm), symmetric on y = 0, z = 0
    data["body"] = [{"name": "wall", "builder": "box", "size": [4.0, 120.0, 120.0], "origin": [116.0, 0.0, 0.0],
                     "n": 8, "m": 8, "material": {"law": "mooney_rivlin", "parameters": stiff}}]
    data["bc"] += [{"surface": "wall.xmax", "fix": ["x", "y", "z"]}, {"surface": "wall.ymin", "fix": ["y"]},
                   {"surface": "wall.zmin", "fix": ["z"]}]
    data["contact"] = [{"name": "wall", "surface": "outer", "obstacle": "surface", "master": "wall.xmin", "mu": mu}]
    return data


@pytest.fixture(scope="module")
def rigid_and_block(tmp_path_factory):
    out = tmp_path_factory.mktemp("deformable_master")
    return run(sphere_plane(block=False), out / "rigid")[1], run(sphere_plane(block=True), out / "block")


def test_stiff_block_follows_the_rigid_plane_through_the_limit_point(rigid_and_block):
    """The located limit point and the whole pressure–pole displacement curve
    within 1 % of the rigid plane's; the block's contact force equals the
    rigid plane's at the same pole displacement within 1 %; the pairing was
    searched and the matrix pattern rebuilt along the path."""
    rigid, (sim, block) = rigid_and_block
    assert len(rigid.limit_points) == len(block.limit_points) == 1
    lr, lb = rigid.limit_points[0], block.limit_points[0]
    assert lr["located"] and lb["located"]
    assert lb["load_factor"] == pytest.approx(lr["load_factor"], rel=0.01)
    assert lb["probes"]["pole"][2] == pytest.approx(lr["probes"]["pole"][2], rel=0.01)
    u_r, u_b = column(rigid, "pole_uz"), column(block, "pole_uz")
    assert u_b[-1] >= 100.0 and np.all(np.diff(u_b) > 0) and np.all(np.diff(u_r) > 0)
    inside = u_b <= u_r[-1]
    assert inside.sum() >= 8
    for key in ("load_factor", "wall_fx"):
        ref = np.interp(u_b[inside], u_r, column(rigid, key))
        got = column(block, key)[inside]
        scale = np.abs(column(rigid, key)).max()
        assert np.max(np.abs(got - ref)) <= 0.01 * scale, key
    closed = column(block, "wall_closed_nodes")
    assert closed[0] == 0 and closed[-1] > 0  # the shell reaches the block along the path
    assert sim.problem.pattern_builds >= 2  # the pairing changed between continuation steps


def test_shell_does_not_pass_through_the_block(rigid_and_block):
    """At the end of the path no node of the shell's outer surface lies beyond
    the block's (deformed) face by more than the penalty's own gap: the
    contact force over ε_N × the loaded area."""
    _, (sim, block) = rigid_and_block
    c = sim.contacts[0]
    ev = c.evaluate(sim.u)
    gap = np.asarray(ev.gap)
    force = abs(block.steps[-1]["wall_fx"]) / sim.scene["output"]["symmetry_factor"]
    closed = gap < 0
    assert closed.any()
    allowed = force / (c.eps_n * np.sum(np.asarray(c.geometry.point_area)[closed]))
    assert -gap.min() <= 3.0 * allowed


@pytest.mark.mpi
def test_continuation_with_a_deformable_master_on_two_ranks_equals_serial(out_dir):
    """The pairing, its pattern rebuilds and the located limit point do not
    depend on the partition: mpirun -n 2 equals serial to 1e-8."""
    data = sphere_plane(block=True)
    data["steps"]["stop_value"] = 70.0
    _, par = run(data, out_dir / "par", MPI.COMM_WORLD)
    _, ser = run(data, out_dir / f"ser{MPI.COMM_WORLD.rank}", MPI.COMM_SELF)
    assert len(par.steps) == len(ser.steps)
    for key in ("load_factor", "pole_uz", "wall_fx"):
        assert column(par, key) == pytest.approx(column(ser, key), rel=1e-8, abs=1e-10), key
    assert par.limit_points[0]["load_factor"] == pytest.approx(ser.limit_points[0]["load_factor"], rel=1e-8)
