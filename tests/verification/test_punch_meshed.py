"""The punch meshed as a stiff deformable body (scenes/punch_meshed.toml:
Mooney–Rivlin with moduli 1000× the plate's, node-to-surface contact on
the plate's top) against the rigid punch of scenes/punch.toml, both on the
16×16×4 plate: the issue asks for the rigid-punch force within 1 %; the
plate-edge and corner uplifts are held to the same 1 %.

A punch 1000× stiffer than the plate deforms ~1/1000 as much, so its
compliance changes the force by ~0.1 % (measured: −0.12 %): 1 % is the
issue's figure, well above that and below any error in the contact
(a missed node or a wrong area/normal changes the force by several %).
"""
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation


def run(name, out):
    sc = scene.load(ROOT / "scenes" / f"{name}.toml", [f"output.dir={out}", "output.xdmf=false"])
    sim = Simulation(sc, MPI.COMM_SELF, log=quiet)
    last = sim.run().steps[-1]
    assert last["load_factor"] == pytest.approx(1.0)
    return -last["punch_fz"], last["edge_uz"], last["corner_uz"]


def test_meshed_stiff_punch_gives_the_rigid_punch_force_and_uplift(tmp_path):
    meshed = run("punch_meshed", tmp_path / "meshed")
    rigid = run("punch", tmp_path / "rigid")
    assert rigid[0] > 0.0 and rigid[1] > 0.0  # the punch pushes down, the plate edge lifts
    for m, r in zip(meshed, rigid):
        assert m == pytest.approx(r, rel=0.01)
