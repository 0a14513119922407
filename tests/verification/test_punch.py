"""The frictionless rigid punch (docs/method.md §9.2) on a coarse mesh:
equilibrium, Newton's quadratic convergence, and independence of the number
of ranks."""
import csv

import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

COARSE = ["mesh.n=8", "mesh.m=2"]


def run_punch(comm, out, extra=()):
    sc = scene.load(ROOT / "scenes" / "punch.toml", [*COARSE, f"output.dir={out}", *extra])
    sim = Simulation(sc, comm, log=quiet)
    writer = sim.run()
    return sim, writer


@pytest.fixture(scope="module")
def punch(tmp_path_factory):
    comm = MPI.COMM_WORLD
    out = comm.bcast(str(tmp_path_factory.mktemp("punch")) if comm.rank == 0 else None)
    return run_punch(comm, out)


@pytest.mark.mpi
def test_punch_force_equals_base_reaction(punch):
    sim, writer = punch
    assert len(writer.steps) >= 4
    for step in writer.steps:
        f_punch, f_base = step["punch_fz"], step["base_fz"]
        assert f_punch < 0 < f_base
        assert abs(f_punch + f_base) <= 1e-8 * abs(f_punch)
    # the punch reaches its full indentation
    assert writer.steps[-1]["load_factor"] == pytest.approx(1.0)
    assert writer.steps[-1]["punch_displacement"] == pytest.approx(2.0)


def observed_orders(step):
    """Observed orders log(d_k+1/d_k) / log(d_k/d_k-1) of the Newton
    corrections d_k = |Δx_k| once the contact active set has settled,
    leaving out corrections at round-off level."""
    d = np.asarray(step["update_norms"])[max(step["active_set_settled_at"] - 1, 0):]
    d = d[d > 1e-12 * d.max()] if d.size else d
    return [np.log(d[k + 1] / d[k]) / np.log(d[k] / d[k - 1]) for k in range(1, len(d) - 1)]


@pytest.fixture(scope="module")
def punch_secant(tmp_path_factory):
    """The punch with each step's first attempt started from the secant
    predictor (steps.predictor = "secant")."""
    comm = MPI.COMM_WORLD
    out = comm.bcast(str(tmp_path_factory.mktemp("punch_secant")) if comm.rank == 0 else None)
    return run_punch(comm, out, ["steps.predictor=secant"])


@pytest.mark.mpi
def test_newton_converges_quadratically(punch, punch_secant):
    """Once the active set stops changing, Newton's corrections fall with an
    observed order near 2 (a modified Newton or a wrong tangent gives ~1)."""
    # converged far below the step's |R_0| (with the secant predictor the unpredicted one, from
    # the last converged state: the predictor starts most steps nearer the solution)
    _, predicted = punch_secant
    assert all(s["residual_reference"] > s["residual_norms"][0] for s in predicted.steps[1:])
    for _, w in (punch, punch_secant):
        assert all(s["residual_reference"] >= s["residual_norms"][0] for s in w.steps)
        assert all(np.asarray(s["residual_norms"])[-1] < 1e-9 * s["residual_reference"] for s in w.steps)
    sim, writer = punch  # from the last converged state: the most iterations to measure the order on
    orders = [o for step in writer.steps for o in observed_orders(step)]
    assert len(orders) >= 4, "too few settled iterations to measure the order"
    assert np.median(orders) >= 1.7, f"observed orders {orders}"


@pytest.mark.mpi
def test_results_on_disk(punch):
    sim, writer = punch
    if MPI.COMM_WORLD.rank == 0:
        rows = list(csv.DictReader(open(writer.out / "curves.csv")))
        assert len(rows) == len(writer.steps)
        assert float(rows[-1]["punch_fz"]) == pytest.approx(writer.steps[-1]["punch_fz"], rel=1e-12)
        assert (writer.out / "fields.xdmf").is_file() and (writer.out / "fields.h5").is_file()
        assert (writer.out / "summary.json").is_file()


@pytest.mark.mpi
def test_parallel_equals_serial(punch, tmp_path_factory):
    """Under mpirun -n 2: the distributed run equals a serial run (COMM_SELF)."""
    comm = MPI.COMM_WORLD
    sim, writer = punch
    out = tmp_path_factory.mktemp(f"serial{comm.rank}")
    _, serial = run_punch(MPI.COMM_SELF, out)
    f_par = np.array([s["punch_fz"] for s in writer.steps])
    f_ser = np.array([s["punch_fz"] for s in serial.steps])
    assert f_par.shape == f_ser.shape
    assert np.max(np.abs(f_par - f_ser)) <= 1e-8 * np.max(np.abs(f_ser))
    assert writer.steps[-1]["edge_uz"] == pytest.approx(serial.steps[-1]["edge_uz"], rel=1e-8, abs=1e-12)
