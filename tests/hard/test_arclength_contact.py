"""Arc-length continuation with contact active (issue #8): the inflated Mooney
sphere (scenes/sphere_plane.toml on a coarse 8 × 8 × 1 octant) against the
fixed rigid plane x = 116 mm, which the shell touches before the free
sphere's pressure maximum, followed through the limit point without and with
Coulomb friction.

The references do not come from the contact code: the 1D sphere oracle and
the same scene without the plane (before the first contact); the geometry of
the deformed shell (the pressure's resultant on the octant is p times the area
its inner surface encloses on a symmetry plane); a membrane bound on the
penetration; the energy balance of the frictional run against the
frictionless one; central differences of the residual for the tangent."""
import tomllib

import numpy as np
import pytest
import ufl
from mpi4py import MPI

from hypercontact import _dolfinx as dfx
from hypercontact import results, scene
from hypercontact.solve import path_following
from hypercontact.solve.continuation import ContinuationFailure
from hypercontact.forms import materials
from hypercontact.contact import OPEN, SLIP, STICK
from hypercontact.simulation import Simulation
from hypercontact.sphere1d import PAPER, Sphere, pressure_curve
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

from conftest import ROOT, quiet
from reference.finite_differences import assembled_and_fd_jacobians

PLANE_X, R_IN, R_OUT = 116.0, 95.0, 96.0
MU = 0.3
SYM = 8.0  # output.symmetry_factor: the CSV forces are for the whole sphere
PARAMS = dict(PAPER, K=5.0, i2="usual")
WRITE_STEP = results.ResultsWriter.write_step


def sphere_plane(mu=0.0, stop=100.0, contact=True):
    data = tomllib.loads((ROOT / "scenes" / "sphere_plane.toml").read_text())
    data["mesh"].update(n=8, m=1)
    data["output"]["xdmf"] = False
    data["steps"].update(initial=0.2, max=0.4, stop_value=stop)
    data["contact"][0]["mu"] = mu
    # the paper's sharp <-g>: the closed-form force below and the FD tangent (h = 1e-6, wider than
    # the default smoothing band of 2.5e-7 here) are those of the sharp law
    data["contact"][0]["smoothing"] = 0.0
    if not contact:
        data["contact"] = []
    return data


class Recorder:
    """Runs a scene and keeps, after every converged step, what the checks
    need: the displacement, the contact's evaluation and friction state,
    the support reactions, the pressure's resultant from the geometry, the
    cavity volume of the octant and the stored energy (strain energy plus the
    normal penalty's ½ ε_N Σ A g²)."""

    def __init__(self, data, out):
        sc = scene.load(data, [f"output.dir={out}"])
        self.sim = sim = Simulation(sc, MPI.COMM_SELF, log=quiet)
        mesh = sim.body.mesh
        self.X = dfx.node_coordinates(sim.V)
        ds = dfx.facet_integration_measure(mesh, sim.body.facet_tags, 4)
        F = ufl.Identity(3) + ufl.grad(sim.u)
        x = ufl.SpatialCoordinate(mesh) + sim.u
        # V = 1/3 ∮ x·n da; the cut planes through the centre add nothing (x·n = 0 there)
        self.volume_form = dfx.compile_form(-ufl.dot(x, ufl.det(F) * ufl.inv(F).T * ufl.FacetNormal(mesh)) / 3
                                            * ds(sim.body.surfaces["inner"]))
        psi = materials.LAWS["mooney_rivlin"][0](ufl.variable(F), **PARAMS)
        self.energy_form = dfx.compile_form(psi * ufl.dx(domain=mesh, metadata={"quadrature_degree": 2}))
        self.steps = []

    def run(self, monkeypatch):
        def write_step(writer, load_factor, *args, **kwargs):
            row = WRITE_STEP(writer, load_factor, *args, **kwargs)
            self.steps.append({**self.record(row), "residual": writer.steps[-1]["residual_norms"][-1]})
            return row

        monkeypatch.setattr(results.ResultsWriter, "write_step", write_step)
        self.writer = self.sim.run()
        return self

    def record(self, row):
        sim, u = self.sim, self.sim.u
        rec = {"row": row, "u": u.x.array.copy(), "p": row["pressure_inner"],
               "volume": dfx.assemble_scalar(self.volume_form, MPI.COMM_SELF),
               "energy": dfx.assemble_scalar(self.energy_form, MPI.COMM_SELF)}
        # the volume and pressure forms without Dirichlet rows: at a support dof the assembled
        # residual is the force the support exerts on the body
        b = dfx.assemble_vector_owned(sim.problem.R)
        f = b.array.reshape(-1, 3).copy()
        b.destroy()
        x = self.X + u.x.array.reshape(-1, 3)
        for axis, name in ((0, "x"), (1, "y")):
            on_plane = np.abs(self.X[:, axis]) < 1e-9
            rec[f"reaction_{name}"] = f[on_plane, axis].sum()
            rec[f"cut_area_{name}"] = cut_area(x[on_plane & (np.abs(np.linalg.norm(self.X, axis=1) - R_IN) < 1e-6)],
                                               [a for a in range(3) if a != axis])
        if sim.contacts:
            c = sim.contacts[0]
            rec["contact"] = c.evaluate(u)
            rec["x_slave"] = c.geometry.coordinates(u)
            gap = np.asarray(rec["contact"].gap)
            rec["energy"] += 0.5 * c.eps_n * np.sum(c.geometry.area * np.minimum(gap, 0.0) ** 2)
            if c.frictional:
                rec["friction"] = c.law.committed
                rec["dissipation_step"] = np.asarray(c.law.committed.dissipation).copy()
        return rec

    def column(self, key):
        return np.array([s[key] for s in self.writer.steps])


