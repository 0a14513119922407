"""Results of a run, in one folder, written as the run goes.

- ``fields.xdmf``: per converged step (ParaView): ``displacement`` (vertex
  values), ``contact_gap`` and ``contact_pressure`` when there are contacts
  (zero off the contact surfaces), with friction also the friction fields of
  :data:`FRICTION_FIELDS` (vertex values on the contact surfaces, zero off
  them), and cell-wise constant (DG0) fields at
  each cell's midpoint: ``J`` = det F, and, when the writer is given the
  material's stress, ``cauchy_stress`` σ = J⁻¹ P Fᵀ (3×3, row by row) and
  ``von_mises`` √(3/2 s:s), s = dev σ. A field with a NaN or an infinite
  value is never written: :class:`NonFiniteField` names it and the step.
- ``curves.csv``: one row per converged step: load factor, each contact's
  obstacle displacement and force on the body (× symmetry factor), probe
  displacements, Newton iterations; with friction, per frictional contact
  the dissipation of the step and accumulated (N mm, × symmetry factor) and
  the numbers of sticking and slipping nodes, and the totals over all
  frictional contacts.
- ``summary.json``: the scene as it ran, the effects built, status, every
  step's Newton history and the wall-time split; rewritten after each step
  and each failed attempt, so a failed run keeps every converged step on
  disk, and why it stopped: ``failed_attempts`` has one entry per failed
  Newton attempt of a load-control step (each cut-back, and the last one,
  ``"outcome": "stopped"``, of a run that stopped): the step and attempt
  numbers, λ and Δλ, the verdict (``reason``: the SNES reason, or
  FORCED_FAILURE, INVERTED_ELEMENT, AUGMENTATION_LIMIT) and ``snes_reason``,
  the residual norms of its last solve (one per iterate: iterations + 1),
  the Newton-update norms, the numbers of iterations in which the active
  set and the stick/slip set changed, per iteration the numbers of slave
  points that flipped open ↔ closed and stick ↔ slip, the points that
  flipped most (``most_open_closed_flips``, ``most_stick_slip_flips``:
  contact, flips, reference ``point`` and ``current`` coordinates at the
  last iterate) and, when its last iterate has det F ≤ 0 somewhere,
  ``inverted_element`` (input cell index, reference centroid, min J).
- ``curves.png``, ``deformed.png``: drawn at the end of a run that converged
  at least one step (completed or not; :mod:`hypercontact.pictures`): the
  contact forces (or pressures) against the first contact's displacement (or
  the first probe's), and the deformed boundary coloured by |u|. A picture
  that cannot be drawn never stops a run: summary.json says why
  (``"pictures"``).
"""
import contextlib
import csv
import json
import resource
import time
from pathlib import Path

import numpy as np
import ufl
from mpi4py import MPI

from . import _dolfinx as dfx


#: Friction fields in fields.xdmf (when a contact has μ > 0): name → (key of
#: FrictionalRigidContact.surface_fields, whether a vector, description).
FRICTION_FIELDS = {
    "contact_status": ("status", False, "vertex values: 0 open or off the contact surfaces, 1 stick, 2 slip "
                       "(a closed node of a frictionless contact: 2)"),
    "contact_tangential_traction": ("traction", True, "vertex values, MPa: the tangential traction the "
                                    "obstacle exerts on the body"),
    "contact_tangential_traction_magnitude": ("traction", False, "vertex values, MPa: its magnitude (≤ μ × "
                                              "contact_pressure)"),
    "contact_slip_increment": ("slip_increment", True, "vertex values, mm: slip (the inelastic part of the "
                               "tangential motion) in this step"),
    "contact_accumulated_slip": ("accumulated_slip", False, "vertex values, mm: Σ |slip increment| over "
                                 "the steps so far"),
    "contact_dissipation_step": ("dissipation_step", False, "vertex values, N/mm (= mJ/mm²): frictional "
                                 "dissipation in this step per unit reference area (Σ nodal area × value = "
                                 "the contact's <name>_dissipation_step / symmetry factor)"),
    "contact_dissipation": ("dissipation", False, "vertex values, N/mm (= mJ/mm²): accumulated frictional "
                            "dissipation per unit reference area"),
}


def frictional(contact):
    """Whether a contact reports friction results (μ > 0)."""
    return hasattr(contact, "surface_fields")


class NonFiniteField(RuntimeError):
    """A field about to be written to fields.xdmf has NaN or infinite values."""


