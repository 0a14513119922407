"""Results of a run, in one folder, written as the run goes.

- ``fields.xdmf``: displacement, contact gap and pressure per converged step
  (ParaView); contact fields are zero off the contact surfaces.
- ``curves.csv``: one row per converged step: load factor, each contact's
  obstacle displacement and force on the body (× symmetry factor), probe
  displacements, Newton iterations.
- ``summary.json``: the scene as it ran, the effects built, status, every
  step's Newton history and the wall-time split; rewritten after each step,
  so a failed run keeps every converged step on disk.
"""
import csv
import json
import time
from pathlib import Path

import numpy as np
from mpi4py import MPI

from . import _dolfinx as dfx


class ResultsWriter:
    def __init__(self, out_dir, comm, scene, effects, u, contacts, probes, previous=None):
        """``previous``: the checkpointed state of an interrupted run being
        resumed: its steps are kept, the CSV rewritten, the XDMF appended."""
        self.comm, self.scene, self.effects = comm, scene, effects
        self.u, self.contacts, self.probes = u, contacts, probes
        self.out = Path(out_dir)
        self.factor = scene["output"]["symmetry_factor"]
        self.steps = list(previous["steps"]) if previous else []
        self.limit_points = list(previous["limit_points"]) if previous else []
        self.status, self.message = "running", ""
        self.started = time.perf_counter()
        self.rank0 = comm.rank == 0
        if self.rank0:
            self.out.mkdir(parents=True, exist_ok=True)
        comm.barrier()
        V = u.function_space
        # XDMF holds first-order fields on the (first-order) mesh: a degree-2
        # displacement is written interpolated at the vertices.
        if V.ufl_element().degree() == 1:
            self.u_out = u
        else:
            self.u_out = dfx.fem.Function(dfx.vector_space(V.mesh, 1), name="displacement")
        if contacts:
            self.Q, q_to_v = V.sub(0).collapse()
            self.q_nodes = np.asarray(q_to_v) // 3
            self.gap = dfx.fem.Function(self.Q, name="contact_gap")
            self.pressure = dfx.fem.Function(self.Q, name="contact_pressure")
        append = previous is not None and (self.out / "fields.xdmf").is_file()
        # A run killed after writing a step's fields but before its checkpoint
        # recomputes that step on resume, identically: its fields are on disk.
        self._frames_on_disk = 0
        if append:
            frames = (self.out / "fields.xdmf").read_text().count('<Grid Name="displacement" GridType="Uniform"')
            self._frames_on_disk = max(frames - len(self.steps), 0)
        self.xdmf = (dfx.XDMFWriter(comm, self.out / "fields.xdmf", V.mesh, append=append)
                     if scene["output"]["xdmf"] else None)
        self.columns = ["step", "load_factor", "newton_iterations"]
        for c in contacts:
            self.columns += [f"{c.name}_displacement"] + [f"{c.name}_f{a}" for a in "xyz"]
            self.columns += [f"{c.name}_closed_nodes"]
        for name in probes:
            self.columns += [f"{name}_u{a}" for a in "xyz"]
        self.pressures = {f"pressure_{p['surface']}": p["value"] for p in scene["pressure"]}
        self.columns += list(self.pressures)
        if self.rank0:
            self._csv_file = open(self.out / "curves.csv", "w", newline="")
            self._csv = csv.writer(self._csv_file)
            self._csv.writerow(self.columns)
            for step in self.steps:
                self._csv.writerow([step[k] for k in self.columns])
            self._csv_file.flush()

    def write_step(self, load_factor, iterations, norms, timers, settled_from=0, update_norms=()):
        row = {"step": len(self.steps) + 1, "load_factor": load_factor,
               "newton_iterations": iterations}
        for c in self.contacts:
            motion = np.asarray(c.spec["motion"])
            row[f"{c.name}_displacement"] = load_factor * float(np.linalg.norm(motion))
            force = self.factor * c.force(self.u)
            for a, f in zip("xyz", force):
                row[f"{c.name}_f{a}"] = float(f)
            row[f"{c.name}_closed_nodes"] = c.num_closed(self.u)
        for name, probe in self.probes.items():
            for a, value in zip("xyz", probe.value(self.u)):
                row[f"{name}_u{a}"] = float(value)
        for name, value in self.pressures.items():
            row[name] = load_factor * value
        self.steps.append({**row, "residual_norms": norms, "active_set_settled_at": settled_from,
                           "update_norms": list(update_norms)})
        if self.rank0:
            self._csv.writerow([row[k] for k in self.columns])
            self._csv_file.flush()
        if self.xdmf is not None:
            self._write_fields(load_factor)
        self.write_summary(timers)
        return row

    def _write_fields(self, t):
        if self._frames_on_disk > 0:
            self._frames_on_disk -= 1
            return
        if self.u_out is not self.u:
            self.u_out.interpolate(self.u)
        if not self.contacts:
            self.xdmf.write([self.u_out], t)
            return
        n_local = dfx.num_local_nodes(self.u.function_space)
        gap, pressure = np.zeros(n_local), np.zeros(n_local)
        for c in self.contacts:
            state = c.evaluate(self.u)
            gap[c.nodes] = state.gap
            pressure[c.nodes] += state.pressure
        self.gap.x.array[:] = gap[self.q_nodes]
        self.pressure.x.array[:] = pressure[self.q_nodes]
        dfx.update_ghosts(self.gap)
        dfx.update_ghosts(self.pressure)
        self.xdmf.write([self.u_out, self.gap, self.pressure], t)

    def finish(self, status, message, timers):
        self.status, self.message = status, message
        self.write_summary(timers)
        if self.xdmf is not None:
            self.xdmf.close()
        if self.rank0:
            self._csv_file.close()

    def write_summary(self, timers):
        wall = self.comm.allreduce(time.perf_counter() - self.started, op=MPI.MAX)
        split = {k: self.comm.allreduce(v, op=MPI.MAX) for k, v in sorted(timers.seconds.items())}
        split["other"] = max(wall - sum(split.values()), 0.0)
        summary = {
            "status": self.status, "message": self.message, "effects": self.effects,
            "ranks": self.comm.size, "wall_time": wall, "time_split": split,
            "newton_iterations": [s["newton_iterations"] for s in self.steps],
            "limit_points": self.limit_points, "steps": self.steps, "scene": self.scene,
        }
        if self.rank0:
            tmp = self.out / "summary.json.tmp"
            tmp.write_text(json.dumps(summary, indent=1))
            tmp.replace(self.out / "summary.json")
        return summary
