"""The generated forms' compiler flags (docs/performance.md §3) make the
assembly faster and change no bit of what it computes: the punch's Mooney
tangent and residual at a deformed state, compiled with the project's flags
and with dolfinx's default (-O2 -g0), are the same arrays, bit for bit."""
import tomllib

import numpy as np
import pytest
from mpi4py import MPI

from conftest import ROOT
from hypercontact import _dolfinx as dfx
from hypercontact import scene
from hypercontact.simulation import Simulation


def assembled(tmp_path, flags, monkeypatch):
    monkeypatch.setattr(dfx, "FORM_COMPILE_ARGS", flags)
    data = tomllib.loads((ROOT / "scenes" / "punch.toml").read_text())
    data["mesh"].update(n=4, m=1)
    data["output"]["xdmf"] = False
    sim = Simulation(scene.load(data, [f"output.dir={tmp_path}"]), MPI.COMM_SELF, log=lambda *a, **k: None)
    sim.set_load_factor(0.5)
    X = dfx.node_coordinates(sim.V)
    # a smooth finite deformation (stretches of ±10 %), so that J ≠ 1 and every pow() matters
    u = 0.1 * np.stack([np.sin(X[:, 1] / 13.0), np.cos(X[:, 0] / 17.0), np.sin(X[:, 2] / 3.0)], axis=1) * 5.0
    sim.w.x.array[:] = u.ravel()
    p = sim.problem
    x, b = p.x, p.b.duplicate()
    sim.w.vector.copy(x)
    p.residual(None, x, b)
    p.jacobian(None, x, p.A, p.A)
    return p.A.getValuesCSR()[2].copy(), b.array.copy()


def test_the_flags_change_no_bit_of_the_tangent_and_residual(tmp_path, monkeypatch):
    assert "-fno-math-errno" in dfx.FORM_COMPILE_ARGS and not any("march" in f for f in dfx.FORM_COMPILE_ARGS)
    A1, b1 = assembled(tmp_path / "project", list(dfx.FORM_COMPILE_ARGS), monkeypatch)
    A0, b0 = assembled(tmp_path / "default", ["-O2", "-g0"], monkeypatch)
    assert np.abs(b0).max() > 1e-3 and np.isfinite(A0).all()
    assert np.array_equal(A1, A0) and np.array_equal(b1, b0)


def test_fused_multiply_add_would_change_bits(tmp_path, monkeypatch):
    """The test above can fail: with FMA contraction (what -march=native brings on these
    processors) the same kernels round differently."""
    import platform

    if platform.machine() != "x86_64" or "fma" not in open("/proc/cpuinfo").read():
        pytest.skip("no FMA on this processor")
    A0, b0 = assembled(tmp_path / "default", ["-O2", "-g0"], monkeypatch)
    A2, b2 = assembled(tmp_path / "fma", ["-O2", "-g0", "-mfma", "-ffp-contract=fast"], monkeypatch)
    assert not (np.array_equal(A2, A0) and np.array_equal(b2, b0))
    assert np.abs(A2 - A0).max() <= 1e-12 * np.abs(A0).max()
