"""A Newton iterate that inverts elements (J ≤ 0) makes the residual NaN:
the step is cut back, never a NaN in the results."""
import csv

import h5py
import numpy as np
import pytest

from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation, StepFailure
from reference.homogeneous import compressed_block, mooney_rivlin_principal
from test_block_compression import PARAMS, block_scene

EPS = 1e4


def squeeze(out, d, max_it=25):
    sc = block_scene(out)
    sc["solver"]["max_it"] = max_it
    sc["steps"] = {"initial": 1.0, "max": 1.0, "max_cutbacks": 4}
    sc["output"]["xdmf"] = True
    sc["contact"][0]["motion"] = [0.0, 0.0, -d]
    for c in sc["contact"]:
        c["eps_n"] = EPS
    messages = []
    sim = Simulation(scene.load(sc), MPI.COMM_WORLD, log=messages.append)
    return sim, messages


def all_finite(out):
    rows = list(csv.DictReader(open(out / "curves.csv")))
    values = np.array([[float(v) for v in row.values()] for row in rows])
    with h5py.File(out / "fields.h5", "r") as h5:
        fields = [h5["Function/displacement"][k][:] for k in h5["Function/displacement"]]
    return len(rows), np.all(np.isfinite(values)) and all(np.all(np.isfinite(f)) for f in fields)


@pytest.mark.mpi
def test_inverting_step_is_cut_back_and_recovers(out_dir):
    """70 % compression in one step: the first Newton iterate inverts elements;
    the step is halved and the run ends on the closed-form state."""
    sim, messages = squeeze(out_dir, 0.7)
    writer = sim.run()
    assert any("DIVERGED_FNORM_NAN" in m for m in messages), messages
    assert writer.steps[-1]["load_factor"] == pytest.approx(1.0)
    _, _, P3 = compressed_block(lambda a, b, c: mooney_rivlin_principal(a, b, c, **PARAMS), 1.0, 0.7, EPS)
    assert sim.contacts[0].force(sim.u)[2] == pytest.approx(P3, rel=1e-6)
    if MPI.COMM_WORLD.rank == 0:
        n, finite = all_finite(out_dir)
        assert n == len(writer.steps) and finite


@pytest.mark.mpi
def test_impossible_squeeze_stops_with_a_diagnosis(out_dir):
    """The top plane driven through the base: no equilibrium exists beyond a
    point; the run stops with a message, keeping only finite results."""
    sim, messages = squeeze(out_dir, 1.5, max_it=10)
    with pytest.raises(StepFailure, match="did not converge"):
        sim.run()
    if MPI.COMM_WORLD.rank == 0:
        n, finite = all_finite(out_dir)
        assert finite
