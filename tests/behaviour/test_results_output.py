"""What a run writes besides the curves: the cell fields in fields.xdmf
(Cauchy stress, von Mises, J), checked against the homogeneous closed form;
the pictures curves.png and deformed.png; and the refusal to write a
non-finite field."""
import csv
import json

import dolfinx.fem
import h5py
import matplotlib.image
import numpy as np
import pytest
import ufl
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import pictures, scene
from hypercontact.forms import materials
from hypercontact.results import NonFiniteField, ResultsWriter
from hypercontact.simulation import Simulation, StepFailure
from reference.homogeneous import compressed_block, mooney_rivlin_principal
from reference.block import D, EPS, PARAMS, block_scene

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def mooney_rivlin_stress(u):
    """P = ∂ψ/∂F of the block's law, written here independently of results.py."""
    F = ufl.variable(ufl.Identity(3) + ufl.grad(u))
    return ufl.diff(materials.mooney_rivlin(F, **PARAMS, i2="usual"), F)


def run_block(out, monkeypatch, stress=None, **steps):
    """The block of test_block_compression pressed by D between two planes,
    with the stress law handed to the results writer."""
    sc = block_scene(out)
    sc["output"]["xdmf"] = True
    sc["steps"].update(steps)
    sim = Simulation(scene.load(sc), MPI.COMM_WORLD, log=quiet)
    if stress is not None:
        sim.model.stress = stress  # the stress law the model hands to its results writer
    return sim, sim.run()


def last_frame(h5, name):
    """The values of a function at the last time written (dataset names are
    the times with '_' for '.')."""
    group = h5[f"Function/{name}"]
    return group[max(group, key=lambda t: float(t.replace("_", ".")))][...]


def assert_png(path, min_px=200):
    assert path.read_bytes()[:8] == PNG_SIGNATURE, f"{path.name} is not a PNG"
    image = matplotlib.image.imread(path)
    h, w = image.shape[:2]
    assert min_px <= h <= 3000 and min_px <= w <= 3000, f"{path.name} is {w} × {h} pixels"
    assert image[..., :3].std() > 0.02, f"{path.name} is blank"


@pytest.mark.mpi
def test_cell_fields_match_homogeneous_closed_form(out_dir, monkeypatch):
    sim, writer = run_block(out_dir, monkeypatch, stress=mooney_rivlin_stress)
    lat, l3, P3 = compressed_block(lambda a, b, c: mooney_rivlin_principal(a, b, c, **PARAMS), 1.0, D, EPS)
    J = lat**2 * l3
    s33 = P3 * l3 / J
    assert s33 < 0 and writer.steps[-1]["load_factor"] == pytest.approx(1.0)
    if MPI.COMM_WORLD.rank == 0:
        xdmf = (out_dir / "fields.xdmf").read_text()
        for name, kind in [("cauchy_stress", "Tensor"), ("von_mises", "Scalar"), ("J", "Scalar")]:
            assert f'<Attribute Name="{name}" AttributeType="{kind}" Center="Cell">' in xdmf
        with h5py.File(out_dir / "fields.h5", "r") as h5:
            sigma = last_frame(h5, "cauchy_stress")
            vm = last_frame(h5, "von_mises").ravel()
            Jh = last_frame(h5, "J").ravel()
        assert sigma.shape == (8, 9) and vm.shape == Jh.shape == (8,)  # 2 × 2 × 2 cells
        expected = np.zeros(9)
        expected[8] = s33
        np.testing.assert_allclose(sigma, np.tile(expected, (8, 1)), rtol=0, atol=1e-6 * abs(s33))
        np.testing.assert_allclose(vm, abs(s33), rtol=1e-6)
        np.testing.assert_allclose(Jh, J, rtol=1e-6)
        summary = json.loads((out_dir / "summary.json").read_text())
        assert {"displacement", "contact_gap", "contact_pressure", "J", "cauchy_stress",
                "von_mises"} == set(summary["fields"])


@pytest.mark.mpi
def test_pictures_of_a_one_step_run(out_dir, monkeypatch):
    """One load step: curves.csv has one row, and both pictures are drawn."""
    sim, writer = run_block(out_dir, monkeypatch, initial=1.0, max=1.0)
    assert len(writer.steps) == 1
    if MPI.COMM_WORLD.rank == 0:
        rows = list(csv.DictReader(open(out_dir / "curves.csv")))
        assert len(rows) == 1
        summary = json.loads((out_dir / "summary.json").read_text())
        assert summary["pictures"] == {"curves.png": "top_fz, base_fz against top_displacement",
                                       "deformed.png": "|u| on the deformed boundary at step 1"}
        assert_png(out_dir / "curves.png")
        assert_png(out_dir / "deformed.png")


@pytest.mark.mpi
def test_pictures_of_a_failed_run(out_dir):
    """A run that stops after some converged steps (step 3 is made to fail)
    still draws both pictures, of the last converged step."""
    sc = scene.load(ROOT / "scenes" / "punch.toml",
                    ["mesh.n=4", "mesh.m=2", f"output.dir={out_dir}", "steps.max_cutbacks=0"])
    sim = Simulation(sc, MPI.COMM_WORLD, log=quiet, fail_attempt=lambda step, lam, dlam, attempt: step == 3)
    with pytest.raises(StepFailure, match="from λ = 0.25 did not converge"):
        sim.run()
    if MPI.COMM_WORLD.rank == 0:
        summary = json.loads((out_dir / "summary.json").read_text())
        assert summary["status"] == "failed" and len(summary["steps"]) == 2
        assert summary["pictures"]["curves.png"] == "punch_fz, base_fz against punch_displacement"
        assert summary["pictures"]["deformed.png"].startswith("|u| on the deformed boundary at step 2")
        assert_png(out_dir / "curves.png")
        assert_png(out_dir / "deformed.png")


