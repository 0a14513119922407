"""The results of a run, in one folder, written as the run goes.

- ``fields.xdmf``: see :mod:`.fields`.
- ``curves.csv``: one row per converged step: load factor, each contact's
  observables (obstacle displacement, force on the body × symmetry factor,
  closed points, loaded contact area × symmetry factor; with friction the dissipation of the step and accumulated,
  N mm × symmetry factor, the stick and slip counts and flips, and the totals
  over all frictional contacts), probe displacements, Newton iterations.
- ``summary.json``: the scene as it ran, the effects built, status, every
  step's Newton history and the wall-time split; rewritten after each step
  and each failed attempt, so a failed run keeps every converged step on
  disk, and why it stopped: ``failed_attempts`` has one entry per failed
  Newton attempt of a load-control step (each cut-back, and the last one,
  ``"outcome": "stopped"``, of a run that stopped): the step and attempt
  numbers, λ and Δλ, the verdict (``reason``: the SNES reason, or
  FORCED_FAILURE, INVERTED_ELEMENT, AUGMENTATION_LIMIT) and ``snes_reason``,
  the residual norms of its last solve (one per iterate: iterations + 1),
  ``solves``: every Newton solve of the attempt (the full-step one and the
  line-search fallback: ``line_search``, iterations, Krylov iterations,
  reasons, residual norms) and their total ``attempt_newton_iterations``,
  ``largest_residuals``: the five nodes with the largest residual force at
  the last iterate (force, reference ``point``, ``current`` coordinates,
  the residual vector, the contacts whose slave point sits there and its
  status),
  the Newton-update norms, the numbers of iterations in which the active
  set and the stick/slip set changed, per iteration the numbers of slave
  points that flipped open ↔ closed and stick ↔ slip and, closed against
  a deformable master, switched master facet, the points that flipped most
  (``most_open_closed_flips``, ``most_stick_slip_flips``,
  ``most_master_facet_flips``:
  contact, flips, reference ``point`` and ``current`` coordinates at the
  last iterate), the augmentations, and, when its last iterate has
  det F ≤ 0 somewhere, ``inverted_element`` (input cell index, reference
  centroid, min J). Under continuation one entry per failed step attempt:
  step and attempt numbers, λ at its start, the step ``size`` tried (arc
  length or controlled displacement), ``reason`` (why the bordered Newton
  solve gave up) and ``outcome``.
- ``curves.png``, ``deformed.png``: see :mod:`.drawing`.
"""
import contextlib
import csv
import json
import resource
import time
from pathlib import Path

from mpi4py import MPI

from . import drawing
from ..scene.path import LoadPath
from .fields import FieldWriter

#: contact observables multiplied by the symmetry factor (forces, energies and the contact area)
SCALED = {"fx", "fy", "fz", "area", "dissipation_step", "dissipation"}