def cut_area(points, axes):
    """Area enclosed in the quarter plane by the polyline of the deformed inner
    surface's nodes on a cut plane and the two symmetry lines (shoelace, with the
    centre as the third corner). Exact for the faceted surface: its trace on the
    plane is straight between nodes."""
    a, b = points[:, axes[0]], points[:, axes[1]]
    order = np.argsort(np.arctan2(b, a))
    a, b = a[order], b[order]
    return 0.5 * np.sum(a[:-1] * b[1:] - a[1:] * b[:-1])


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The free sphere up to the plane's height, and the sphere against the
    plane without and with friction, through the limit point."""
    out = tmp_path_factory.mktemp("arclength_contact")
    with pytest.MonkeyPatch.context() as mp:
        free = Recorder(sphere_plane(contact=False, stop=30.0), out / "free").run(mp)
        plane = Recorder(sphere_plane(), out / "plane").run(mp)
        friction = Recorder(sphere_plane(mu=MU), out / "friction").run(mp)
    return {"free": free, "plane": plane, "friction": friction}


@pytest.mark.parametrize("case", ["plane", "friction"])
def test_passes_the_limit_point_with_contact_active(runs, case):
    """λ rises to one maximum and falls; the pole moves outward at every step;
    the shell touches the plane before the maximum and stays on it through it."""
    r = runs[case]
    lam, pole, closed = r.column("load_factor"), r.column("pole_uz"), r.column("wall_closed_nodes")
    assert np.all(np.isfinite(r.sim.u.x.array))
    assert len(r.writer.limit_points) == 1
    k = int(np.argmax(lam))
    assert 0 < k < len(lam) - 1
    assert np.all(np.diff(lam[:k + 1]) > 0) and np.all(np.diff(lam[k:]) < 0)
    assert np.all(np.diff(pole) > 0) and pole[-1] >= 100.0
    first = int(np.argmax(closed > 0))
    assert 0 < first < k and np.all(closed[first:] > 0)
    # the contact force grows throughout: the patch keeps taking load after the maximum
    fx = r.column("wall_fx")
    assert np.all(fx[:first] == 0) and np.all(np.diff(fx[first:]) < 0)


def test_before_contact_the_curve_is_the_free_spheres(runs):
    """While the shell is off the plane the run is the free sphere's: the same
    arc-length steps to round-off (the open contact adds nothing), on the 1D
    oracle's curve within the coarse mesh's error; and the plane is first met
    between the pressures at which the oracle's outer surface passes x = 116."""
    free, plane = runs["free"], runs["plane"]
    closed = plane.column("wall_closed_nodes")
    first = int(np.argmax(closed > 0))
    assert first >= 2
    for a, b in zip(free.steps[:first], plane.steps[:first]):
        assert b["p"] == pytest.approx(a["p"], rel=1e-12)
        assert np.max(np.abs(b["u"] - a["u"])) <= 1e-10 * np.max(np.abs(a["u"]))
    u_eq, p = free.column("pole_uz"), free.column("pressure_inner")
    assert np.max(np.abs(p / pressure_curve("mooney_rivlin", PARAMS, u_eq) - 1)) < 0.01
    # oracle: the inner displacement at which the outer surface reaches the plane, and its pressure
    def outer_radius(v):
        sol = Sphere("mooney_rivlin", PARAMS).solve(v)
        return sol.r[np.argmax(sol.R)]

    u_touch = brentq(lambda v: outer_radius(v) - PLANE_X, 10.0, 30.0)
    p_touch = pressure_curve("mooney_rivlin", PARAMS, u_touch)[0]
    p_run = plane.column("pressure_inner")
    assert p_run[first - 1] < p_touch * 1.01 and p_touch * 0.99 < p_run[first]


