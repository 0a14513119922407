"""The inflated sphere (docs/method.md §9.1): the finite-element limit point
against the spherically symmetric 1D oracle, continuation past it, ranks
independence."""
import numpy as np
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation
from hypercontact.sphere1d import (PAPER, incompressible_limit_point, incompressible_pressure, limit_point,
                                 pressure_curve)

SCENE = ROOT / "scenes" / "sphere.toml"


def run_sphere(comm, out, overrides):
    sc = scene.load(SCENE, [f"output.dir={out}", "output.xdmf=false", *overrides])
    sim = Simulation(sc, comm, log=quiet)
    writer = sim.run()
    u = np.array([s["equator_ux"] for s in writer.steps])
    p = np.array([s["pressure_inner"] for s in writer.steps])
    return sim, writer, u, p


def vertex(u, p):
    """Limit point (u, p) from the parabola through the highest computed
    pressure and its two neighbours."""
    k = int(np.argmax(p))
    assert 0 < k < len(p) - 1, "the computed curve must bracket the maximum"
    a, b, c = np.polyfit(u[k - 1:k + 2], p[k - 1:k + 2], 2)
    return -b / (2 * a), c - b * b / (4 * a)


@pytest.mark.slow
@pytest.mark.parametrize("K, formulation, reach", [
    (1.0, "displacement", 1.3), (5.0, "displacement", 1.3), (200.0, "displacement", 2.05),
    # selective reduced integration leaves the spherical branch soon after
    # the maximum (docs/verification.md §5), so its curve is checked only just past it
    (1.0, "sri", 1.15), (5.0, "sri", 1.15), (200.0, "sri", 1.15)])
def test_limit_point_matches_1d_oracle(K, formulation, reach, out_dir):
    """16 × 16 × 4 octant, arc length: the limit pressure and the displacement
    at it within 1 % of the oracle, and every computed point, before and
    after the maximum (up to ``reach`` × the displacement at it), on the
    oracle's curve within 1 %."""
    params = dict(PAPER, K=K, i2="usual")
    u_ref, p_ref = limit_point("mooney_rivlin", params)
    sim, writer, u, p = run_sphere(MPI.COMM_WORLD, out_dir, [
        f"material.parameters.K={K}", f"discretisation.formulation={formulation}", "steps.max=0.15",
        f"steps.stop_value={reach * u_ref}"])
    assert len(writer.limit_points) == 1
    limit = writer.limit_points[0]
    assert limit["located"]
    p_max, u_max = 0.01 * limit["load_factor"], limit["probes"]["equator"][0]
    assert p_max == pytest.approx(p_ref, rel=0.01)
    assert u_max == pytest.approx(u_ref, rel=0.01)
    # the turn was detected at the computed maximum, and located at or above it
    assert limit["sampled_load_factor"] == pytest.approx(p.max() / 0.01, rel=1e-12)
    assert p_max >= p.max()
    # every computed point lies on the oracle's curve, before and after the maximum
    assert np.max(np.abs(p / pressure_curve("mooney_rivlin", params, u) - 1)) < 0.01
    assert u[-1] >= reach * u_ref * (1 - 1e-9) and p[-1] < p.max()


@pytest.mark.mpi
def test_sphere_parallel_equals_serial(out_dir):
    """Arc length through the limit point on a coarse octant: mpirun -n 2
    follows the same path as a serial run."""
    coarse = ["mesh.n=4", "mesh.m=1", "steps.initial=0.2", "steps.stop_value=50"]
    _, w_par, u_par, p_par = run_sphere(MPI.COMM_WORLD, out_dir / "par", coarse)
    _, w_ser, u_ser, p_ser = run_sphere(MPI.COMM_SELF, out_dir / f"ser{MPI.COMM_WORLD.rank}", coarse)
    assert len(w_par.limit_points) == len(w_ser.limit_points) == 1
    located_par, located_ser = w_par.limit_points[0], w_ser.limit_points[0]
    assert located_par["located"] and located_ser["located"]
    assert located_par["load_factor"] == pytest.approx(located_ser["load_factor"], rel=1e-8)
    assert located_par["probes"]["equator"] == pytest.approx(located_ser["probes"]["equator"], rel=1e-8)
    assert u_par.shape == u_ser.shape
    assert np.max(np.abs(u_par - u_ser)) <= 1e-8 * np.max(np.abs(u_ser))
    assert np.max(np.abs(p_par - p_ser)) <= 1e-8 * np.max(np.abs(p_ser))


@pytest.mark.slow
def test_incompressible_limit_with_mixed_formulation(out_dir):
    """K = inf with Taylor–Hood Q2–Q1 (8 × 8 × 2 octant): the limit point and
    the curve to twice its displacement against Ogden's closed form for the
    incompressible thick shell."""
    params = dict(PAPER, i2="usual")
    u_ref, p_ref = incompressible_limit_point("mooney_rivlin", params)
    sc = scene.load(ROOT / "scenes" / "sphere_incompressible.toml", [f"output.dir={out_dir}", "output.xdmf=false"])
    sim = Simulation(sc, MPI.COMM_WORLD, log=quiet)
    writer = sim.run()
    u = np.array([s["equator_ux"] for s in writer.steps])
    p = np.array([s["pressure_inner"] for s in writer.steps])
    assert len(writer.limit_points) == 1
    u_max, p_max = vertex(u, p)
    assert p_max == pytest.approx(p_ref, rel=0.01)
    assert u_max == pytest.approx(u_ref, rel=0.01)
    ref = np.array([incompressible_pressure("mooney_rivlin", params, x) for x in u])
    assert np.max(np.abs(p / ref - 1)) < 0.01
    assert u[-1] >= 2 * u_ref


def test_incompressible_needs_the_mixed_formulation(tmp_path):
    with pytest.raises(scene.SceneError, match="K = inf .* needs discretisation.formulation"):
        Simulation(scene.load(SCENE, ["material.parameters.K=inf", f"output.dir={tmp_path}"]),
                   MPI.COMM_SELF, log=quiet)
    with pytest.raises(scene.SceneError, match="degree >= 4"):
        Simulation(scene.load(ROOT / "scenes" / "sphere_incompressible.toml",
                              ["discretisation.quadrature_degree=2", f"output.dir={tmp_path}"]),
                   MPI.COMM_SELF, log=quiet)
