"""The rigid sphere obstacle (a ball, outside admissible) end to end.

References independent of the code:
- Hertz: a rigid sphere of radius R pressed by the depth d into the flat
  top of an elastic block (a quarter model: symmetry planes x = 0 and
  y = 0 through the sphere's axis, the bottom on rollers), frictionless.
  Hertz's closed form for a rigid indenter on a half-space,
  F_H = (4/3) E* √R d^{3/2}, E* = E/(1 − ν²), a = √(R d).
  Its model errors, none of them the code's: d/R = 0.0025 (a/R = 0.05:
  the paraboloid approximation of the sphere, against Sneddon's exact
  profile, changes F by −0.1 (a/R)² ≈ −0.03 %; finite strain enters at
  the order of the strain ~ a/R); the block is L = 40 a wide and deep on
  rollers, stiffer than the half-space (the Boussinesq displacement at
  r = L is 4 a/(3π L) ≈ 1 % of d); the automatic penalty leaves a
  penetration below 0.1 % of d (asserted).
  Tolerance 4 % at 16 graded cells per edge (about 4.7 across a): the
  discretisation error falls with the mesh, each coarser mesh is further
  off (asserted: 8 and 12 cells); when this test was written the errors
  were +23 %, +7.5 %, +1.5 % at 8, 12, 16 cells, and +2.5 % at 24 cells
  (50 s, not run here), where they are down to the model errors above
  (at 24 cells with L = 80 a: +1.8 %). 4 % is that floor, 2.5 %, with a
  margin, not the 1.5 % of a lucky crossing at 16.
- the same Hertz problem on quadratic elements (integration = "auto"):
  27-node hexahedra (nodal weights) at 8 cells per edge, 10-node tetrahedra
  (the graded box split six per cell; Gauss points) at 8. Measured
  (bench/results/hertz_elements.md): Q2 +22.7 %, +0.6 %, −1.3 %, +3.5 % at
  4, 6, 8, 10 cells, so Q2 reaches the floor above by 6–8 cells and then
  scatters by about ±3 % as the contact edge crosses nodes; its tolerance is
  the Q1 test's 4 % (the floor 2.5 % with a margin). P2 +50 %, +13.0 %,
  +10.0 % at 4, 6, 8 cells: still discretisation error (P1 is +9.6 % at 20
  cells; the Gauss points over-constrain the 6-node facets: pressures
  oscillate up to 4 p0 at the contact edge), and 12 cells cost > 5 min;
  its tolerance 12 % is that measured error, the floor's 2.5 % included,
  with a 2 % margin: a guard against regressions, not a claim of accuracy.
  Each coarser mesh is further off (asserted).
- a stiff block (G = 1e6 ≫ ε_N h) under a sphere of moderate radius: the
  body does not move, so each slave node's penetration is its overlap
  with the ball and the force is Σ ε_N A_i ⟨R − |X_i − c|⟩ n_i, with the
  nodal areas A_i of a uniform 2 × 2 top face (1/16, 1/8, 1/4) and
  n_i = (X_i − c)/|X_i − c|, off-centre so that Fx, Fy ≠ 0.
- phases (press, then slide the sphere with friction): the second phase
  starts where the first ended (the centre is carried) and full sliding
  transmits T = μ N, N the overlap force above of the moved ball (of huge
  radius: nearly flat, so every node's slip is along the sliding).
"""
import math

import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import _cpp, scene
from hypercontact.phases import run_phase
from hypercontact.results import ResultsWriter
from hypercontact.simulation import Simulation


@pytest.fixture(autouse=True)
def no_pictures(monkeypatch):
    monkeypatch.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})


def simulate(data, comm=MPI.COMM_WORLD):
    sim = Simulation(scene.load(data), comm, log=quiet)
    sim.run(out_dir=data["output"]["dir"])
    return sim, sim.contacts[0].force(sim.u)


# --- Hertz: a rigid sphere indenting an elastic block -------------------------------------------

E, NU = 1.0, 0.3
E_STAR = E / (1.0 - NU ** 2)  # the rigid indenter adds no compliance
R = 1.0
DEPTH = 0.0025 * R            # d/R = 0.0025: a = √(R d) = 0.05 R
A_HERTZ = math.sqrt(R * DEPTH)
L = 40.0 * A_HERTZ            # the block's width and depth
GRADING = 3.0                 # cell edges ∝ t³ towards the contact: about n (a/L)^(1/3) cells across a
MESHES = (8, 12, 16)          # cells per edge; the last is the one the tolerance is for
TOLERANCE = 0.04              # |F/F_H − 1| at the finest mesh (see the module text)


