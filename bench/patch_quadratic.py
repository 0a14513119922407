"""The contact patch test on non-matching meshes (scenes/blocks.toml: 5 × 5 slave
facets on 4 × 4 master facets) with trilinear and triquadratic hexahedra: the
σ_zz spread over the cells ((max − min)/|mean|, tests/reference/patch_spread.py)
and the Newton iterations of the two steps, for single-pass nodal, Gauss-point
and two-pass integration, the faceted and the smooth master, ε_N = 10³, 10⁴, 10⁵.
One process, no cut-back allowed (a step that does not converge is reported as
stopped).

    .venv/bin/python bench/patch_quadratic.py   # → bench/results/patch_quadratic.md, .jsonl

A benchmark reports; the assertions are in
tests/verification/test_quadratic_surface_contact.py and test_surface_contact.py."""
import json
import sys
import time
from pathlib import Path

from mpi4py import MPI

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from hypercontact import scene  # noqa: E402
from hypercontact.simulation import Simulation, StepFailure  # noqa: E402
from reference.patch_spread import sigma_zz_spread  # noqa: E402

OUT = ROOT / "bench" / "results"
PASSES = {"single pass": ("nodal", 1), "Gauss points": ("gauss", 1), "two-pass": ("nodal", 2)}


def run(degree, eps, integration, passes, master, work):
    s = scene.load(ROOT / "scenes" / "blocks.toml", overrides=[
        f"discretisation.degree={degree}", f"contact.0.eps_n={eps}", f'contact.0.integration="{integration}"',
        f"contact.0.passes={passes}", f'contact.0.master_surface="{master}"', "steps.max_cutbacks=0",
        "output.xdmf=false", f'output.dir="{work}"'])
    t = time.perf_counter()
    sim = Simulation(s, MPI.COMM_SELF, log=lambda m: None)
    try:
        writer = sim.run()
        its, spread = [st["newton_iterations"] for st in writer.steps], sigma_zz_spread(sim)
    except StepFailure:
        its, spread = None, None
    return {"degree": degree, "eps_n": eps, "integration": integration, "passes": passes, "master": master,
            "newton_its": its, "spread": spread, "wall_s": round(time.perf_counter() - t, 2)}


def main():
    import tempfile
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for degree in (2, 1):
            for eps in (1e3, 1e4, 1e5):
                for master in ("faceted", "smooth"):
                    for integration, passes in PASSES.values():
                        r = run(degree, eps, integration, passes, master, work)
                        print(json.dumps(r), flush=True)
                        rows.append(r)
    (OUT / "patch_quadratic.jsonl").write_text("".join(json.dumps(r) + "\n" for r in rows))
    cell = {(r["degree"], r["eps_n"], r["master"], r["integration"], r["passes"]): r for r in rows}
    lines = ["# The contact patch test on non-matching meshes: faceted and smooth masters", "",
             "σ_zz spread over the cells, (Newton iterations of the two steps), wall seconds; "
             "`bench/patch_quadratic.py`, one process.", ""]
    for degree, name in ((2, "27-node hexahedra"), (1, "8-node hexahedra")):
        lines += [f"## {name}", "", "| ε_N | master | " + " | ".join(PASSES) + " |",
                  "|---|---|" + "---|" * len(PASSES)]
        for eps in (1e3, 1e4, 1e5):
            for master in ("faceted", "smooth"):
                entries = []
                for integration, passes in PASSES.values():
                    r = cell[(degree, eps, master, integration, passes)]
                    entries.append("stops" if r["spread"] is None else
                                   f"{100 * r['spread']:.3g} % ({', '.join(map(str, r['newton_its']))}), "
                                   f"{r['wall_s']:.1f} s")
                lines.append(f"| {eps:.0e} | {master} | " + " | ".join(entries) + " |")
        lines.append("")
    (OUT / "patch_quadratic.md").write_text("\n".join(lines))


if __name__ == "__main__":
    main()