@pytest.mark.parametrize("case", ["plane", "friction"])
def test_penalty_law_and_penetration_bound(runs, case):
    """Normal force = Σ A_i ε_N ⟨x_i − 116⟩ over the slave nodes (gaps from the
    node coordinates), as the CSV reports it; no node is beyond the plane by
    more than a flat membrane pressed by the inner pressure p can push it: a
    flat membrane carries no normal load by its tension, so per reference area
    the plane takes p times the areal stretch, at most (r_max / R)² for a shell
    grown to radius r_max; the penetration is at most p (r_max/R)² / ε_N
    (×1.5), and once the apex node is inside a flat patch (stretched, areal
    stretch > 1) it is pressed in by at least p / ε_N."""
    r = runs[case]
    c = r.sim.contacts[0]
    seen_contact = False
    for s in r.steps:
        pen = np.maximum(s["x_slave"][:, 0] - PLANE_X, 0.0)
        normal = -np.sum(c.geometry.area * c.eps_n * pen)
        if case == "plane":
            assert SYM * normal == pytest.approx(s["row"]["wall_fx"], rel=1e-12, abs=1e-12)
        assert np.asarray(s["contact"].gap) == pytest.approx(PLANE_X - s["x_slave"][:, 0], abs=1e-12)
        if not pen.any():
            continue
        seen_contact = True
        x = r.X + s["u"].reshape(-1, 3)
        stretch2 = (np.linalg.norm(x, axis=1).max() / R_OUT) ** 2
        assert pen.max() <= 1.5 * s["p"] * stretch2 / c.eps_n
        if s["row"]["wall_closed_nodes"] >= 4:  # a flat patch around the apex node
            assert pen.max() >= s["p"] / c.eps_n
    assert seen_contact


@pytest.mark.parametrize("case", ["plane", "friction"])
def test_global_balance_on_the_octant(runs, case):
    """Forces on the octant along x: the pressure pushes it out with p × the
    area its inner surface encloses on x = 0 (closing the inner surface with
    the three cut planes, ∮ n da = 0 and only the x = 0 piece has n_x ≠ 0), the
    plane pushes back, the x = 0 support (the other half of the sphere) holds
    the rest; with friction the same along y, where the plane's tangential
    force enters. The imbalance is a sum of the converged residual over the free
    dofs of one direction, at most √n |R| (Cauchy–Schwarz); and every accepted
    step is in balance to far better than the forces involved (solver.rtol =
    1e-9 of the scene, here asked to 1e-7 of the pressure's push), also when
    the predictor pushed the shell deep into the plane."""
    r = runs[case]
    n = np.sqrt(len(r.X))
    for s in r.steps:
        row = s["row"]
        assert s["residual"] <= 1e-7 * s["p"] * s["cut_area_x"]
        for a in ("x", "y"):
            push = s["p"] * s[f"cut_area_{a}"]
            imbalance = s[f"reaction_{a}"] + push + row[f"wall_f{a}"] / SYM
            assert abs(imbalance) <= n * s["residual"] + 1e-12 * push
    # the plane takes a growing share of the push: at the end a sizeable part of it
    last = r.steps[-1]
    assert -last["row"]["wall_fx"] / SYM > 0.1 * last["p"] * last["cut_area_x"]


