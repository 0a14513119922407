"""Hard case: slave nodes exactly on master vertices and on master edges
(deformable–deformable node-to-surface contact, obstacle = "surface").

Two equal neo-Hookean blocks 1 × 1 × 0.5, stacked and touching (zero gap at
the start), confined laterally (x held on both x faces, y on both y faces of
each block) and compressed by moving the top face down by δ. The exact
solution is homogeneous uniaxial strain, F = diag(1, 1, λ) in both blocks,
whatever the contact mesh, as long as the contact transmits a uniform
pressure:

- matching meshes (2 × 2 facets on 2 × 2): every slave node sits exactly on
  a master vertex, where four master facets meet;
- the slave twice as fine (4 × 4 on 2 × 2): slave nodes sit on master
  vertices, at the midpoints of master edges (where two facets meet) and at
  facet centres. The slave nodal forces, split by the bilinear shape
  functions at the projections, are then exactly the master's consistent
  nodal forces of a uniform pressure, so the homogeneous state is still
  exact.

Closed form, independent of the code: the nominal stress of ψ = μ/2 (Ī1 − 3)
+ K/2 (J − 1)² in uniaxial strain, P(λ) = dψ/dλ with Ī1 = λ^(−2/3) (2 + λ²),
and the penalty's penetration −g = −P/ε_N (the pressure is ε_N times the
penetration, per reference area = current area here):
δ = 2 h (1 − λ) − P(λ)/ε_N, solved for λ by bisection. The contact force is
−P(λ) × area; every slave point carries the same pressure −P(λ)."""
import tomllib

import numpy as np
import pytest
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation

from conftest import ROOT

MU, K, EPS, H, DELTA = 1.0, 2.0, 1000.0, 0.5, 0.05


def nominal_stress(lam):
    """P_zz = dψ/dλ for F = diag(1, 1, λ)."""
    return 0.5 * MU * (-2.0 / 3.0 * lam ** (-5.0 / 3.0) * (2.0 + lam * lam) + 2.0 * lam ** (1.0 / 3.0)) \
        + K * (lam - 1.0)


def closed_form():
    """λ with 2 h (1 − λ) − P(λ)/ε_N = δ (bisection), and P(λ)."""
    lo, hi = 0.5, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if 2 * H * (1 - mid) - nominal_stress(mid) / EPS > DELTA:
            lo = mid
        else:
            hi = mid
    lam = 0.5 * (lo + hi)
    return lam, nominal_stress(lam)


def compressed_blocks(out, n_master, n_slave):
    data = tomllib.loads((ROOT / "scenes" / "blocks.toml").read_text())
    data["mesh"].update(n=n_master, m=1)
    data["body"][0].update(n=n_slave, m=1)
    data["contact"][0]["eps_n"] = EPS
    data["pressure"] = []
    data["bc"] = [{"surface": "zmin", "fix": ["z"]},
                  {"surface": "top.zmax", "fix": ["z"], "motion": [0.0, 0.0, -DELTA]}]
    for body in ("", "top."):
        data["bc"] += [{"surface": f"{body}{s}", "fix": [s[0]]} for s in ("xmin", "xmax", "ymin", "ymax")]
    data["steps"] = {"initial": 0.5, "max": 0.5}
    data["output"].update(dir=str(out), xdmf=False, probes={}, symmetry_factor=1.0)
    return data


@pytest.mark.parametrize("n_master, n_slave, where", [
    (2, 2, "on master vertices"),
    (2, 4, "on master vertices, edge midpoints and facet centres"),
])
def test_uniform_compression_through_vertices_and_edges(n_master, n_slave, where, tmp_path):
    sc = scene.load(compressed_blocks(tmp_path, n_master, n_slave))
    sim = Simulation(sc, MPI.COMM_SELF, log=lambda *a, **k: None)
    c = sim.contacts[0]
    # the slave nodes really sit where the case says: projections at ξ ∈ {−1, 0, 1} of the master facets
    sim.update_pairing(fresh=True)
    state0 = c.evaluate(sim.u)
    xi0 = np.round(np.asarray(state0.xi), 12)
    assert np.all(np.isin(xi0, [-1.0, 0.0, 1.0])), where
    on_vertex = np.all(np.abs(xi0) == 1.0, axis=1)
    on_edge = np.sum(np.abs(xi0) == 1.0, axis=1) == 1
    assert on_vertex.sum() == (n_master + 1) ** 2
    assert on_edge.sum() == (0 if n_slave == n_master else 2 * n_master * (n_master + 1))
    np.testing.assert_allclose(np.asarray(state0.gap), 0.0, atol=1e-14)  # touching at the start

    writer = sim.run()
    assert writer.steps[-1]["load_factor"] == pytest.approx(1.0)
    assert np.all(np.isfinite(sim.u.x.array))
    lam, P = closed_form()
    assert P < 0
    force = c.force(sim.u)
    assert force[2] == pytest.approx(-P * 1.0, rel=1e-8)  # area 1
    assert np.abs(force[:2]).max() <= 1e-10 * abs(P)
    state = c.evaluate(sim.u)
    p = np.asarray(state.pressure)
    assert np.all(np.asarray(state.gap) < 0)  # every slave point closed
    np.testing.assert_allclose(p, -P, rtol=1e-8)  # uniform pressure, the closed form's
    assert writer.steps[-1]["interface_fz"] == pytest.approx(-P, rel=1e-8)
