"""Locking with contact, K/μ = 10³: a nearly incompressible neo-Hookean pad
bonded to its base and pressed by a frictionless rigid plate (quarter model).
The Taylor–Hood elements, P2–P1 on tetrahedra and Q2–Q1 on hexahedra, are two
independent discretisations of the same problem and must approach each other
as the meshes are refined; linear tetrahedra and trilinear hexahedra lock
(stiffer by an order of magnitude) and quadratic displacement-only tetrahedra
partly (≈ 10 %), which is what the test must tell apart from the mixed pair.
And from K/μ = 10³ to 10⁵ the mixed pair's force converges as F∞ + a/K where
linear tetrahedra stiffen with K."""
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

K_OVER_MU, PRESS = 1000.0, 0.05


def force(out, cells, degree, formulation, n, m, k_over_mu=K_OVER_MU):
    data = {
        "mesh": {"builder": "box", "size": [1.0, 1.0, 0.5], "n": n, "m": m, "cells": cells},
        "material": {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": k_over_mu}},
        "discretisation": {"degree": degree, "formulation": formulation,
                           "quadrature_degree": 4 if degree == 2 or formulation == "mixed" else 2},
        "bc": [{"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]},
               {"surface": "zmin", "fix": ["x", "y", "z"]}],
        "contact": [{"name": "plate", "surface": "zmax", "obstacle": "plane", "point": [0, 0, 0.5],
                     "normal": [0, 0, -1], "motion": [0, 0, -PRESS]}],
        "steps": {"initial": 0.5, "max": 1.0},
        "output": {"dir": str(out / f"{cells}{degree}{formulation}{n}K{k_over_mu:g}"), "xdmf": False,
                   "symmetry_factor": 4.0},
    }
    writer = Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet).run()
    assert writer.steps[-1]["load_factor"] == pytest.approx(1.0)
    return -writer.steps[-1]["plate_fz"]


def test_taylor_hood_tetrahedra_and_hexahedra_agree_where_linear_elements_lock(out_dir):
    sizes = (4, 8, 12)
    hexa = {n: force(out_dir, "hexahedra", 2, "mixed", n, n // 2) for n in sizes}
    tetra = {n: force(out_dir, "tetrahedra", 2, "mixed", n, n // 2) for n in sizes}
    gap = [abs(tetra[n] - hexa[n]) / hexa[n] for n in sizes]
    # the two mixed discretisations close in on each other as the mesh is refined, to within
    # 1 % on the 12 × 12 × 6 meshes
    assert gap[0] > gap[1] > gap[2]
    assert gap[2] < 0.01
    # what locks is far off at the coarse mesh: linear tetrahedra and hexahedra by more than 5 ×,
    # quadratic displacement-only tetrahedra by more than 5 %
    assert force(out_dir, "tetrahedra", 1, "displacement", 4, 2) > 5 * hexa[12]
    assert force(out_dir, "hexahedra", 1, "displacement", 4, 2) > 5 * hexa[12]
    assert force(out_dir, "tetrahedra", 2, "displacement", 4, 2) > 1.05 * hexa[12]


def test_taylor_hood_with_contact_is_locking_free_to_k_over_mu_1e5(out_dir):
    """K/μ = 10³, 10⁴, 10⁵ on the 4 × 4 × 2 pad: the force of a locking-free element
    converges to the incompressible limit as F∞ + a/K — each decade changes it about ten
    times less than the one before (measured 0.0043 then 0.0004 on both cell kinds), and
    10⁵ is within 1 % of 10³ (measured 0.21 %) — while linear tetrahedra stiffen with K
    (measured 43.7, 243 and 520)."""
    ks = (1e3, 1e4, 1e5)
    for cells in ("hexahedra", "tetrahedra"):
        f = [force(out_dir, cells, 2, "mixed", 4, 2, k) for k in ks]
        assert abs(f[2] - f[1]) < 0.2 * abs(f[1] - f[0]), (cells, f)
        assert abs(f[2] - f[0]) < 0.01 * f[0], (cells, f)
    linear = [force(out_dir, "tetrahedra", 1, "displacement", 4, 2, k) for k in ks[:2]]
    assert linear[1] > 3 * linear[0]