def test_friction_on_the_coulomb_cone_and_dissipation(runs):
    """Every slipping node is on the cone |t| = μ p_N to round-off, every
    sticking node inside it, open nodes carry nothing; the slip increment is
    along the traction (D = A t·Δs = μ p_N |Δs| A ≥ 0) and the accumulated
    dissipation never decreases. The shell slides outward on the plane (the
    patch is stretched by the free membrane), so friction pulls it back
    towards the axis: F_y = F_z < 0 (the octant is symmetric in y and z)."""
    r = runs["friction"]
    c = r.sim.contacts[0]
    slipping = 0
    for s in r.steps:
        st = s["friction"]
        if st is None:
            continue
        state = np.asarray(st.state)
        t = np.linalg.norm(np.asarray(st.traction), axis=1)
        pN = np.asarray(s["contact"].pressure)
        slip = state == SLIP
        slipping += slip.sum()
        assert np.allclose(t[slip], MU * pN[slip], rtol=1e-10, atol=0)
        assert np.all(t[state == STICK] <= MU * pN[state == STICK] * (1 + 1e-12))
        assert np.all(t[state == OPEN] == 0) and np.all(pN[state == OPEN] == 0)
        ds = np.asarray(st.slip_increment)
        assert np.all(np.einsum("ij,ij->i", np.asarray(st.traction), ds)[slip] > 0)
        D = np.asarray(st.dissipation)
        assert np.all(D >= 0)
        assert D == pytest.approx(MU * pN * np.linalg.norm(ds, axis=1) * c.geometry.area, rel=1e-12, abs=1e-300)
    assert slipping > 0
    D = r.column("dissipation")
    assert np.all(np.diff(D) >= 0) and D[-1] > 0
    fy, fz = r.column("wall_fy"), r.column("wall_fz")
    assert np.all(fy <= 0) and fy[-1] < 0
    assert fz == pytest.approx(fy, rel=1e-6)


def test_friction_stores_more_energy_and_needs_more_pressure(runs):
    """Energy: the frictionless equilibrium at cavity volume V (pressure p the
    multiplier of the volume) minimises the stored energy E = strain energy +
    ½ ε_N Σ A g² among all states of the octant with volume V; the frictional
    state at V is one of them, so E_friction(V) ≥ E_frictionless(V) (and the
    pressure's work is larger still, by the dissipation). Between computed
    points E_frictionless(V) is interpolated by cubic Hermite with its exact
    slope dE/dV = p. Pointwise: friction pulls the sliding patch back towards
    the axis, against the outward stretch the free shell imposes on it, so
    inflating the shell to the same pole displacement takes a higher pressure."""
    f, o = runs["friction"], runs["plane"]
    Vo, Eo, po = (np.array([s[k] for s in o.steps]) for k in ("volume", "energy", "p"))
    first = int(np.argmax(o.column("wall_closed_nodes") > 0))
    checked = 0
    for s in f.steps:
        V = s["volume"]
        if not Vo[first] <= V <= Vo[-1] or s["row"]["dissipation"] <= 0:
            continue
        k = min(np.searchsorted(Vo, V) - 1, len(Vo) - 2)
        h, t = Vo[k + 1] - Vo[k], (V - Vo[k]) / (Vo[k + 1] - Vo[k])
        E_o = ((2 * t**3 - 3 * t**2 + 1) * Eo[k] + (t**3 - 2 * t**2 + t) * h * po[k]
               + (-2 * t**3 + 3 * t**2) * Eo[k + 1] + (t**3 - t**2) * h * po[k + 1])
        assert s["energy"] >= E_o
        checked += 1
    assert checked >= 3
    # pressure against pole displacement, after both runs are in contact
    uo, uf = o.column("pole_uz"), f.column("pole_uz")
    pf = f.column("pressure_inner")
    spline = CubicSpline(uo[first:], po[first:])
    inside = (uf > uo[first + 1]) & (uf < uo[-1])
    assert inside.sum() >= 3
    assert np.all(pf[inside] > spline(uf[inside]))


