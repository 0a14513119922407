"""Only the effects a scene calls for are built and run: no contact pair, no
contact assembly; no pressure, no load form; no continuation asked for, no
continuation solver; and the other way round."""
import json

from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation


def run(name, out, overrides):
    sc = scene.load(ROOT / "scenes" / name, [f"output.dir={out}", "output.xdmf=false", *overrides])
    sim = Simulation(sc, MPI.COMM_WORLD, log=quiet)
    sim.run()
    return sim, json.loads((out / "summary.json").read_text()) if MPI.COMM_WORLD.rank == 0 else None


def test_punch_builds_contact_and_load_control_only(out_dir):
    sim, summary = run("punch.toml", out_dir, ["mesh.n=4", "mesh.m=2"])
    assert sim.q_form is None and sim.bordered is None and sim.snes is not None
    assert sim.timers.calls.get("contact", 0) > 0
    assert summary["effects"] == ["Mooney–Rivlin (usual I2)", "2 rigid contacts (frictionless)", "load control",
                                  "direct linear solver (MUMPS LDLᵀ, symmetric tangent)"]
    assert summary["calls"]["contact"] > 0 and summary["peak_memory_mb"]["max_rank"] > 0


def test_sphere_builds_no_contact_and_no_snes(out_dir):
    sim, summary = run("sphere.toml", out_dir, ["mesh.n=4", "mesh.m=1", "steps.stop_value=20"])
    assert sim.contacts == [] and "contact" not in sim.timers.calls
    assert sim.snes is None and sim.bordered is not None and sim.q_form is not None
    assert summary["effects"][-2:] == ["1 follower pressure", "arc-length continuation"]
    assert "no contact" in summary["effects"] and "contact" not in summary["calls"]


def test_no_contact_pairs_no_contact_code(out_dir):
    """The punch without its contact pairs but pushed by a pressure: the
    contact phase is never entered."""
    sc = scene.load(ROOT / "scenes" / "punch.toml", [
        "mesh.n=2", "mesh.m=1", f"output.dir={out_dir}", "output.xdmf=false"])
    sc["contact"] = []
    sc["pressure"] = [{"surface": "zmax", "value": 0.01}]
    sc["bc"].append({"surface": "zmin", "fix": ["z"], "motion": [0.0, 0.0, 0.0]})
    sim = Simulation(sc, MPI.COMM_WORLD, log=quiet)
    sim.run()
    assert sim.contacts == [] and "contact" not in sim.timers.calls
    assert sim.problem.contacts == []
