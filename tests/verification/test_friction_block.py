"""Coulomb's law on a block: pressed onto a rigid frictional plane by a
constant normal force N, then pushed sideways by a growing prescribed motion
of its top face. While the push is below μN every node sticks and the
tangential displacement of the bottom comes from the tangential penalty
only; beyond it every node slides and the tangential reaction is μN. The
frictional dissipation is never negative, and in steady sliding each step
dissipates μN × the slip increment.

The references are independent of the code: N = ε_N A δ (a rigid block
pushed δ into the plane), T = ε_T A s λ in stick (a rigid block moved by
s λ), the stick limit at T = μN, the additive split of the tangential
displacement into an elastic part t/ε_T and slip, equilibrium (T = μN) and
the kinematics (the slip increment is the bottom's displacement increment
in steady sliding). The block is stiff (shear modulus G ≫ ε_T h), so the
rigid-block closed forms hold to a few ε_T h / G.

Also: a load step that fails and is cut back leaves the friction history
exactly as if the attempt had never been made."""
import csv

import h5py
import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.contact import SLIP, STICK
from hypercontact.results import ResultsWriter
from hypercontact.simulation import Simulation
from hypercontact.solve.newton_solver import NewtonSolver

G = 1.0e6        # shear modulus of the (rigid-ish) block, MPa
EPS = 10.0       # ε_N = ε_T, N/mm³
MU = 0.3
DELTA = 0.01     # the plane starts δ above the block's bottom: N = ε_N A δ for a rigid block
PUSH = 0.0065    # top face moved by λ × PUSH along x
AREA = 1.0       # bottom of the 1 × 1 × 1 block
N_REF = EPS * AREA * DELTA
LAMBDA_SLIDE = MU * N_REF / (EPS * AREA * PUSH)  # the push reaches μN: ≈ 0.46
RIGID = 5 * EPS * 1.0 / G  # relative accuracy of the rigid-block closed forms (block compliance)


def block_scene(out, mu=MU, xdmf=True):
    """A 2 × 2 × 1 neo-Hookean block on a rigid plane at z = δ; the top face
    held and moved by (λ s, 0, 0); y held on the sides ymin and ymax (so the
    block cannot spread sideways and slides exactly along x)."""
    return {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 2, "m": 1},
        "material": {"law": "neo_hookean", "parameters": {"mu": G, "K": G}},
        "bc": [{"surface": "zmax", "fix": ["x", "y", "z"], "motion": [PUSH, 0.0, 0.0]},
               {"surface": "ymin", "fix": ["y"]}, {"surface": "ymax", "fix": ["y"]}],
        "contact": [{"name": "base", "surface": "zmin", "obstacle": "plane", "point": [0.0, 0.0, DELTA],
                     "normal": [0.0, 0.0, 1.0], "eps_n": EPS, "eps_t": EPS, "mu": mu}],
        "steps": {"initial": 0.1, "max": 0.1},
        "solver": {"rtol": 1e-12, "atol": 1e-13, "max_it": 30, "linesearch": "basic"},
        "output": {"dir": str(out), "xdmf": xdmf, "symmetry_factor": 1.0},
    }


def gather(a):
    """This rank's per-node array joined with every other rank's."""
    return np.concatenate(MPI.COMM_WORLD.allgather(np.asarray(a)))


@pytest.fixture(scope="module", autouse=True)
def no_pictures():
    """These tests read numbers; drawing curves.png and deformed.png at the
    end of every run would be most of their time (tests/behaviour/test_results_output.py
    tests the pictures)."""
    with pytest.MonkeyPatch.context() as m:
        m.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})
        yield


def run_recording(data):
    """Run a scene, recording after every converged step the base's
    per-node state: (displacement, area, surface fields), all ranks."""
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet)
    (base,) = sim.contacts
    record, commit = [], base.commit

    def recording_commit():
        commit()
        fields = {k: gather(v) for k, v in base.law.point_fields(base.geometry.area).items()}
        u = sim.u
        record.append((gather(u.x.array.reshape(-1, 3)[base.geometry.nodes]), gather(base.geometry.area), fields))

    base.commit = recording_commit
    return sim, sim.run(), record


@pytest.fixture(scope="module")
def pushed(tmp_path_factory):
    comm = MPI.COMM_WORLD
    out = comm.bcast(str(tmp_path_factory.mktemp("pushed")) if comm.rank == 0 else None, root=0)
    return run_recording(block_scene(out))


