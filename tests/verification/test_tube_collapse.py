"""Continuation with self-contact (docs/verification.md, "Tube collapsed by
pressure"): the built-in scene scenes/tube_collapse.toml, a half tube under an
external follower pressure followed by arc length through its buckling and
on until its inner wall has folded onto itself and is squeezed. Checked
against references the run does not compute:

- the mirror model: the quarter tube whose inner wall meets a rigid
  frictionless plane at y = 0 (penalty 4 ε_N, see test_self_contact.py)
  must be in equilibrium, at the half model's final pressure, in the half
  model's final state (Newton on the quarter from that state moves nothing);
- the classical ring: before the fold, the ovality grows as w0 p / (p_cr − p)
  (a Southwell plot of the path gives p_cr) with p_cr = 3 D / R³ for a ring
  under hydrostatic pressure (D the plane-strain bending stiffness of the
  wall, R its mid-surface radius);
- the builder's ovality and the point bc against their definitions."""
import copy
import tomllib
from pathlib import Path

import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import _dolfinx as dfx
from hypercontact import scene
from hypercontact.geometry import tube_arrays
from hypercontact.scene import SceneError
from hypercontact.simulation import Simulation
from reference.runs import column, run

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "tube_collapse.toml"


@pytest.fixture(scope="module")
def collapsed(tmp_path_factory):
    data = tomllib.loads(SCENE.read_text())
    sim, w = run(data, tmp_path_factory.mktemp("tube_collapse"))
    return data, sim, w


