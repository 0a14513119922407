"""The study command: a sweep's table, plot and Pareto front."""
import csv

import pytest

from hypercontact import _dolfinx
from hypercontact import cli
from hypercontact.study import cases_of, pareto_front, richardson


def test_pareto_front_is_the_set_of_non_dominated_points():
    points = [(1.0, 0.5), (2.0, 0.1), (3.0, 0.1), (0.5, 0.9), (2.5, 0.05), (4.0, 0.2)]
    # (3, 0.1) is beaten by (2, 0.1); (4, 0.2) by (2, 0.1); the rest trade time for error
    assert pareto_front(points) == [0, 1, 3, 4]
    assert pareto_front([(1.0, 1.0), (1.0, 1.0)]) == [0, 1]  # equal points do not beat each other


def test_richardson_recovers_a_known_limit_and_refuses_oscillation():
    # f(h) = 3 + 2 h² with h = 1/n: the limit 3 and order 2 exactly
    ns = [4, 8, 16]
    f_inf, unc, p = richardson(ns, [3 + 2 / n**2 for n in ns])
    assert f_inf == pytest.approx(3.0, rel=1e-12) and p == pytest.approx(2.0, rel=1e-12)
    assert unc == pytest.approx(2 / 16**2, rel=1e-9)
    with pytest.raises(ValueError, match="monotonically"):
        richardson(ns, [1.0, 1.1, 1.05])


def test_richardson_family_ignores_cases_that_change_other_settings():
    from hypercontact.study import mesh_family

    rows = [{"settings": "mesh.n=8", "mesh.n": 8}, {"settings": "mesh.n=16", "mesh.n": 16},
            {"settings": "mesh.n=16 contact.0.penalty_factor=10", "mesh.n": 16}, {"settings": "mesh.n=32", "mesh.n": 32}]
    assert [r["settings"] for r in mesh_family(rows)] == ["mesh.n=8", "mesh.n=16", "mesh.n=32"]


def test_cases_are_the_product_of_the_sweeps():
    study = {"sweep": [{"key": "mesh.n", "values": [2, 4]}, {"key": "solver.linesearch", "values": ["bt", "basic"]}]}
    assert cases_of(study) == [["mesh.n=2", 'solver.linesearch="bt"'], ["mesh.n=2", 'solver.linesearch="basic"'],
                               ["mesh.n=4", 'solver.linesearch="bt"'], ["mesh.n=4", 'solver.linesearch="basic"']]


def test_tiny_study_writes_table_plot_and_marks_the_front(tmp_path, scenes_dir):
    study = tmp_path / "tiny.toml"
    study.write_text(f'''
title = "tiny"
scene = "{scenes_dir / 'punch.toml'}"
set = ["contact.0.motion=[0.0, 0.0, -0.5]"]
quantity = "maxabs:punch_fz"
reference = 100.0
[[sweep]]
key = "mesh.n"
values = [2, 4]
[[sweep]]
key = "mesh.m"
values = [1]
''')
    out = tmp_path / "out"
    assert cli.main(["study", str(study), "--out", str(out)]) == 0
    # the console (on this test's captured stdout) no longer hears of JIT compilations: a later
    # compilation in this process would print into a closed stream
    assert _dolfinx._compiler_log.listener is None
    rows = list(csv.DictReader(open(out / "study.csv")))
    assert [r["settings"] for r in rows] == ["mesh.n=2 mesh.m=1", "mesh.n=4 mesh.m=1"]
    for r in rows:
        assert float(r["error"]) == pytest.approx(abs(float(r["value"]) - 100.0) / 100.0, rel=1e-12)
    points = [(float(r["wall_s"]), float(r["error"])) for r in rows]
    assert [r["pareto"] == "True" for r in rows] == [i in pareto_front(points) for i in range(len(rows))]
    assert (out / "study.png").stat().st_size > 1000
    assert "Cheapest within 1 %" in (out / "study.md").read_text()


def test_bad_study_is_rejected_naming_the_key(tmp_path, capsys):
    study = tmp_path / "bad.toml"
    study.write_text('scene = "punch"\nquantity = "mean:punch_fz"\nreference = 1.0\ncases = [[]]\n')
    assert cli.main(["study", str(study), "--out", str(tmp_path / "o")]) == 2
    assert "study key 'quantity'" in capsys.readouterr().err
