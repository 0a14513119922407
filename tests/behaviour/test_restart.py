"""A run stopped after some steps and resumed from its checkpoint ends with
the same results as an uninterrupted run."""
import json

import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation


class Stop(Exception):
    pass


def run(scene_name, out, overrides, stop_after=None, resume=False):
    sc = scene.load(ROOT / "scenes" / scene_name, [f"output.dir={out}", *overrides])
    steps = []

    def log(message):
        if message.startswith("step"):
            steps.append(message)
            if stop_after is not None and len(steps) == stop_after:
                raise Stop  # as if the process were killed right after this step

    sim = Simulation(sc, MPI.COMM_WORLD, log=log)
    return sim, sim.run(resume=resume)


CASES = {
    "load control (punch)": ("punch.toml", ["mesh.n=4", "mesh.m=2"], 3),
    "arc length (sphere)": ("sphere.toml", ["mesh.n=4", "mesh.m=1", "steps.stop_value=50"], 5),
}


@pytest.mark.mpi
@pytest.mark.parametrize("case", list(CASES))
def test_resume_equals_uninterrupted(case, out_dir):
    name, overrides, k = CASES[case]
    sim_full, full = run(name, out_dir / "full", overrides)
    with pytest.raises(Stop):
        run(name, out_dir / "cut", overrides, stop_after=k)
    sim_res, resumed = run(name, out_dir / "cut", overrides, resume=True)
    assert len(resumed.steps) == len(full.steps) > k
    for a, b in zip(full.steps, resumed.steps):
        assert a["load_factor"] == pytest.approx(b["load_factor"], rel=1e-10, abs=1e-14)
    diff = np.abs(sim_full.w.x.array - sim_res.w.x.array).max()
    scale = np.abs(sim_full.w.x.array).max()
    assert MPI.COMM_WORLD.allreduce(diff, op=MPI.MAX) <= 1e-10 * MPI.COMM_WORLD.allreduce(scale, op=MPI.MAX)
    if MPI.COMM_WORLD.rank == 0:
        summary = json.loads((out_dir / "cut" / "summary.json").read_text())
        assert summary["status"] == "completed" and len(summary["steps"]) == len(full.steps)
        rows = (out_dir / "cut" / "curves.csv").read_text().strip().splitlines()
        assert len(rows) == 1 + len(full.steps)
        xdmf = (out_dir / "cut" / "fields.xdmf").read_text()
        assert xdmf.count('<Grid Name="displacement" GridType="Uniform"') == len(full.steps)


def test_resume_without_checkpoint_says_so(tmp_path):
    sc = scene.load(ROOT / "scenes" / "punch.toml", ["mesh.n=2", "mesh.m=1", f"output.dir={tmp_path}"])
    with pytest.raises(FileNotFoundError, match="no checkpoint"):
        Simulation(sc, MPI.COMM_SELF, log=quiet).run(resume=True)