def quarter_with_plane(data, eps_n):
    """The quarter model (θ from 0° to 90°, the cut face θ = 0 held on y = 0)
    whose inner wall meets the rigid frictionless plane y = 0."""
    q = copy.deepcopy(data)
    q["mesh"].update(angles=[0.0, 90.0], n=data["mesh"]["n"] // 2)
    q["bc"] = [dict(b, fix=["y"]) if b.get("surface") == "start" else b for b in q["bc"] if "point" not in b]
    q["contact"] = [{"name": "fold", "surface": "inner", "obstacle": "plane", "point": [0.0, 0.0, 0.0],
                     "normal": [0.0, 1.0, 0.0], "eps_n": eps_n}]
    q["steps"] = {}
    return q


def test_the_collapsed_half_tube_is_the_mirror_models_equilibrium(collapsed, tmp_path):
    data, sim, w = collapsed
    side = column(w, "side_ux")
    assert side[-1] >= data["steps"]["stop_value"]
    # the path went forward: the side point never moved back (a step that converged behind its
    # start would retrace the path towards the round tube)
    assert np.all(np.diff(side) > 0)
    assert column(w, "fold_closed_nodes")[-1] >= 8  # well past the touch
    lam = column(w, "load_factor")[-1]

    quarter = Simulation(scene.load(quarter_with_plane(data, 4 * sim.contacts[-1].eps_n),
                                    [f"output.dir={tmp_path}"]), MPI.COMM_SELF, log=lambda *a, **k: None)
    Xh, Xq = dfx.node_coordinates(sim.V), dfx.node_coordinates(quarter.V)
    d = np.linalg.norm(Xq[:, None, :] - Xh[None, :, :], axis=2)
    twin = d.argmin(axis=1)
    assert d.min(axis=1).max() < 1e-12  # every node of the quarter is a node of the half
    uh = sim.u.x.array.reshape(-1, 3)[twin]

    quarter.set_load_factor(lam)
    p = quarter.problem
    x, b = p.x, p.b.duplicate()
    x.array[:] = uh.ravel()  # the displacement formulation: the unknown is u, 3 per node
    norms = []
    for _ in range(6):
        p.residual(None, x, b)
        norms.append(np.abs(b.array).max())
        if norms[-1] < 1e-11:
            break
        p.jacobian(None, x, p.A, p.A)
        x.array[:] -= np.linalg.solve(p.A.copy().convert("dense").getDenseArray(), b.array)
    assert norms[-1] < 1e-11  # Newton on the quarter converged
    moved = np.abs(x.array - uh.ravel()).max()
    assert moved <= 1e-6 * np.abs(uh).max()

    # the walls overlap by twice the quarter's penetration of its plane (the pressure between
    # them carried by the points of both walls, as in test_self_contact.py)
    quarter.w.x.array[:] = x.array
    overlap = -np.asarray(sim.contacts[-1].evaluate(sim.u).gap).min()
    depth = -np.asarray(quarter.contacts[-1].evaluate(quarter.u).gap).min()
    assert depth > 0 and overlap == pytest.approx(2 * depth, rel=1e-3)


def test_before_the_fold_the_tube_buckles_at_the_ring_pressure(collapsed):
    """Southwell: w / p = w / p_cr + w0 / p_cr on the early path, w the ovalisation
    amplitude (side outwards plus crown inwards, halved: the uniform contraction
    cancels). A thick ring (t / R = 0.22) at finite strain: with selective reduced
    integration 1.093, 1.058, 1.050 × 3 D / R³ on 24 × 3, 48 × 6, 96 × 12 cells;
    fully integrated 24 × 3 cells lock (1.461 ×) and fail this."""
    data, sim, w = collapsed
    mat, mesh = data["material"]["parameters"], data["mesh"]
    mu, K = mat["mu"], mat["K"]
    E, nu = 9 * K * mu / (3 * K + mu), (3 * K - 2 * mu) / (2 * (3 * K + mu))
    t, R = mesh["thickness"], mesh["inner_radius"] + mesh["thickness"] / 2
    D = E / (1 - nu ** 2) * t ** 3 / 12
    p_ring = 3 * D / R ** 3

    p = data["pressure"][0]["value"] * column(w, "load_factor")
    amplitude = (column(w, "side_ux") - column(w, "crown_uy")) / 2
    early = (amplitude < 0.3) & (column(w, "fold_closed_nodes") == 0)
    assert early.sum() >= 4
    slope, intercept = np.polyfit(amplitude[early], amplitude[early] / p[early], 1)
    p_cr, w0 = 1 / slope, intercept / slope
    assert 1.0 <= p_cr / p_ring <= 1.15
    # the imperfection the fit sees is the builder's: Δ0 × the mid radius, within the same margin
    assert w0 == pytest.approx(mesh["ovality"] * R, rel=0.15)


def test_the_builders_ovality_scales_the_radius_by_1_plus_d_cos_2theta():
    d0 = 0.05
    x, *_ = tube_arrays(8.0, 2.0, 1.0, 12, 2, 1, (0.0, 90.0), ovality=d0)
    r, theta = np.hypot(x[:, 0], x[:, 1]), np.arctan2(x[:, 1], x[:, 0])
    x0, *_ = tube_arrays(8.0, 2.0, 1.0, 12, 2, 1, (0.0, 90.0))
    np.testing.assert_allclose(r, np.hypot(x0[:, 0], x0[:, 1]) * (1 + d0 * np.cos(2 * theta)), rtol=1e-14)
    on_x, on_y = np.abs(x[:, 1]) < 1e-12, np.abs(x[:, 0]) < 1e-12
    assert r[on_x].min() == pytest.approx(8.0 * (1 + d0)) and r[on_y].min() == pytest.approx(8.0 * (1 - d0))


def test_a_point_bc_holds_one_node_and_a_point_off_the_mesh_is_refused(tmp_path):
    data = tomllib.loads(SCENE.read_text())
    data["output"]["xdmf"] = False
    sim = Simulation(scene.load(data, [f"output.dir={tmp_path}"]), MPI.COMM_SELF, log=lambda *a, **k: None)
    X = dfx.node_coordinates(sim.V)
    pinned = sim.bcs[-1]
    dofs = dfx.bc_dofs(pinned)
    # the layer of one cell: the node at z = 0 only, its y component
    assert len(dofs) == 1 and dofs[0] % 3 == 1
    np.testing.assert_allclose(X[dofs[0] // 3], data["bc"][-1]["point"], atol=1e-12)

    data["bc"][-1]["point"] = [10.0, 0.0, 0.0]  # 0.1 inside the wall's outer surface
    with pytest.raises(SceneError, match=r"scene key 'bc\[4\]\.point': no mesh node at \[10\.0, 0\.0, 0\.0\] "
                                         r"\(nearest is 0\.1 away\)"):
        Simulation(scene.load(data, [f"output.dir={tmp_path}"]), MPI.COMM_SELF, log=lambda *a, **k: None)


@pytest.mark.mpi
def test_the_collapse_on_two_ranks_equals_serial(out_dir):
    """The whole arc-length path with self-contact and the point bc (its node owned by one
    rank, a ghost on the other): the same steps and columns as one process."""
    data = tomllib.loads(SCENE.read_text())
    data["output"]["xdmf"] = False
    _, par = run(data, out_dir / "par", MPI.COMM_WORLD)
    _, ser = run(data, out_dir / f"ser{MPI.COMM_WORLD.rank}", MPI.COMM_SELF)
    assert len(par.steps) == len(ser.steps)
    for key in ("load_factor", "side_ux", "crown_uy", "fold_closed_nodes"):
        assert column(par, key) == pytest.approx(column(ser, key), rel=1e-8, abs=1e-12), key
