"""The command line: built-in scenes, --np, Ctrl-C and --resume."""
import json
import os
import signal
import subprocess
import sys
import time

import pytest
from conftest import ROOT

CLI = [sys.executable, "-m", "hypercontact.cli"]
SMALL_PUNCH = ["--set", "mesh.n=4", "--set", "mesh.m=2"]


def test_scenes_lists_every_builtin_scene_with_its_title():
    out = subprocess.run(CLI + ["scenes"], capture_output=True, text=True, check=True).stdout
    for path in (ROOT / "scenes").glob("*.toml"):
        line = next(ln for ln in out.splitlines() if ln.startswith(path.stem + " "))
        assert len(line.split(None, 1)[1]) > 10, line  # a title, not just the name


def test_builtin_scene_by_name():
    result = subprocess.run(CLI + ["check", "punch"], capture_output=True, text=True)
    assert result.returncode == 0 and "valid" in result.stdout


@pytest.mark.slow
def test_np_runs_under_mpi(tmp_path):
    # as from a shell: without the MPI variables of this (MPI-initialised) test process
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMI", "PMIX"))}
    result = subprocess.run(CLI + ["run", str(ROOT / "scenes" / "punch.toml"), "--np", "2", "--out", str(tmp_path),
                                   *SMALL_PUNCH], capture_output=True, text=True, timeout=600, env=env)
    assert result.returncode == 0, result.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["ranks"] == 2 and summary["status"] == "completed"


@pytest.mark.slow
def test_ctrl_c_stops_cleanly_and_resume_completes(tmp_path):
    """SIGINT after the first converged step: exit 130, status 'interrupted',
    the converged steps on disk; --resume then completes the run."""
    args = CLI + ["run", str(ROOT / "scenes" / "sphere.toml"), "--out", str(tmp_path),
                  "--set", "mesh.n=4", "--set", "mesh.m=1", "--set", "steps.stop_value=85", "--set", "steps.max=0.05"]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    csv = tmp_path / "curves.csv"
    deadline = time.time() + 300
    while time.time() < deadline and proc.poll() is None:
        if csv.is_file() and len(csv.read_text().strip().splitlines()) >= 3:
            break
        time.sleep(0.05)
    assert proc.poll() is None, "the run ended before it could be interrupted"
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert "Traceback" not in err and "interrupted" in err
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["status"] == "interrupted"
    done = len(summary["steps"])
    assert done >= 2 and len(csv.read_text().strip().splitlines()) == done + 1
    resumed = subprocess.run(args + ["--resume"], capture_output=True, text=True, timeout=600)
    assert resumed.returncode == 0, resumed.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["status"] == "completed" and len(summary["steps"]) > done