class ResultsWriter:
    def __init__(self, out_dir, comm, scene, effects, u, contacts, probes, previous=None, stress=None, path=None):
        """``previous``: the checkpointed state of an interrupted run being
        resumed: its steps are kept, the CSV rewritten, the XDMF appended.
        ``stress``: the material's first Piola–Kirchhoff stress, a callable
        ``stress(u) -> P`` (a 3×3 UFL expression of u, e.g.
        :func:`~.fields.first_piola_stress`): fields.xdmf then also holds the
        Cauchy stress and its von Mises value. ``path``: the load path
        (:class:`~hypercontact.scene.path.LoadPath`): with phases, each row
        has its phase and the accumulated parameter τ (``time``), and the
        summary lists the phases as run."""
        self.comm, self.scene, self.effects = comm, scene, effects
        self.path = path if path is not None else LoadPath(scene)
        self.phases = list(previous.get("phases", [])) if previous else []
        self.u, self.contacts, self.probes = u, contacts, probes
        self.out = Path(out_dir)
        self.factor = scene["output"]["symmetry_factor"]
        self.steps = list(previous["steps"]) if previous else []
        self.limit_points = list(previous["limit_points"]) if previous else []
        self.failed_attempts = list(previous.get("failed_attempts", [])) if previous else []
        self.status, self.message = "running", ""
        self.started = time.perf_counter()
        self.rank0 = comm.rank == 0
        if self.rank0:
            self.out.mkdir(parents=True, exist_ok=True)
        comm.barrier()
        self.field_writer = None
        if scene["output"]["xdmf"]:
            path = self.out / "fields.xdmf"
            append = previous is not None and path.is_file()
            # A run killed after writing a step's fields but before its checkpoint
            # recomputes that step on resume, identically: its fields are on disk.
            frames = 0
            if append:
                frames = path.read_text().count('<Grid Name="displacement" GridType="Uniform"')
            self.field_writer = FieldWriter(path, comm, u, contacts, stress, append,
                                            max(frames - len(self.steps), 0))
        self.fields = self.field_writer.descriptions() if self.field_writer else {}
        self.pictures = {}
        # The displacement of the last converged step, for the picture drawn at the end.
        self._u_last = u.x.array.copy() if self.steps else None
        self.columns = self._columns()
        if self.rank0:
            self._csv_file = open(self.out / "curves.csv", "w", newline="")
            self._csv = csv.writer(self._csv_file)
            self._csv.writerow(self.columns)
            for step in self.steps:
                self._csv.writerow([step.get(k, "") for k in self.columns])
            self._csv_file.flush()

    def _columns(self):
        columns = ["step", "load_factor", "newton_iterations"]
        if not self.path.implicit:
            columns[1:1] = ["phase", "time"]
        if self.scene["steps"]["control"] == "load":  # continuation solves its bordered systems with LU
            columns.append("linear_iterations")
        for c in self.contacts:
            columns += [f"{c.name}_{key}" for key in c.observable_names()]
        if any(c.frictional for c in self.contacts):
            columns += ["dissipation_step", "dissipation"]  # over all frictional contacts
            # Newton iterations in which a frictional contact's stick/slip set changed; flips summed
            columns += ["stick_slip_changes", "stick_slip_flips"]
        for name in self.probes:
            columns += [f"{name}_u{a}" for a in "xyz"]
        self.pressures = {f"pressure_{p['surface']}": i for i, p in enumerate(self.scene["pressure"])}
        return columns + list(self.pressures)

    def start_phase(self, k):
        """Phase k begins (or goes on, after a resume)."""
        spec = self.path.phases[k]
        if self.phases and self.phases[-1]["index"] == k + 1:
            self.phases[-1]["status"] = "running"
            return
        self.phases.append({"index": k + 1, "name": spec.name, "length": spec.length, "start": spec.start,
                            "first_step": len(self.steps) + 1, "last_step": None, "status": "running",
                            "steps": spec.steps, "solver": spec.solver})

    def end_phase(self, k, status):
        if self.phases and self.phases[-1]["index"] == k + 1:
            self.phases[-1]["status"] = status
            self.phases[-1]["last_step"] = len(self.steps) if len(self.steps) >= self.phases[-1]["first_step"] \
                else None

    def write_step(self, load_factor, iterations, norms, timers, settled_from=0, update_norms=(),
                   active_set_changes=0, stick_slip_changes=0, augmentations=0, linear_iterations=None, phase=0,
                   residual_reference=None, negative_eigenvalues=None):
        # The fields first: a non-finite one stops here, before anything of this step is recorded.
        step = len(self.steps) + 1
        # fields.xdmf's time: the load factor, or with phases the accumulated τ (λ restarts in each phase)
        t = load_factor if self.path.implicit else self.path.time(phase, load_factor)
        fields = self.field_writer.compute(t, step) if self.field_writer else None
        row = {"step": step, "load_factor": load_factor,
               "newton_iterations": iterations}
        if not self.path.implicit:
            row["phase"], row["time"] = phase + 1, self.path.time(phase, load_factor)
        if linear_iterations is not None:
            row["linear_iterations"] = linear_iterations
        friction = {"dissipation_step": 0.0, "dissipation": 0.0, "stick_slip_flips": 0}
        for c in self.contacts:
            for key, value in c.observables().items():
                row[f"{c.name}_{key}"] = self.factor * value if key in SCALED else value
                if key in friction:
                    friction[key] += row[f"{c.name}_{key}"]
        if any(c.frictional for c in self.contacts):
            row["dissipation_step"], row["dissipation"] = friction["dissipation_step"], friction["dissipation"]
            row["stick_slip_changes"] = stick_slip_changes
            row["stick_slip_flips"] = friction["stick_slip_flips"]
        for name, probe in self.probes.items():
            for a, value in zip("xyz", probe.value(self.u)):
                row[f"{name}_u{a}"] = float(value)
        values = self.path.values(phase, load_factor) if self.pressures else {}
        for name, i in self.pressures.items():
            row[name] = values[("pressure", i)]
        reference = max(norms[0], residual_reference or 0.0) if norms else residual_reference
        self.steps.append({**row, "residual_norms": norms, "residual_reference": reference,
                           "active_set_settled_at": settled_from,
                           "active_set_changes": active_set_changes, "update_norms": list(update_norms),
                           "augmentations": augmentations,
                           **({"negative_eigenvalues": negative_eigenvalues} if negative_eigenvalues is not None else {})})
        if self.rank0:
            self._csv.writerow([row.get(k, "") for k in self.columns])  # a driver may give no Krylov count
            self._csv_file.flush()
        if self.field_writer:
            self.field_writer.write(t, fields)
        self._u_last = self.u.x.array.copy()
        self.write_summary(timers)
        return row

    def record_failed_attempt(self, story, timers):
        """Keep a failed attempt's story (see the module's summary.json) and
        rewrite the summary with it. Collective."""
        self.failed_attempts.append(story)
        self.write_summary(timers)

    def finish(self, status, message, timers):
        """Close the files, draw the pictures (if a step converged) and write
        the final summary. Collective."""
        self.status, self.message = status, message
        if self.field_writer:
            self.field_writer.close()
        if self.rank0:
            self._csv_file.close()
        timed = timers("output") if callable(timers) else contextlib.nullcontext()
        with timed:
            self.pictures = self.draw_pictures()
        self.write_summary(timers)

    def draw_pictures(self):
        """curves.png and deformed.png (:func:`.drawing.draw_pictures`). Collective."""
        return drawing.draw_pictures(self)

    def write_summary(self, timers):
        wall = self.comm.allreduce(time.perf_counter() - self.started, op=MPI.MAX)
        split = {k: self.comm.allreduce(v, op=MPI.MAX) for k, v in sorted(timers.seconds.items())}
        split["other"] = max(wall - sum(split.values()), 0.0)
        peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: kB
        calls = {k: self.comm.allreduce(v, op=MPI.MAX) for k, v in sorted(timers.calls.items())}
        summary = {
            "status": self.status, "message": self.message, "effects": self.effects,
            "ranks": self.comm.size, "wall_time": wall, "time_split": split, "calls": calls,
            "peak_memory_mb": {"max_rank": self.comm.allreduce(peak_mb, op=MPI.MAX),
                               "sum_ranks": self.comm.allreduce(peak_mb, op=MPI.SUM)},
            "newton_iterations": [s["newton_iterations"] for s in self.steps],
            "linear_iterations": [s.get("linear_iterations") for s in self.steps],
            "linear_solver": {k: (self.comm.allreduce(v, op=MPI.MAX) if isinstance(v, (int, float)) and v is not None
                                  else v)
                              for k, v in getattr(timers, "linear", {}).items()},
            "limit_points": self.limit_points, "fields": self.fields, "pictures": self.pictures,
            "phases": self.phases,
            "steps": self.steps, "failed_attempts": self.failed_attempts, "scene": self.scene,
        }
        if self.rank0:
            tmp = self.out / "summary.json.tmp"
            tmp.write_text(json.dumps(summary, indent=1))
            tmp.replace(self.out / "summary.json")
        return summary