def first_piola_stress(psi, **params):
    """``stress(u)`` for :class:`ResultsWriter` from a law ψ(F, **params):
    P = ∂ψ/∂F by UFL at F = I + ∇u."""

    def stress(u):
        F = ufl.variable(ufl.Identity(len(u)) + ufl.grad(u))
        return ufl.diff(psi(F, **params), F)

    return stress


def von_mises(sigma):
    """√(3/2 s:s), s = σ − tr σ / 3 I, of an array of 3×3 tensors (n, 3, 3)."""
    s = sigma - np.trace(sigma, axis1=1, axis2=2)[:, None, None] / 3.0 * np.eye(3)
    return np.sqrt(1.5 * np.einsum("nij,nij->n", s, s))


class ResultsWriter:
    def __init__(self, out_dir, comm, scene, effects, u, contacts, probes, previous=None, stress=None):
        """``previous``: the checkpointed state of an interrupted run being
        resumed: its steps are kept, the CSV rewritten, the XDMF appended.

        ``stress``: the material's first Piola–Kirchhoff stress, a callable
        ``stress(u) -> P`` (a 3×3 UFL expression of the displacement u, e.g.
        :func:`first_piola_stress`); with it, fields.xdmf also holds the
        Cauchy stress and its von Mises value. u is the solution's own
        displacement (degree 2 in the mixed formulation: the cell fields are
        evaluated from it at the cell midpoints, not from its vertex values).
        """
        self.comm, self.scene, self.effects = comm, scene, effects
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
        self.friction_fields = {}
        if any(frictional(c) for c in contacts) and scene["output"]["xdmf"]:
            # contact needs degree 1: V is the first-order vector space
            self.friction_fields = {name: dfx.fem.Function(V if vector else self.Q, name=name)
                                    for name, (_, vector, _) in FRICTION_FIELDS.items()}
        append = previous is not None and (self.out / "fields.xdmf").is_file()
        # A run killed after writing a step's fields but before its checkpoint
        # recomputes that step on resume, identically: its fields are on disk.
        self._frames_on_disk = 0
        if append:
            frames = (self.out / "fields.xdmf").read_text().count('<Grid Name="displacement" GridType="Uniform"')
            self._frames_on_disk = max(frames - len(self.steps), 0)
        self.xdmf = (dfx.XDMFWriter(comm, self.out / "fields.xdmf", V.mesh, append=append)
                     if scene["output"]["xdmf"] else None)
        # Cell-wise constant fields (DG0) at the cell midpoints; their kernels
        # are compiled at the first step (FFCx JIT, timed as output).
        self.stress = stress
        self._cell_kernels = None
        if self.xdmf is not None:
            S = dfx.fem.FunctionSpace(V.mesh, ("DG", 0))
            self.J = dfx.fem.Function(S, name="J")
            if stress is not None:
                T = dfx.fem.TensorFunctionSpace(V.mesh, ("DG", 0))
                self.sigma = dfx.fem.Function(T, name="cauchy_stress")
                self.von_mises = dfx.fem.Function(S, name="von_mises")
        self.fields = {}
        if self.xdmf is not None:
            self.fields["displacement"] = "vertex values (Lagrange degree 1), mm"
            if contacts:
                self.fields["contact_gap"] = "vertex values, mm (0 off the contact surfaces)"
                self.fields["contact_pressure"] = "vertex values, MPa (0 off the contact surfaces)"
            for name in self.friction_fields:
                self.fields[name] = FRICTION_FIELDS[name][2]
            self.fields["J"] = "per cell (DG0, at the midpoint): det F"
            if stress is not None:
                self.fields["cauchy_stress"] = "per cell (DG0, at the midpoint): σ = J⁻¹ P Fᵀ, 3×3 row by row, MPa"
                self.fields["von_mises"] = "per cell (DG0, at the midpoint): √(3/2 s:s), s = dev σ, MPa"
        self.pictures = {}
        # The displacement of the last converged step, for the picture drawn at the end.
        self._u_last = u.x.array.copy() if self.steps else None
        self.columns = ["step", "load_factor", "newton_iterations"]
        for c in contacts:
            self.columns += [f"{c.name}_displacement"] + [f"{c.name}_f{a}" for a in "xyz"]
            self.columns += [f"{c.name}_closed_nodes"]
            if frictional(c):  # frictional dissipation (N mm) of the step and accumulated, stick/slip nodes
                self.columns += [f"{c.name}_dissipation_step", f"{c.name}_dissipation",
                                 f"{c.name}_stick_nodes", f"{c.name}_slip_nodes"]
                self.columns += [f"{c.name}_stick_slip_flips"]  # points that flipped stick <-> slip
        if any(frictional(c) for c in contacts):
            self.columns += ["dissipation_step", "dissipation"]  # over all frictional contacts
            # Newton iterations in which a frictional contact's stick/slip set changed; flips summed
            self.columns += ["stick_slip_changes", "stick_slip_flips"]
        for name in probes:
            self.columns += [f"{name}_u{a}" for a in "xyz"]
        self.pressures = {f"pressure_{p['surface']}": p["value"] for p in scene["pressure"]}
        self.columns += list(self.pressures)
        if self.rank0:
            self._csv_file = open(self.out / "curves.csv", "w", newline="")
            self._csv = csv.writer(self._csv_file)
            self._csv.writerow(self.columns)
            for step in self.steps:
                self._csv.writerow([step.get(k, "") for k in self.columns])
            self._csv_file.flush()

    def write_step(self, load_factor, iterations, norms, timers, settled_from=0, update_norms=(),
                   active_set_changes=0, stick_slip_changes=0):
        # The fields first: a non-finite one stops here, before anything of this step is recorded.
        fields = self._fields(load_factor) if self.xdmf is not None and self._frames_on_disk == 0 else None
        row = {"step": len(self.steps) + 1, "load_factor": load_factor,
               "newton_iterations": iterations}
        for c in self.contacts:
            motion = np.asarray(c.spec["motion"])
            row[f"{c.name}_displacement"] = load_factor * float(np.linalg.norm(motion))
            force = self.factor * c.force(self.u)
            for a, f in zip("xyz", force):
                row[f"{c.name}_f{a}"] = float(f)
            row[f"{c.name}_closed_nodes"] = c.num_closed(self.u)
            if frictional(c):
                row[f"{c.name}_dissipation_step"] = self.factor * c.dissipation_step
                row[f"{c.name}_dissipation"] = self.factor * c.dissipation
                row[f"{c.name}_stick_nodes"], row[f"{c.name}_slip_nodes"] = c.stick_slip_counts()
                row[f"{c.name}_stick_slip_flips"] = c.flips_step
        if any(frictional(c) for c in self.contacts):
            row["dissipation_step"] = self.factor * sum(c.dissipation_step for c in self.contacts if frictional(c))
            row["dissipation"] = self.factor * sum(c.dissipation for c in self.contacts if frictional(c))
            row["stick_slip_changes"] = stick_slip_changes
            row["stick_slip_flips"] = sum(c.flips_step for c in self.contacts if frictional(c))
        for name, probe in self.probes.items():
            for a, value in zip("xyz", probe.value(self.u)):
                row[f"{name}_u{a}"] = float(value)
        for name, value in self.pressures.items():
            row[name] = load_factor * value
        self.steps.append({**row, "residual_norms": norms, "active_set_settled_at": settled_from,
                           "active_set_changes": active_set_changes, "update_norms": list(update_norms)})
        if self.rank0:
            self._csv.writerow([row[k] for k in self.columns])
            self._csv_file.flush()
        if self.xdmf is not None:
            self._write_fields(load_factor, fields)
        self._u_last = self.u.x.array.copy()
        self.write_summary(timers)
        return row

    def record_failed_attempt(self, story, timers):
        """Keep a failed attempt's story (see the module's summary.json) and
        rewrite the summary with it. Collective."""
        self.failed_attempts.append(story)
        self.write_summary(timers)

    def _write_fields(self, t, fields):
        if self._frames_on_disk > 0:
            self._frames_on_disk -= 1
            return
        self.xdmf.write(fields, t)

    def _fields(self, t):
        """The functions to write at this step, checked to be finite."""
        if self.u_out is not self.u:
            self.u_out.interpolate(self.u)
        self._check_finite([self.u_out], t)  # first: the other fields are computed from it
        fields = self._contact_fields() if self.contacts else []
        fields += self._cell_fields()
        self._check_finite(fields, t)
        return [self.u_out] + fields

    def _cell_kernels_compiled(self):
        """DG0 interpolation kernels of J and (with a stress law) σ = J⁻¹ P Fᵀ."""
        u = self.u
        F = ufl.Identity(len(u)) + ufl.grad(u)
        J = ufl.det(F)
        points = self.J.function_space.element.interpolation_points
        points = points() if callable(points) else points  # a method in dolfinx 0.5, a property later
        kernels = {"J": dfx.fem.Expression(J, points)}
        if self.stress is not None:
            P = self.stress(u)
            if not isinstance(P, ufl.core.expr.Expr) or P.ufl_shape != (3, 3):
                raise TypeError("ResultsWriter: stress(u) must return the first Piola–Kirchhoff stress as a "
                                f"3×3 UFL expression, returned {getattr(P, 'ufl_shape', type(P).__name__)}")
            kernels["cauchy_stress"] = dfx.fem.Expression(P * F.T / J, points)
        return kernels

    def _cell_fields(self):
        if self._cell_kernels is None:
            self._cell_kernels = self._cell_kernels_compiled()
        self.J.interpolate(self._cell_kernels["J"])
        if self.stress is None:
            return [self.J]
        self.sigma.interpolate(self._cell_kernels["cauchy_stress"])
        with np.errstate(invalid="ignore"):  # NaN in, NaN out: caught by the check
            self.von_mises.x.array[:] = von_mises(self.sigma.x.array.reshape(-1, 3, 3))
        return [self.sigma, self.von_mises, self.J]

    def _check_finite(self, functions, t):
        """Raise NonFiniteField naming every field with a NaN or an infinite value."""
        counts = []
        for f in functions:
            V = f.function_space
            owned = dfx.num_owned_nodes(V) * V.dofmap.index_map_bs
            counts.append([int(np.count_nonzero(~np.isfinite(f.x.array[:owned]))), owned])
        counts = np.array(counts, dtype=np.int64).reshape(-1, 2)
        self.comm.Allreduce(MPI.IN_PLACE, counts, op=MPI.SUM)
        bad = [f"'{f.name}' ({n} of {total} values)" for f, (n, total) in zip(functions, counts) if n]
        if bad:
            raise NonFiniteField(
                f"non-finite field{'s' if len(bad) > 1 else ''} {', '.join(bad)} at step {len(self.steps) + 1} "
                f"(load factor {t:.6g}): NaN or infinite values, not written to {self.out / 'fields.xdmf'}")

    def _contact_fields(self):
        n_local = dfx.num_local_nodes(self.u.function_space)
        gap, pressure = np.zeros(n_local), np.zeros(n_local)
        for c in self.contacts:
            if c.nodes is None:  # Gauss-point contact: no value per node
                continue
            state = c.evaluate(self.u)
            gap[c.nodes] = state.gap
            pressure[c.nodes] += state.pressure
        self.gap.x.array[:] = gap[self.q_nodes]
        self.pressure.x.array[:] = pressure[self.q_nodes]
        dfx.update_ghosts(self.gap)
        dfx.update_ghosts(self.pressure)
        return [self.gap, self.pressure] + self._friction_fields(n_local)

    def _friction_fields(self, n_local):
        """The FRICTION_FIELDS at the last converged step: vertex values on
        the slave nodes, summed where two contacts share a node (the status:
        the larger), zero elsewhere."""
        if not self.friction_fields:
            return []
        values = {"status": np.zeros(n_local), "traction": np.zeros((n_local, 3)),
                  "slip_increment": np.zeros((n_local, 3)), "accumulated_slip": np.zeros(n_local),
                  "dissipation_step": np.zeros(n_local), "dissipation": np.zeros(n_local)}
        for c in self.contacts:
            if frictional(c):
                for key, v in c.surface_fields().items():
                    if key == "status":
                        values[key][c.nodes] = np.maximum(values[key][c.nodes], v)
                    else:
                        values[key][c.nodes] += v
            else:  # frictionless: a closed node slides freely
                closed = c.nodes[np.asarray(c.evaluate(self.u).gap) <= 0.0]
                values["status"][closed] = np.maximum(values["status"][closed], 2.0)
        out = []
        for name, f in self.friction_fields.items():
            key, vector, _ = FRICTION_FIELDS[name]
            v = values[key]
            if vector:
                f.x.array[:] = v.ravel()
            elif v.ndim == 2:  # the magnitude of a vector
                f.x.array[:] = np.linalg.norm(v, axis=1)[self.q_nodes]
            else:
                f.x.array[:] = v[self.q_nodes]
            dfx.update_ghosts(f)
            out.append(f)
        return out

    def finish(self, status, message, timers):
        """Close the files, draw the pictures (if a step converged) and write
        the final summary. Collective."""
        self.status, self.message = status, message
        if self.xdmf is not None:
            self.xdmf.close()
        if self.rank0:
            self._csv_file.close()
        timed = timers("output") if callable(timers) else contextlib.nullcontext()
        with timed:
            self.pictures = self.draw_pictures()
        self.write_summary(timers)

    def curve_columns(self):
        """(x, ys) drawn in curves.png: the contact forces (each contact's
        largest component) against the first contact's displacement; without
        contacts, the pressures (else the load factor) against the stop
        probe's controlled component, or the first probe's largest one."""
        def largest(columns):
            return max(columns, key=lambda c: max(abs(s[c]) for s in self.steps))

        if self.contacts:
            x = f"{self.contacts[0].name}_displacement"
            return x, [largest([f"{c.name}_f{a}" for a in "xyz"]) for c in self.contacts]
        st = self.scene["steps"]
        if st.get("control", "load") != "load" and st.get("stop_probe") in self.probes:
            x = f"{st['stop_probe']}_u{st['stop_component']}"
        elif self.probes:
            x = largest([f"{next(iter(self.probes))}_u{a}" for a in "xyz"])
        else:
            x = "load_factor"
        ys = list(self.pressures) or (["load_factor"] if x != "load_factor" else ["newton_iterations"])
        return x, ys

    def draw_pictures(self):
        """curves.png (rank 0) and deformed.png (collective) of the last
        converged step. Never raises: returns what was drawn, or why not.
        Every collective call is reached on every rank, whatever fails."""
        if not self.steps or self._u_last is None:
            return {"skipped": "no converged step"}
        done, error = {}, None
        try:
            from . import pictures
        except Exception as err:  # e.g. matplotlib missing
            error = f"failed: {type(err).__name__}: {err}"
        errors = [e for e in self.comm.allgather(error) if e]
        if errors:
            return {"curves.png": errors[0], "deformed.png": errors[0]}
        title = self.scene.get("title") or self.out.name
        if self.rank0:
            try:
                x, ys = self.curve_columns()
                pictures.load_curves(self.out / "curves.csv", self.out / "curves.png", x, ys, title=title)
                done["curves.png"] = f"{', '.join(ys)} against {x}"
            except Exception as err:
                done["curves.png"] = f"failed: {type(err).__name__}: {err}"
        try:
            u = dfx.fem.Function(self.u.function_space, name="displacement")
            u.x.array[:] = self._u_last
        except Exception as err:
            u, error = None, f"failed: {type(err).__name__}: {err}"
        errors = [e for e in self.comm.allgather(error) if e]
        if errors:
            done["deformed.png"] = errors[0]
            return done
        scale = self._picture_scale(u)
        last = self.steps[-1]
        magnified = f", displacements × {scale:g}" if scale != 1 else ""
        # With contacts, look from the low-x, low-y side: the symmetry cuts of a
        # quarter model and what an obstacle presses into them show. Without,
        # from the high side: the outside of a shell octant.
        view = (28.0, -130.0) if self.contacts else (28.0, 50.0)
        try:  # collective, and raises on every rank or on none
            pictures.deformed_shape(
                self.u.function_space.mesh, u, None, self.out / "deformed.png", scale=scale, view=view,
                title=f"{title}\nstep {last['step']}, load factor {last['load_factor']:.4g}{magnified}")
            done["deformed.png"] = f"|u| on the deformed boundary at step {last['step']}{magnified}"
        except Exception as err:
            done["deformed.png"] = f"failed: {type(err).__name__}: {err}"
        return done

    def _picture_scale(self, u):
        """1, or a round magnification when the largest displacement is below
        2 % of the body's size (so that the deformation shows). Collective."""
        x = u.function_space.mesh.geometry.x
        extent = np.full(7, -np.inf)  # −min x, max x, max |u|
        if len(x):
            extent[:3], extent[3:6] = -x.min(axis=0), x.max(axis=0)
        U = u.x.array.reshape(-1, 3)
        if len(U):
            extent[6] = np.linalg.norm(U, axis=1).max()
        self.comm.Allreduce(MPI.IN_PLACE, extent, op=MPI.MAX)
        size, umax = float(np.linalg.norm(extent[3:6] + extent[:3])), float(extent[6])
        if not np.isfinite(umax) or umax <= 0.0 or umax >= 0.02 * size:
            return 1.0
        target = 0.1 * size / umax
        return float(max(m * 10.0 ** e for e in range(0, 9) for m in (1, 2, 5) if m * 10.0 ** e <= target))

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
            "limit_points": self.limit_points, "fields": self.fields, "pictures": self.pictures,
            "steps": self.steps, "failed_attempts": self.failed_attempts, "scene": self.scene,
        }
        if self.rank0:
            tmp = self.out / "summary.json.tmp"
            tmp.write_text(json.dumps(summary, indent=1))
            tmp.replace(self.out / "summary.json")
        return summary
