"""The punch pressed on a frictionless base, then held while the base's μ
goes from 0 to 1 (scenes/punch_hold_mu.toml).

References independent of the phase code: Coulomb friction resists
increments of tangential motion, and a held punch moves nothing, so the
hold phase changes nothing — its force is the frictionless punch's
(scenes/punch.toml, run by the plain one-phase path) to the Newton
tolerance, every base node in contact sticks, nothing is dissipated; and
μ has reached 1 (the law was built frictional although the [[contact]]
entry says μ = 0)."""
import pytest
from conftest import quiet
from mpi4py import MPI

from hypercontact import scene
from hypercontact.results import ResultsWriter
from hypercontact.simulation import Simulation

COARSE = ["mesh.n=8", "mesh.m=2", "output.xdmf=false"]


@pytest.fixture(autouse=True)
def no_pictures(monkeypatch):
    monkeypatch.setattr(ResultsWriter, "draw_pictures", lambda self: {"skipped": "not drawn in this test"})


def run(path, out, extra=()):
    sim = Simulation(scene.load(path, overrides=COARSE + [f"output.dir={out}", *extra]), MPI.COMM_WORLD, log=quiet)
    return sim, sim.run()


def test_raising_the_base_friction_under_a_held_punch_changes_nothing(scenes_dir, out_dir):
    sim, held = run(scenes_dir / "punch_hold_mu.toml", out_dir / "held")
    _, plain = run(scenes_dir / "punch.toml", out_dir / "plain")
    press = [s for s in held.steps if s["phase"] == 1]
    hold = [s for s in held.steps if s["phase"] == 2]
    assert len(hold) >= 2 and hold[-1]["load_factor"] == pytest.approx(1.0)
    # the press is the frictionless punch, step by step
    assert [s["load_factor"] for s in press] == pytest.approx([s["load_factor"] for s in plain.steps], abs=1e-14)
    fz = plain.steps[-1]["punch_fz"]
    for a, b in zip(press, plain.steps):
        assert a["punch_fz"] == pytest.approx(b["punch_fz"], rel=1e-9)
    # the hold: the same force while μ rises; the base sticks where it touches; nothing dissipated
    for s in hold:
        assert s["punch_fz"] == pytest.approx(fz, rel=1e-9)
        assert s["base_fz"] == pytest.approx(plain.steps[-1]["base_fz"], rel=1e-9)
        assert s["base_closed_nodes"] > 0 and s["base_stick_nodes"] == s["base_closed_nodes"]
        assert s["base_slip_nodes"] == 0
        assert abs(s["dissipation"]) <= 1e-12 * abs(fz)
    punch, base = sim.contacts
    assert base.frictional and base.law.mu == pytest.approx(1.0) and not punch.frictional
    # the run says what it simulates: μ along the phases, the phases by name
    assert "Coulomb friction μ = 0 → 1" in sim.effects[1]
    assert "2 phases ('press', 'hold, base friction 0 → 1')" in sim.effects


def test_a_study_sweeps_the_phases_of_a_scene(scenes_dir, out_dir, tmp_path):
    """`hypercontact study` over the held punch, sweeping a phase's steps:
    every case ends at the frictionless punch's force (run here without
    phases), and each case ran with its phase setting."""
    import csv
    import json

    from hypercontact import cli

    _, plain = run(scenes_dir / "punch.toml", out_dir / "plain")
    reference = abs(plain.steps[-1]["punch_fz"])
    study = tmp_path / "hold.toml"
    study.write_text(f'''title = "held punch: the hold phase's step"
scene = "{scenes_dir / 'punch_hold_mu.toml'}"
set = {json.dumps(COARSE)}
quantity = "last:punch_fz"
reference = {-reference!r}
cases = [["phase.1.steps.initial=0.5", "phase.1.steps.max=0.5"],
         ["phase.1.steps.initial=0.25", "phase.1.steps.max=0.25"]]
''')
    out = tmp_path / "study"
    assert cli.main(["study", str(study), "--out", str(out)]) == 0
    rows = list(csv.DictReader(open(out / "study.csv")))
    assert [r["status"] for r in rows] == ["completed", "completed"]
    assert all(float(r["error"]) <= 1e-9 for r in rows)
    for k, initial in enumerate((0.5, 0.25)):
        summary = json.loads((out / f"case{k:02d}" / "summary.json").read_text())
        hold = summary["phases"][1]
        assert hold["steps"]["initial"] == hold["steps"]["max"] == initial
        assert hold["last_step"] - hold["first_step"] + 1 == round(1 / initial)