def hertz_force(d):
    """Hertz's total force of a rigid sphere (radius R) pressed d into a half-space."""
    return 4.0 / 3.0 * E_STAR * math.sqrt(R) * d ** 1.5


def indentation(out, n):
    """The quarter model at n × n × n graded cells; the sphere's axis is the line x = y = 0."""
    return {
        "mesh": {"builder": "box", "size": [L, L, L], "origin": [0.0, 0.0, -L], "n": n, "m": n,
                 "grading": [GRADING, GRADING, -GRADING]},
        "material": {"law": "neo_hookean", "parameters": {"mu": E / (2.0 * (1.0 + NU)),
                                                          "K": E / (3.0 * (1.0 - 2.0 * NU))}},
        "bc": [{"surface": "zmin", "fix": ["z"]}, {"surface": "xmin", "fix": ["x"]},
               {"surface": "ymin", "fix": ["y"]}],
        "contact": [{"name": "ball", "surface": "zmax", "obstacle": "sphere", "center": [0.0, 0.0, R],
                     "radius": R, "motion": [0.0, 0.0, -DEPTH]}],
        "steps": {"initial": 1.0, "max": 1.0},
        "output": {"dir": str(out), "xdmf": False, "symmetry_factor": 4.0},
    }


@pytest.fixture(scope="module")
def indented(tmp_path_factory):
    """n → (total force / Hertz's − 1, largest penetration / d, closed slave nodes)."""
    runs = {}
    for n in MESHES:
        sim, force = simulate(indentation(tmp_path_factory.mktemp(f"hertz{n}"), n), MPI.COMM_SELF)
        state = sim.contacts[0].evaluate(sim.u)
        runs[n] = dict(error=4.0 * abs(float(force[2])) / hertz_force(DEPTH) - 1.0,
                       penetration=-float(np.min(state.gap)) / DEPTH,
                       closed=int(np.sum(np.asarray(state.gap) <= 0.0)))
    return runs


def test_hertz_force_of_a_rigid_sphere_on_a_block(indented):
    fine = indented[MESHES[-1]]
    assert fine["closed"] >= 10      # the contact zone spans several slave nodes
    assert fine["penetration"] < 1e-3  # the penalty's share of the error is negligible
    assert abs(fine["error"]) <= TOLERANCE


def test_hertz_error_shrinks_under_refinement(indented):
    """The error of the finest mesh is discretisation error: each coarser mesh is further off."""
    errors = [abs(indented[n]["error"]) for n in MESHES]
    assert errors == sorted(errors, reverse=True), errors
    assert errors[0] > 2.0 * TOLERANCE


#: Quadratic elements: element → (cells, meshes (the last is the one the tolerance is for), tolerance).
QUADRATIC = {"Q2": ("hexahedra", (4, 8), 0.04), "P2": ("tetrahedra", (4, 6, 8), 0.12)}


@pytest.fixture(scope="module")
def indented_quadratic(tmp_path_factory):
    """element → [F/F_H − 1 per mesh of QUADRATIC] with degree 2 and integration = "auto"."""
    errors = {}
    for element, (cells, meshes, _) in QUADRATIC.items():
        errors[element] = []
        for n in meshes:
            data = indentation(tmp_path_factory.mktemp(f"hertz_{element}_{n}"), n)
            data["mesh"]["cells"] = cells
            data["discretisation"] = {"degree": 2}
            _, force = simulate(data, MPI.COMM_SELF)
            errors[element].append(4.0 * abs(float(force[2])) / hertz_force(DEPTH) - 1.0)
    return errors


@pytest.mark.parametrize("element", list(QUADRATIC))
def test_hertz_force_on_quadratic_elements(indented_quadratic, element):
    """Within the tolerance at the finest mesh (see the module text); each coarser mesh further off."""
    errors = [abs(e) for e in indented_quadratic[element]]
    tolerance = QUADRATIC[element][2]
    assert errors[-1] <= tolerance, indented_quadratic[element]
    assert errors == sorted(errors, reverse=True), indented_quadratic[element]
    assert errors[0] > 2.0 * tolerance


# --- Pressure and radius on a block with a uniform core under the contact ------------------------

#: The same block with uniform cells over 1.5 a under the ball (mesh.core) and graded t³ beyond:
#: element → (cells, degree, n). Measured (bench/results/hertz_elements.md, the "core" rows): the
#: trilinear sequence n = 16 … 28 converges to F/F_H − 1 = +2.52 %, p_pole/p0(F) − 1 = −1.06 %,
#: a_m/a(F) − 1 = −0.1 %; Q1 at 16 is at +2.42 / −1.04 / +0.53 %, Q2 at 14 at +2.05 / +0.12 / +0.27 %.
CORE = {"Q1": ("hexahedra", 1, 16), "Q2": ("hexahedra", 2, 14)}