@pytest.mark.mpi
def test_sticks_below_mu_n_then_slides_at_mu_n(pushed):
    sim, writer, record = pushed
    steps = writer.steps
    assert steps[-1]["load_factor"] == pytest.approx(1.0)
    stick = [k for k, s in enumerate(steps) if s["load_factor"] < LAMBDA_SLIDE * (1 - 10 * RIGID)]
    slide = [k for k, s in enumerate(steps) if s["load_factor"] > LAMBDA_SLIDE * (1 + 10 * RIGID)]
    assert len(stick) >= 3 and len(slide) >= 3 and len(stick) + len(slide) == len(steps)
    for k, s in enumerate(steps):
        U, A, fields = record[k]
        T, N = -s["base_fx"], s["base_fz"]
        assert N == pytest.approx(N_REF, rel=RIGID)  # the normal force stays N = ε_N A δ
        assert s["base_fy"] == pytest.approx(0.0, abs=1e-12 * N)
        if k in stick:
            # phase 1: every node sticks, the push is below μN and is carried by ε_T alone
            assert np.all(fields["status"] == STICK) and s["base_stick_nodes"] == len(A)
            assert 0 < T < MU * N
            assert T == pytest.approx(EPS * AREA * PUSH * s["load_factor"], rel=RIGID)  # rigid block moved by sλ
            u_t = U[:, 0]
            assert np.sum(A * u_t) == pytest.approx(T / EPS, rel=1e-9)  # mean u_t = T / (ε_T A), exactly
            np.testing.assert_allclose(u_t, T / (EPS * AREA), rtol=RIGID)  # and every node moves with it
            np.testing.assert_allclose(fields["traction"][:, 0], -EPS * u_t, rtol=1e-9)  # t = ε_T u_t, node by node
            assert s["base_dissipation_step"] == 0.0 and np.all(fields["slip_increment"] == 0.0)
        else:
            # phase 2: every node slides, the tangential reaction is μN
            assert np.all(fields["status"] == SLIP) and s["base_slip_nodes"] == len(A)
            assert T == pytest.approx(MU * N, rel=1e-6)
            assert np.all(fields["slip_increment"][:, 0] > 0)  # along the push
            np.testing.assert_allclose(fields["traction"][:, 1:], 0.0, atol=1e-12)


@pytest.mark.mpi
def test_dissipation_never_negative_and_mu_n_slip_in_steady_sliding(pushed):
    sim, writer, record = pushed
    steps = writer.steps
    total = 0.0
    for k, s in enumerate(steps):
        U, A, fields = record[k]
        assert np.all(fields["dissipation_step"] >= 0.0) and s["base_dissipation_step"] >= 0.0
        total += s["base_dissipation_step"]
        assert s["base_dissipation"] == pytest.approx(total, rel=1e-12, abs=1e-300)
        assert np.sum(A * fields["dissipation_step"]) == pytest.approx(s["base_dissipation_step"], rel=1e-12)
        assert s["dissipation_step"] == s["base_dissipation_step"] and s["dissipation"] == s["base_dissipation"]
        # additive split: tangential displacement = elastic t/ε_T + accumulated slip (monotone sliding)
        elastic = np.linalg.norm(fields["traction"], axis=1) / EPS
        np.testing.assert_allclose(fields["accumulated_slip"], U[:, 0] - elastic, rtol=0, atol=1e-9 * PUSH)
        if k >= 1 and s["base_slip_nodes"] == len(A) and steps[k - 1]["base_slip_nodes"] == len(A):
            # steady sliding: the slip increment is the bottom's displacement increment
            du = np.sum(A * (U[:, 0] - record[k - 1][0][:, 0])) / AREA
            assert du > 0
            assert s["base_dissipation_step"] == pytest.approx(MU * s["base_fz"] * du, rel=1e-6)
    assert total > 0
    # the same numbers are on disk: curves.csv, and the surface fields in fields.h5
    if MPI.COMM_WORLD.rank == 0:
        with open(writer.out / "curves.csv", newline="") as f:
            rows = list(csv.DictReader(f))
        assert [float(r["base_dissipation_step"]) for r in rows] == [s["base_dissipation_step"] for s in steps]
        with h5py.File(writer.out / "fields.h5", "r") as h5:
            X = h5["Mesh/mesh/geometry"][...]
            last = max(h5["Function/contact_dissipation_step"], key=lambda t: float(t.replace("_", ".")))
            d = h5[f"Function/contact_dissipation_step/{last}"][...].ravel()
            status = h5[f"Function/contact_status/{last}"][...].ravel()
            t = h5[f"Function/contact_tangential_traction/{last}"][...]
            tmag = h5[f"Function/contact_tangential_traction_magnitude/{last}"][...].ravel()
            p = h5[f"Function/contact_pressure/{last}"][...].ravel()
        bottom = np.abs(X[:, 2]) < 1e-12
        weight = lambda c: np.where(np.isclose(c, 0.5), 0.5, 0.25)  # nodal areas of the 2 × 2 bottom
        area = weight(X[:, 0]) * weight(X[:, 1])
        assert np.sum(area[bottom] * d[bottom]) == pytest.approx(steps[-1]["base_dissipation_step"], rel=1e-10)
        np.testing.assert_allclose(status[bottom], SLIP, atol=1e-12)
        np.testing.assert_allclose(status[~bottom], 0.0, atol=1e-12)
        np.testing.assert_allclose(tmag[bottom], MU * p[bottom], rtol=1e-9)  # on the Coulomb cone
        np.testing.assert_allclose(t[bottom, 0], -tmag[bottom], rtol=1e-9)  # against the push