def test_picture_failure_does_not_stop_the_run(out_dir, monkeypatch):
    def broken(*args, **kwargs):
        raise ValueError("no ink")

    monkeypatch.setattr(pictures, "load_curves", broken)
    sim, writer = run_block(out_dir, monkeypatch, initial=1.0, max=1.0)
    summary = json.loads((out_dir / "summary.json").read_text())
    assert summary["status"] == "completed"
    assert summary["pictures"]["curves.png"] == "failed: ValueError: no ink"
    assert not (out_dir / "curves.png").exists()
    assert_png(out_dir / "deformed.png")


def test_load_curves_and_deformed_shape(tmp_path, monkeypatch):
    """The two drawing functions on their own: named columns, labels, a
    one-row csv, a cell field; a missing column names itself."""
    sim, writer = run_block(tmp_path, monkeypatch, stress=mooney_rivlin_stress, initial=1.0, max=1.0)
    png = pictures.load_curves(tmp_path / "curves.csv", tmp_path / "c.png", "top_displacement",
                               ["top_fz"], labels=["force of the top plane"])
    assert_png(png)
    with pytest.raises(KeyError, match="no column 'top_fzz'"):
        pictures.load_curves(tmp_path / "curves.csv", tmp_path / "x.png", "top_displacement", ["top_fzz"])
    assert_png(pictures.deformed_shape(sim.body.mesh, sim.u, writer.field_writer.von_mises, tmp_path / "vm.png", title="σ_vM"))
    assert_png(pictures.deformed_shape(sim.body.mesh, sim.u, "uz", tmp_path / "uz.png", scale=3.0))


@pytest.mark.mpi
def test_boundary_facets_gathered_once(out_dir, monkeypatch):
    """Every exterior facet of the 2 × 2 × 2 block exactly once over the ranks,
    at its deformed position (the homogeneous stretches), as a polygon that
    goes round the facet."""
    sim, writer = run_block(out_dir, monkeypatch, initial=1.0, max=1.0)
    polygons, colour, _ = pictures._local_surface(sim.body.mesh, sim.u, None, 1.0)
    everything = MPI.COMM_WORLD.allgather(polygons)
    polygons = np.concatenate(everything)
    assert polygons.shape == (6 * 4, 4, 3)
    centres = np.round(polygons.mean(axis=1), 9)
    assert len(np.unique(centres, axis=0)) == 24
    lat, l3, _ = compressed_block(lambda a, b, c: mooney_rivlin_principal(a, b, c, **PARAMS), 1.0, D, EPS)
    extent = polygons.reshape(-1, 3).max(axis=0) - polygons.reshape(-1, 3).min(axis=0)
    np.testing.assert_allclose(extent, [lat, lat, l3], rtol=1e-6)
    # each polygon walks around its facet: its four edges are sides, never a diagonal
    edges = np.linalg.norm(np.roll(polygons, -1, axis=1) - polygons, axis=2)
    is_side = np.isclose(edges, lat / 2, rtol=1e-6) | np.isclose(edges, l3 / 2, rtol=1e-6)
    assert is_side.all()


@pytest.mark.mpi
def test_non_finite_stress_stops_the_run_naming_field_and_step(out_dir, monkeypatch):
    def nan_stress(u):  # √(−J) is NaN in every cell
        return mooney_rivlin_stress(u) * ufl.sqrt(-ufl.det(ufl.Identity(3) + ufl.grad(u)))

    with pytest.raises(NonFiniteField, match=r"'cauchy_stress' \(72 of 72 values\), 'von_mises' \(8 of 8 values\) at step 1 "):
        run_block(out_dir, monkeypatch, stress=nan_stress)
    if MPI.COMM_WORLD.rank == 0:
        summary = json.loads((out_dir / "summary.json").read_text())
        assert summary["status"] == "failed" and "'cauchy_stress'" in summary["message"]
        assert summary["steps"] == [] and summary["pictures"] == {"skipped": "no converged step"}
        assert len(list(csv.reader(open(out_dir / "curves.csv")))) == 1  # the header only


@pytest.mark.mpi
def test_non_finite_displacement_names_the_step(out_dir, monkeypatch):
    sim, _ = run_block(out_dir / "run", monkeypatch, initial=1.0, max=1.0)
    u = dolfinx.fem.Function(sim.V, name="displacement")
    u.x.array[:] = sim.u.x.array
    writer = ResultsWriter(out_dir / "out", MPI.COMM_WORLD, sim.scene, sim.effects, u, sim.contacts,
                           sim.probes, stress=mooney_rivlin_stress)
    writer.write_step(1.0, 1, [1.0], sim.timers)
    if MPI.COMM_WORLD.rank == 0:
        u.x.array[0] = np.nan
    with pytest.raises(NonFiniteField, match=r"field 'displacement' \(1 of 81 values\) at step 2 \(load factor 1\)"):
        writer.write_step(1.0, 1, [1.0], sim.timers)
    assert len(writer.steps) == 1