def bottom_compliance():
    """Boussinesq: the vertical displacement, over d, that a half-space under Hertz's force F_H(d)
    has at the block's depth L on the axis, (1 + ν)(3 − 2ν) F / (2π E L) — the approach a block
    on rollers at depth L lacks, so that it carries F_H(d (1 + this)) ≈ F_H (1 + 1.5 this)."""
    return (1.0 + NU) * (3.0 - 2.0 * NU) * hertz_force(DEPTH) / (2.0 * math.pi * E * L) / DEPTH


@pytest.fixture(scope="module")
def cored(tmp_path_factory):
    """element → (F/F_H − 1, p_pole/p0(F) − 1, a_m/a(F) − 1, closed points): Hertz at the run's own
    force F (a(F) = (3FR/4E*)^(1/3), p0(F) = 3F/(2π a(F)²)); p_pole the pressure of the slave node on
    the axis; a_m from the second moment of the slave nodes' normal forces, Σ f r² / Σ f = (2/5) a² for
    Hertz's pressure (a radius from all the closed nodes, not the outermost one's position)."""
    from hypercontact.hertz import slave_points

    out = {}
    for element, (cells, degree, n) in CORE.items():
        data = indentation(tmp_path_factory.mktemp(f"hertz_core_{element}"), n)
        data["mesh"].update(cells=cells, core=[1.5 * A_HERTZ] * 3)
        data["discretisation"] = {"degree": degree}
        sim, force = simulate(data, MPI.COMM_SELF)
        contact = sim.contacts[0]
        _, x, gap, p = slave_points(contact, sim.u)
        f = p * np.asarray(contact.geometry.point_area)
        r = np.hypot(x[:, 0], x[:, 1])
        F = 4.0 * abs(float(force[2]))
        a_F = (3.0 * F * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
        p0_F = 3.0 * F / (2.0 * math.pi * a_F ** 2)
        a_m = math.sqrt(2.5 * np.sum(f * r ** 2) / np.sum(f))
        out[element] = (F / hertz_force(DEPTH) - 1.0, p[np.argmin(r)] / p0_F - 1.0, a_m / a_F - 1.0,
                        int(np.sum(gap <= 0.0)))
    return out


@pytest.mark.parametrize("element", list(CORE))
def test_hertz_peak_pressure_and_radius_on_a_cored_block(cored, element):
    """Against Hertz at the run's own force: the pole's pressure within 2 % (the set-up's own
    departure, measured on the converged trilinear sequence, is −1.1 %: nominal pressure and
    finite strain) and the radius within 2 %; the force above Hertz's by the rollers' missing
    compliance (Boussinesq, +2.7 % here; converged +2.5 %) to 1 %."""
    force, pole, radius, closed = cored[element]
    assert closed >= 10
    assert abs(pole) <= 0.02, cored[element]
    assert abs(radius) <= 0.02, cored[element]
    assert abs(force - 1.5 * bottom_compliance()) <= 0.01, (cored[element], 1.5 * bottom_compliance())


def test_trilinear_and_triquadratic_agree_on_the_cored_block(cored):
    """Two element families on the same block: pole pressure and radius within 1.5 %."""
    (_, p1, a1, _), (_, p2, a2, _) = cored["Q1"], cored["Q2"]
    assert abs(p1 - p2) <= 0.015 and abs(a1 - a2) <= 0.015, cored


# --- A stiff block: the force is the ball's overlap with the reference nodes --------------------

G = 1.0e6   # stiff block: the body moves by ~ε_N δ h / G, 1e-5 of the overlap
EPS = 10.0
MU = 0.3


def block(out, contact, mu=0.0):
    """A 1 × 1 × 1 block, bottom clamped, its top (the slave: 3 × 3 nodes) under the ball."""
    return {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 1.0], "n": 2, "m": 1},
        "material": {"law": "neo_hookean", "parameters": {"mu": G, "K": G}},
        "bc": [{"surface": "zmin", "fix": ["x", "y", "z"]}],
        "contact": [dict(name="ball", surface="zmax", eps_n=EPS, eps_t=EPS, mu=mu, **contact)],
        "steps": {"initial": 0.5, "max": 0.5},
        "solver": {"rtol": 1e-10, "atol": 1e-9, "max_it": 30},
        "output": {"dir": str(out), "xdmf": False, "symmetry_factor": 1.0},
    }


def sphere(center, radius, motion):
    return {"obstacle": "sphere", "center": list(center), "radius": radius, "motion": list(motion)}


