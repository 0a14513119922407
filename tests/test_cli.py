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


TINY_PUNCH = ["--set", "mesh.n=2", "--set", "mesh.m=1", "--set", "output.xdmf=false"]


def test_cold_form_cache_says_compiling_without_the_compiler_lines(tmp_path):
    """An empty FFCx cache: the C compiler's INFO lines (setuptools logs each
    command on the root logger) stay off the console; one line says that the
    forms are being compiled and how long it took. A second run, warm, says
    nothing about compiling."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMI", "PMIX"))}
    env["XDG_CACHE_HOME"] = str(tmp_path / "cache")
    args = CLI + ["run", str(ROOT / "scenes" / "punch.toml"), "--out", str(tmp_path / "out"), *TINY_PUNCH]
    cold = subprocess.run(args, capture_output=True, text=True, timeout=600, env=env)
    assert cold.returncode == 0, cold.stderr
    assert "INFO" not in cold.stdout + cold.stderr and "gcc" not in cold.stdout + cold.stderr
    first = cold.stdout.splitlines()[0]
    assert first.startswith("hypercontact: compiling the forms (first run, cached afterwards)… ")
    assert first.endswith(" s") and first.split()[-2].isdigit()
    warm = subprocess.run(args, capture_output=True, text=True, timeout=600, env=env)
    assert warm.returncode == 0, warm.stderr
    assert "compiling" not in warm.stdout and "INFO" not in warm.stdout + warm.stderr


def test_warnings_still_reach_the_console():
    """Only the compiler's chatter is dropped: a library's warning shows."""
    code = ("import logging; from hypercontact import cli; cli.console_logging(cli.Console()); "
            "logging.getLogger('somelib').warning('act on this'); logging.getLogger().info('not this')")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert "act on this" in result.stderr and "not this" not in result.stdout + result.stderr