def test_tangent_of_the_bordered_system_with_sliding_contact(runs, tmp_path, monkeypatch):
    """In the middle of an arc-length step with the shell sliding on the plane
    (friction history of the previous step, nodes slipping): the assembled
    K = ∂R/∂u, non-symmetric with friction, and q = ∂R/∂λ (the fixed plane
    adds nothing to it) against central differences of the residual; and the
    last Newton iterations of the contact steps converge quadratically."""
    rec = Recorder(sphere_plane(mu=MU, stop=60.0), tmp_path)
    sim = rec.sim
    checked = []
    original = path_following.continuation_step

    def step(bordered, constraint, x, lam, du_prev, set_load_factor, *args, **kwargs):
        Du, dlam, its, norms = original(bordered, constraint, x, lam, du_prev, set_load_factor, *args, **kwargs)
        c = sim.contacts[0]
        if not checked and np.count_nonzero(np.asarray(c.evaluate(sim.u).state) == SLIP) >= 2:
            problem = sim.problem
            free = np.flatnonzero(~np.isin(np.arange(x.getSize()), np.concatenate(
                [dfx.bc_dofs(bc) for bc in sim.bcs])))
            J, J_fd = assembled_and_fd_jacobians(problem, x, free, h=1e-6)
            scale = np.abs(J[np.ix_(free, free)]).max()
            assert np.abs(J[np.ix_(free, free)] - J_fd[np.ix_(free, free)]).max() < 1e-6 * scale
            asym = np.abs(J[np.ix_(free, free)] - J[np.ix_(free, free)].T).max()
            assert asym > 1e-3 * scale  # friction (and the follower pressure) make K non-symmetric
            # q against a central difference in λ
            b_p, b_m, h = problem.b.duplicate(), problem.b.duplicate(), 1e-6
            set_load_factor(lam + dlam + h)
            problem.residual(None, x, b_p)
            set_load_factor(lam + dlam - h)
            problem.residual(None, x, b_m)
            set_load_factor(lam + dlam)
            bordered.assemble(x)
            q_fd = (b_p.array - b_m.array) / (2 * h)
            assert np.abs(bordered.q.array[free] - q_fd[free]).max() < 1e-6 * np.abs(q_fd).max()
            checked.append(True)
        return Du, dlam, its, norms

    monkeypatch.setattr(path_following, "continuation_step", step)
    rec.run(monkeypatch)
    assert checked
    orders = []
    for s in rec.writer.steps:
        # above the round-off floor, which scales with the forces: 1e-13 of the step's first residual
        # (about 40 times the converged iterates here). A fixed floor of 1e-7 cut iterates five decades
        # above it and left the order to pre-asymptotic triples (one of them -200), whose median moved
        # across 1.6 with the OpenBLAS kernel.
        norms = s["residual_norms"]
        r = [v for v in norms if v > 1e-13 * norms[0]]
        if s["wall_closed_nodes"] > 0 and len(r) >= 3:
            orders.append(np.log(r[-1] / r[-2]) / np.log(r[-2] / r[-3]))
    assert len(orders) >= 3 and np.median(orders) > 1.6