#: The top face's nodes and their areas: 2 × 2 facets of 0.5 × 0.5.
TOP = [(np.array([x, y, 1.0]), (0.5 if x == 0.5 else 0.25) * (0.5 if y == 0.5 else 0.25))
       for x in (0.0, 0.5, 1.0) for y in (0.0, 0.5, 1.0)]


def overlap_force(center, radius):
    """Σ ε_N A_i ⟨R − |X_i − c|⟩ (X_i − c)/|X_i − c| over the top nodes, and how many overlap."""
    force, touching = np.zeros(3), 0
    for X, area in TOP:
        d = X - np.asarray(center)
        depth = radius - np.linalg.norm(d)
        if depth > 0:
            force += EPS * area * depth * d / np.linalg.norm(d)
            touching += 1
    return force, touching


def test_a_stiff_block_feels_the_balls_overlap_off_centre(out_dir):
    """A ball of radius 2 off the top's centre, lowered 0.05: two nodes overlap, Fx and Fy ≠ 0."""
    c0, radius, motion = np.array([0.6, 0.45, 3.0]), 2.0, np.array([0.0, 0.0, -0.05])
    expected, touching = overlap_force(c0 + motion, radius)
    assert touching == 2 and abs(expected[0]) > 1e-3 * abs(expected[2])
    _, force = simulate(block(out_dir, sphere(c0, radius, motion)))
    assert np.allclose(force, expected, rtol=1e-4, atol=1e-4 * abs(expected[2]))


def test_phases_press_then_slide_the_sphere_with_friction(out_dir):
    """A ball of huge radius: press δ, then slide 0.05 along x (≫ the elastic slip μ p/ε_T = 0.003).
    The slide starts where the press ended (the centre is carried: Fz stays the overlap of the
    moved ball, 0 had it jumped back) and drags the block along +x with T = μ N."""
    radius, delta, slide = 1.0e4, 0.01, np.array([0.05, 0.0, 0.0])
    c0 = np.array([0.5, 0.5, 1.0 + radius])
    sim = Simulation(scene.load(block(out_dir, sphere(c0, radius, [0.0, 0.0, 0.0]), mu=MU)), MPI.COMM_WORLD,
                     log=quiet)
    run_phase(sim, {}, out_dir / "press", obstacle_motions={0: [0.0, 0.0, -delta]})
    f_press = sim.contacts[0].force(sim.u)
    run_phase(sim, {}, out_dir / "slide", obstacle_motions={0: slide.tolist()})
    f_slide = sim.contacts[0].force(sim.u)
    pressed = c0 + np.array([0.0, 0.0, -delta])
    n_press, touching = overlap_force(pressed, radius)
    assert touching == 9
    assert f_press == pytest.approx(n_press, rel=1e-4, abs=1e-6 * abs(n_press[2]))
    n_slide, _ = overlap_force(pressed + slide, radius)
    assert f_slide[2] == pytest.approx(n_slide[2], rel=1e-4)
    assert f_slide[0] == pytest.approx(MU * abs(f_slide[2]), rel=2e-3)  # full slip along +x
    assert abs(f_slide[1]) < 1e-6 * abs(f_slide[2])
    assert np.all(np.asarray(sim.contacts[0].law.committed.state)[np.asarray(sim.contacts[0].geometry.area) > 0] == 2)


def test_sphere_keys_and_errors(tmp_path):
    ok = scene.load(block(tmp_path, sphere([0.5, 0.5, 3.0], 2.0, [0.0, 0.0, -0.05])))
    assert ok["contact"][0]["center"] == [0.5, 0.5, 3.0] and ok["contact"][0]["radius"] == 2.0
    bad = block(tmp_path, sphere([0.5, 0.5, 3.0], 2.0, [0.0, 0.0, -0.05]))
    del bad["contact"][0]["radius"]
    with pytest.raises(scene.SceneError, match=r"contact\[0\]\.radius.*sphere needs a radius > 0"):
        scene.load(bad)
    for key, owner in (("normal", "plane"), ("axis", "cylinder")):
        bad = block(tmp_path, dict(sphere([0.5, 0.5, 3.0], 2.0, [0.0, 0.0, -0.05]), **{key: [0.0, 0.0, 1.0]}))
        with pytest.raises(scene.SceneError, match=rf"contact\[0\]\.{key}': applies to obstacle = \"{owner}\""):
            scene.load(bad)
    with pytest.raises(ValueError, match="radius"):
        _cpp.RigidSphere([0, 0, 0], 0.0)
    with pytest.raises(ValueError, match="center"):
        _cpp.RigidSphere([0, 0, float("nan")], 1.0)
    assert _cpp.project(_cpp.RigidSphere([0, 0, 1], 0.5), [0.0, 0.3, 1.4]).gap == pytest.approx(0.0, abs=1e-15)
