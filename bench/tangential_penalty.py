"""What the tangential penalty ε_T costs: Newton iterations, load steps and
force, at ε_T = ε_N (the default until 2026-12-04), 10 G/h (the automatic
default now) and 100 G/h, on four frictional cases (μ = 0.3):

- the README's rubber pad with friction on its base (load control);
- the O-ring between plates, n = m = 4, squeezed 18 % in four steps, on
  P2–P1 tetrahedra and on Q2–Q1 hexahedra (load control);
- the inflated sphere against a rigid plane (arc length through the limit
  point; its limit pressure from the parabola through the largest step).

    .venv/bin/python bench/tangential_penalty.py   # → bench/results/tangential_penalty.md, .json

G is the slave body's small-strain shear modulus and h its first element
layer, read off the automatic run's own note (summary.json "effects").
Each run is the CLI in a subprocess, one thread, stopped after TIMEOUT_S
(then reported with the steps it had converged). A benchmark reports; the
assertions are in tests/behaviour/test_automatic_penalty.py and
tests/verification/test_oring.py."""
import json
import os
import re
import subprocess
import time
import tomllib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CLI = ROOT / ".venv" / "bin" / "hypercontact"
OUT = ROOT / "bench" / "results"
WORK = Path("/tmp/bench_tangential_penalty")
TIMEOUT_S = 300
ORING = ["mesh.n=4", "mesh.m=4", "contact.0.motion=[0.0, 0.0, -0.36]", "contact.0.mu=0.3", "steps.initial=0.25",
         "steps.max=0.25"]


def readme_pad():
    """The complete scene of the README, with μ = 0.3 on its base (the commented-out line)."""
    text = (ROOT / "README.md").read_text()
    block = next(b for b in re.findall(r"```toml\n(.*?)```", text, re.S) if "[mesh]" in b)
    block = re.sub(r"^# mu = 0\.3 .*$", "mu = 0.3", block, flags=re.M)
    tomllib.loads(block)  # refuse a README whose scene does not parse here rather than in the CLI
    path = WORK / "pad.toml"
    path.write_text(block)
    return str(path)


CASES = {  # name → (scene, overrides, force column, contact with friction)
    "README pad, μ = 0.3 on the base": (None, [], "plate_fz", "base"),
    "O-ring P2–P1, n = m = 4, 18 %": (str(ROOT / "scenes" / "oring_plates.toml"),
                                      ORING + ["mesh.cells=tetrahedra"], "plate_fz", "plate"),
    "O-ring Q2–Q1, n = m = 4, 18 %": (str(ROOT / "scenes" / "oring_plates.toml"),
                                      ORING + ["mesh.cells=hexahedra"], "plate_fz", "plate"),
    "sphere against a plane, μ = 0.3, arc length": (str(ROOT / "scenes" / "sphere_plane.toml"),
                                                      ["contact.0.mu=0.3"], "wall_fx", "wall"),
}


def execute(scene, overrides, out):
    out.mkdir(parents=True, exist_ok=True)
    for f in ("curves.csv", "summary.json"):
        (out / f).unlink(missing_ok=True)
    args = [str(CLI), "run", scene, "--out", str(out)]
    for s in overrides + ["output.xdmf=false"]:
        args += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    t = time.perf_counter()
    try:
        with open(out / "log.txt", "w") as log:
            code = subprocess.run(args, stdout=log, stderr=subprocess.STDOUT, env=env, timeout=TIMEOUT_S).returncode
    except subprocess.TimeoutExpired:
        code = "timeout"
    wall = time.perf_counter() - t
    summary = json.loads((out / "summary.json").read_text()) if (out / "summary.json").exists() else {}
    return code, wall, summary


def limit_pressure(steps):
    y = np.array([s["pressure_inner"] for s in steps])
    x = np.array([s["pole_uz"] for s in steps])
    k = int(np.argmax(y))
    if k in (0, len(y) - 1):
        return float(y[k])
    a, b, c = np.polyfit(x[k - 1:k + 2], y[k - 1:k + 2], 2)
    return float(c - b * b / (4 * a))