def test_cut_back_restores_the_history_exactly(out_dir, monkeypatch):
    """The 6th Newton solve (a sliding step) fails and is cut back, in two
    ways: after a real solve (its iterates pass through the contact code,
    and even converge) or without any iteration. Both runs must end
    identically: the failed attempt leaves no trace in the history."""
    original_solve = NewtonSolver.solve

    def run(out, real_attempt):
        data = block_scene(out, xdmf=False)
        sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet)
        solve, calls = original_solve, []

        def failing_once(newton, *args):
            calls.append(sim.contacts[0].geometry.load_factor)
            if len(calls) != 6:
                return solve(newton, *args)
            if real_attempt:
                ok, its, norms, reason = solve(newton, *args)
                assert its >= 1 and ok  # the attempt iterated, through the contact code, to a solution
            return False, 0, [], "FORCED_FAILURE"

        with monkeypatch.context() as m:
            m.setattr(NewtonSolver, "solve", failing_once)
            return sim, sim.run(), calls

    sim_a, wa, calls_a = run(out_dir / "real", True)
    sim_b, wb, calls_b = run(out_dir / "none", False)
    assert calls_a == calls_b and calls_a[6] < calls_a[5]  # the 6th attempt was cut back
    assert calls_a[5] > LAMBDA_SLIDE  # ... in the sliding phase, with a non-trivial history
    assert [s["load_factor"] for s in wa.steps] == [s["load_factor"] for s in wb.steps]
    a, b = sim_a.contacts[0], sim_b.contacts[0]
    scale = np.abs(sim_b.u.x.array).max()
    assert np.abs(sim_a.u.x.array - sim_b.u.x.array).max() <= 1e-10 * scale
    assert np.abs(a.law.history.traction - b.law.history.traction).max() <= 1e-10 * np.abs(b.law.history.traction).max()
    assert np.abs(a.law.history.positions - b.law.history.positions).max() <= 1e-10 * np.abs(b.law.history.positions).max()
    assert np.abs(a.law.slip_accumulated - b.law.slip_accumulated).max() <= 1e-10 * b.law.slip_accumulated.max()
    assert a.law.dissipation == pytest.approx(b.law.dissipation, rel=1e-10) and b.law.dissipation > 0
    for sa, sb in zip(wa.steps, wb.steps):
        for key in ("base_fx", "base_fz", "base_dissipation_step", "base_dissipation"):
            assert sa[key] == pytest.approx(sb[key], rel=1e-10, abs=1e-300)


class Stop(Exception):
    pass


@pytest.mark.mpi
def test_resume_keeps_the_friction_history(pushed, out_dir):
    """Stopped after the 6th step (sliding) and resumed from the checkpoint:
    the same forces, dissipation and per-node accumulated slip and
    dissipation as the uninterrupted run."""
    sim_full, full, _ = pushed
    data = block_scene(out_dir, xdmf=False)
    logged = []

    def log(message):
        logged.append(message)
        if sum(m.startswith("step") for m in logged) == 6:
            raise Stop

    with pytest.raises(Stop):
        Simulation(scene.load(data), MPI.COMM_WORLD, log=log).run()
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet)
    resumed = sim.run(resume=True)
    assert len(resumed.steps) == len(full.steps)
    for a, b in zip(full.steps, resumed.steps):
        for key in ("load_factor", "base_fx", "base_fz", "base_dissipation_step", "base_dissipation"):
            assert b[key] == pytest.approx(a[key], rel=1e-10, abs=1e-300)
    a, b = sim_full.contacts[0], sim.contacts[0]
    for name, (x, y) in {"slip_accumulated": (a.law.slip_accumulated, b.law.slip_accumulated),
                         "dissipation_points": (a.law.dissipation_points, b.law.dissipation_points),
                         "traction": (a.law.history.traction, b.law.history.traction)}.items():
        diff = gather(x - y)
        assert np.abs(diff).max() <= 1e-10 * np.abs(gather(x)).max(), name
    assert gather(b.law.slip_accumulated).min() > 0
