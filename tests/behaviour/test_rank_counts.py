"""The same answer on 1, 2, 3 and 4 ranks.

The frictional punch (μ1 = 0.3, history-dependent stick/slip states on every
slave node) and the two-body Hertz scene with two passes (a deformable master
on both sides, nodes of one body slave to facets owned by other ranks) run
through the command line under `mpirun -n k` (oversubscribed on this 2-core
machine) and serially. Every number in curves.csv (forces, probes, closed,
stick and slip counts, dissipation, Newton iterations) must agree with the
serial run to 1e-8 of that column's largest value, and the runs must take the
same steps with the same Newton iterations: a rank count that changed the
active set or the step control would show here first.

Partitions with 3 and 4 ranks of these coarse meshes leave ranks with no slave
node or no master facet of a contact, which the two-rank tests do not reach.
"""
import csv
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HYPERCONTACT = str(Path(sys.executable).with_name("hypercontact"))

CASES = {
    "punch_mu0.3": ("punch_mu0.3_0.toml", ["mesh.n=8", "mesh.m=2"]),
    "hertz_two_pass": ("hertz.toml", ["mesh.n=8", "mesh.m=8", "body.0.n=6", "body.0.m=6", "contact.0.passes=2"]),
}
RANKS = (2, 3, 4)
REL = 1e-8


def run(scene, sets, out, ranks):
    cmd = [HYPERCONTACT, "run", str(ROOT / "scenes" / scene), "--out", str(out)]
    for s in sets:
        cmd += ["--set", s]
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks), "--allow-run-as-root", "--oversubscribe", *cmd]
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)
    assert proc.returncode == 0, f"{ranks} ranks: {' '.join(cmd)}\n{proc.stdout[-2000:]}\n{proc.stderr[-2000:]}"
    with open(out / "curves.csv") as f:
        return list(csv.DictReader(f))


def numeric_columns(rows):
    cols = {}
    for key in rows[0]:
        try:
            cols[key] = [float(r[key]) for r in rows]
        except ValueError:
            continue
    return cols


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="needs mpirun")
@pytest.mark.parametrize("case", sorted(CASES))
def test_one_to_four_ranks_agree(case, tmp_path):
    scene, sets = CASES[case]
    serial = numeric_columns(run(scene, sets, tmp_path / "np1", 1))
    assert len(serial["step"]) >= 3
    assert max(serial["newton_iterations"]) > 1
    for ranks in RANKS:
        par = numeric_columns(run(scene, sets, tmp_path / f"np{ranks}", ranks))
        assert set(par) == set(serial), f"{ranks} ranks wrote other columns"
        assert par["step"] == serial["step"], f"{ranks} ranks took other steps"
        assert par["load_factor"] == serial["load_factor"], f"{ranks} ranks: other load factors"
        assert par["newton_iterations"] == serial["newton_iterations"], f"{ranks} ranks: other Newton counts"
        for key, ref in serial.items():
            scale = max(abs(v) for v in ref)
            if key == "linear_iterations":
                continue
            worst = max(abs(a - b) for a, b in zip(par[key], ref))
            assert worst <= REL * scale, f"{case}, {ranks} ranks: {key} differs by {worst:.3e} (scale {scale:.3e})"