def record(case, label, eps_t, code, wall, summary, column):
    steps = summary.get("steps", [])
    row = {"case": case, "eps_t": label, "eps_t_value": eps_t, "exit": code, "wall_s": wall,
           "status": summary.get("status", "no summary"), "steps": len(steps),
           "newton": sum(s["newton_iterations"] for s in steps),
           "newton_max": max((s["newton_iterations"] for s in steps), default=0),
           "failed_attempts": len(summary.get("failed_attempts", [])),
           "load_factor": steps[-1]["load_factor"] if steps else 0.0,
           "force": abs(steps[-1][column]) if steps else float("nan")}
    if steps and "pressure_inner" in steps[-1]:
        row["limit_kPa"] = 1000.0 * limit_pressure(steps)
    return row


def automatic_values(summary, contact):
    """(ε_N, G/h) from the run's note 'name: ε_N = … ; name: ε_T = … = 10 × G g / h h'."""
    note = next(e for e in summary["effects"] if e.startswith("automatic penalty"))
    eps_n = float(re.search(rf"{contact}: ε_N = ([0-9.eE+-]+)", note).group(1))
    G, h = (float(v) for v in re.search(rf"{contact}: ε_T = [0-9.eE+-]+ = 10 × G ([0-9.eE+-]+) / h ([0-9.eE+-]+)",
                                        note).groups())
    return eps_n, G / h


def main():
    import sys

    if "--report" in sys.argv:
        report(json.loads((OUT / "tangential_penalty.json").read_text()))
        return
    WORK.mkdir(parents=True, exist_ok=True)
    rows = []
    for case, (scene, overrides, column, contact) in CASES.items():
        scene = scene or readme_pad()
        tag = re.sub(r"[^a-z0-9]+", "_", case.lower())[:30]
        code, wall, summary = execute(scene, overrides, WORK / f"{tag}_auto")
        eps_n, g_over_h = automatic_values(summary, contact)
        rows.append(record(case, "10 G/h (default)", 10 * g_over_h, code, wall, summary, column))
        print(rows[-1], flush=True)
        for label, eps_t in (("ε_N (old default)", eps_n), ("100 G/h", 100 * g_over_h)):
            code, wall, summary = execute(scene, overrides + [f"contact.0.eps_t={eps_t:.6g}"],
                                          WORK / f"{tag}_{label.split()[0].replace('/', '')}")
            rows.append(record(case, label, eps_t, code, wall, summary, column))
            print(rows[-1], flush=True)
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "tangential_penalty.json").write_text(json.dumps(rows, indent=1, ensure_ascii=False))
    report(rows)


def report(rows):
    lines = ["# The tangential penalty: what ε_T costs", "",
             f"`bench/tangential_penalty.py` (one thread, the CLI in a subprocess, stopped after {TIMEOUT_S} s; "
             "`--report` rewrites this page from the JSON). Force: the last converged step's (N, whole body; "
             "the pad's plate, the O-ring's plate, the sphere's plane normal force — the sphere's runs end at "
             "different pole displacements, so its comparison is on the limit pressure). Newton: total over the "
             "converged steps (largest per step). Wall times on a 2-core machine shared with other jobs: compare "
             "within a case.",
             "", "| case | ε_T | value | status | steps | failed attempts | Newton (max) | wall s | force | "
             "limit kPa | against 100 G/h |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for case in dict.fromkeys(r["case"] for r in rows):
        rs = [r for r in rows if r["case"] == case]
        ref = next(r for r in rs if r["eps_t"] == "100 G/h")
        key = "limit_kPa" if "limit_kPa" in ref else "force"
        for r in rs:
            dev = (f"{100 * (r[key] / ref[key] - 1):+.2f} % ({'limit' if key == 'limit_kPa' else 'force'})"
                   if r["status"] == "completed" and ref["status"] == "completed" else "—")
            status = r["status"] if r["exit"] != "timeout" else f"stopped at {TIMEOUT_S} s, λ = {r['load_factor']:.3g}"
            limit = f"{r['limit_kPa']:.4f}" if "limit_kPa" in r else ""
            lines.append(f"| {case} | {r['eps_t']} | {r['eps_t_value']:.4g} | {status} | {r['steps']} | "
                         f"{r['failed_attempts']} | {r['newton']} ({r['newton_max']}) | {r['wall_s']:.1f} | "
                         f"{r['force']:.4g} | {limit} | {dev} |")
    (OUT / "tangential_penalty.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