def test_a_cut_back_leaves_no_trace_in_the_friction_history(tmp_path, monkeypatch):
    """The friction history (ξ, t, dissipation) changes only when the driver
    commits a converged arc-length step: no Newton iterate of a step, converged
    or failed, touches it. A failed attempt that iterated through the return
    mapping with trial slips and is cut back leaves no trace: the run ends
    exactly where a run that took the halved step directly ends."""
    calls = {"n": 0}
    original = path_following.continuation_step
    target = 6  # a step that starts with the shell on the plane and slides
    holder = {}

    def untouched(attempt):
        """Run attempt(); the friction history must be the same after it."""
        c = holder["sim"].contacts[0]
        before = (c.law.history.positions.copy(), c.law.history.traction.copy(), c.law.dissipation, c.law.history.lam_committed)
        try:
            return attempt()
        finally:
            assert np.array_equal(c.law.history.positions, before[0]) and np.array_equal(c.law.history.traction, before[1])
            assert (c.law.dissipation, c.law.history.lam_committed) == before[2:]

    def failing(bordered, constraint, x, lam, du_prev, set_load_factor, rtol, atol, max_it, **kw):
        calls["n"] += 1
        if calls["n"] == target:
            with pytest.raises(ContinuationFailure):
                untouched(lambda: original(bordered, constraint, x, lam, du_prev, set_load_factor, 1e-30, 0.0, 2, **kw))
            raise ContinuationFailure("forced by the test")
        return untouched(lambda: original(bordered, constraint, x, lam, du_prev, set_load_factor, rtol, atol, max_it,
                                          **kw))

    def halved(bordered, constraint, x, lam, du_prev, set_load_factor, rtol, atol, max_it, **kw):
        calls["n"] += 1
        if calls["n"] == target:
            constraint.scale(0.5)
        return untouched(lambda: original(bordered, constraint, x, lam, du_prev, set_load_factor, rtol, atol, max_it,
                                          **kw))

    ends, stories = [], {}
    for name, wrapper in (("failing", failing), ("halved", halved)):
        calls["n"] = 0
        monkeypatch.setattr(path_following, "continuation_step", wrapper)
        rec = Recorder(sphere_plane(mu=MU, stop=60.0), tmp_path / name)
        holder["sim"] = rec.sim
        rec.run(monkeypatch)
        c = rec.sim.contacts[0]
        assert rec.writer.steps[target - 2]["wall_closed_nodes"] > 0
        assert rec.writer.steps[target - 1]["wall_slip_nodes"] > 0
        ends.append((rec.sim.u.x.array.copy(), c.law.history.positions.copy(), c.law.history.traction.copy(), c.law.dissipation,
                     rec.column("load_factor")))
        stories[name] = rec.writer.failed_attempts
    # the cut-back's story is on disk (summary.json): which step, from where, what size, why
    [story] = stories["failing"]
    assert (story["step"], story["attempt"], story["reason"], story["outcome"]) == (target, 0, "forced by the test",
                                                                                    "cut back")
    assert story["load_factor"] == pytest.approx(rec.column("load_factor")[target - 2], rel=1e-12)
    assert stories["halved"] == []
    (u1, xi1, t1, d1, lam1), (u2, xi2, t2, d2, lam2) = ends
    assert len(lam1) == len(lam2) and np.allclose(lam1, lam2, rtol=1e-12, atol=0)
    assert np.abs(u1 - u2).max() <= 1e-10 * np.abs(u2).max()
    assert np.abs(xi1 - xi2).max() <= 1e-10 * np.abs(xi2).max()
    assert np.abs(t1 - t2).max() <= 1e-9 * np.abs(t2).max() and np.abs(t2).max() > 0
    assert d1 == pytest.approx(d2, rel=1e-9) and d2 > 0


def test_augmented_lagrangian_with_continuation_is_refused():
    """The Uzawa loop runs around the load-control Newton solve only: with
    arc length the scene is refused, naming the key."""
    data = sphere_plane()
    data["contact"][0]["enforcement"] = "augmented_lagrangian"
    with pytest.raises(scene.SceneError, match=r"contact\[0\]\.enforcement"):
        scene.load(data)
