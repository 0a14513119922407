"""The run loop: a model's load path solved by its driver (load control or
continuation), with observers — the results writer, the checkpoint, the
console — told about every converged step and every failed attempt."""
import time
from contextlib import contextmanager
from pathlib import Path

from petsc4py import PETSc

from .. import _dolfinx as dfx
from ..results import ResultsWriter
from .checkpoint import Checkpoint
from .load_stepping import LoadStepping
from .path_following import PathFollowing


class Observers:
    """What happens after a converged step or a failed attempt: a results row
    and fields, a checkpoint, a console line (with chattering warnings and a
    time estimate)."""

    def __init__(self, run, writer):
        self.run, self.writer = run, writer
        self.model, self.log = run.model, run.log
        self.negative_eigenvalues = 0  # the last count a console line reported (converged)

    @property
    def steps(self):
        """The [steps] of the phase running (the scene's, with the phase's keys)."""
        return self.run.driver.scene["steps"]

    def steps_written(self):
        return len(self.writer.steps)

    def converged(self, lam, its, norms, reason, history, controller, **arrays):
        """A converged load-control step (``arrays``: the driver's own, for the checkpoint)."""
        with self.run.timers("output"):
            changes, flips = history.active_set_changes(), history.stick_slip_changes()
            row = self.writer.write_step(lam, its, norms, self.run.split(), history.last_active_set_change(),
                                         history.update_norms, changes, flips, self.run.driver.augmentations,
                                         self.run.driver.linear_its, phase=self.model.phase,
                                         residual_reference=self.run.driver.reference,
                                         negative_eigenvalues=self.run.driver.negative_eigenvalues)
        for n, what in ((changes, "contact active set"), (flips, "stick/slip status")):
            if n >= self.steps["chatter_warning"]:
                self.log(f"   the {what} changed in {n} Newton iterations of this step "
                         "(chattering): smaller steps or a backtracking line search damp it")
        krylov = (f"  Krylov {row['linear_iterations']:4d}"
                  if self.model.problem.linear_kind == "iterative" else "")
        where = f"{self.run.phase_label()}λ = {lam:.4f}"
        self.log(f"step {row['step']:3d}  {where}  Newton {its:2d}{krylov}  "
                 f"|R| = {norms[-1]:.2e}  ({reason}){self.run.eta(self.model.path.progress(self.model.phase, lam))}")
        negative = self.run.driver.negative_eigenvalues
        if negative is not None and negative != self.negative_eigenvalues:  # each change once
            self.log(f"   the tangent has {negative} negative eigenvalue{'s' * (negative != 1)}: this equilibrium is "
                     "unstable, past a bifurcation or a limit point" if negative else
                     "   the tangent is positive definite again: a stable equilibrium")
            self.negative_eigenvalues = negative
        self.run.save_checkpoint(self.writer, controller, **arrays)

    def converged_path(self, lam, its, norms, reached, target, controller, du_prev):
        """A converged continuation step."""
        with self.run.timers("output"):
            row = self.writer.write_step(lam, its, norms, self.run.split(), phase=self.model.phase)
        st = self.steps
        self.log(f"step {row['step']:3d}  {self.run.phase_label()}λ = {lam:.5f}  {st['stop_probe']} u{st['stop_component']} = "
                 f"{reached:.4g}  Newton {its:2d}  |R| = {norms[-1]:.2e}{self.run.eta(reached / target)}")
        self.run.save_checkpoint(self.writer, controller, du_prev=du_prev)

    def limit_point(self, record):
        """A limit point of the path (continuation): its load factor, where it was found and how."""
        self.writer.limit_points.append(record)

    def failed(self, story):
        if not self.model.path.implicit:
            story = {"phase": self.model.phase + 1, **story}
        self.writer.record_failed_attempt(story, self.run.split())


class Run:
    """One run of a model into a results folder (``resume``: from its checkpoint)."""

    def __init__(self, model, scene, timers, log, fail_attempt=None):
        self.model, self.scene, self.timers, self.log = model, scene, timers, log
        self.fail_attempt = fail_attempt
        self.driver = None  # built by each run: the SNES takes the scene's PETSc options then
        #: continuation phases among load-control ones time their linear solves here (split() adds them)
        self.bordered_timers = _Aside(timers, "linear solve")

    def phase_label(self):
        """'phase 2 "slide"  ' in a scene with phases, else ''."""
        path = self.model.path
        if path.implicit:
            return ""
        return f"phase {self.model.phase + 1} {path.phases[self.model.phase].name!r}  "

    def _driver(self, phase):
        """The driver of a phase: the scene with the phase's [steps] and [solver]."""
        spec = self.model.path.phases[phase]
        scene = {**self.scene, "steps": spec.steps, "solver": spec.solver}
        if scene["steps"]["control"] == "load":
            return LoadStepping(self.model, scene, self.timers, self.log, self.fail_attempt)
        self.model.set_rates(phase)  # q = ∂R/∂s of the phase's loads
        mixed = any(ph.steps["control"] == "load" for ph in self.model.path.phases)
        return PathFollowing(self.model, scene, self.bordered_timers if mixed else self.timers, self.log)

    def _start(self):
        PETSc.Log.begin()
        self._events = {name: PETSc.Log.Event(name) for name in ("SNESSolve", "SNESFunctionEval", "SNESJacobianEval")}
        self._t0 = {name: e.getPerfInfo()["time"] for name, e in self._events.items()}
        self._started, self._progress0 = time.perf_counter(), 0.0
        self._linear_before = (0, 0.0, 0.0, 0)

    def split(self):
        """The timers, with the linear solve = SNES time less residual and
        Jacobian evaluation (factorisation, triangular solves and line-search
        vector work); continuation times its own solves."""
        if any(ph.steps["control"] == "load" for ph in self.model.path.phases):
            t = {name: e.getPerfInfo()["time"] - self._t0[name] for name, e in self._events.items()}
            self.timers.seconds["linear solve"] = max(t["SNESSolve"] - t["SNESFunctionEval"] - t["SNESJacobianEval"],
                                                      0.0) + self.bordered_timers.get("linear solve")
            counts = self._linear_counts()
            iterative = self.model.problem.linear_kind == "iterative"
            self.timers.linear = {"kind": self.model.problem.linear_kind, "preconditioner_setups": counts[0],
                                  "preconditioner_setup_s": counts[1] if iterative else None,
                                  "krylov_s": counts[2] if iterative else None,
                                  # Newton corrections halved so as not to invert an element (InversionDamping)
                                  "damped_corrections": counts[3]}
        return self.timers

    def _linear_counts(self):
        """(preconditioner set-ups, their seconds, Krylov seconds, damped corrections) of this run's load-control
        Newton solves: the phases before (folded) and the current one's."""
        newton = getattr(self.driver, "newton", None)
        now = ((newton.preconditioner_setups, newton.preconditioner_setup_s, newton.krylov_s,
                len(newton.damping.halvings) if newton.damping is not None else 0) if newton else (0, 0, 0, 0))
        return tuple(a + b for a, b in zip(self._linear_before, now))

    def _fold_linear_counts(self):
        """A phase ends: its Newton solver's counts join those of the phases before."""
        self._linear_before = self._linear_counts()
        self.driver = None

    def eta(self, progress):
        """'  ~N s left', extrapolating the time since this run (or resume)
        started over the fraction of the load path still to go."""
        if not 0 < progress < 1:
            return ""
        done = progress - self._progress0
        elapsed = time.perf_counter() - self._started
        return f"  ~{elapsed * (1 - progress) / done:.0f} s left" if done > 0 else ""

    def save_checkpoint(self, writer, controller, **arrays):
        """The state after a converged step: solution, controller, contacts' histories, results so far."""
        with self.timers("output"):
            contacts = {}
            for c in self.model.contacts:
                meta, data = c.state_dict()
                contacts[c.name] = meta
                arrays.update({f"{c.name}.{k}": v for k, v in data.items()})
            state = {**controller, "phase": self.model.phase, "phase_ends": self.model.path.ended,
                     "steps": writer.steps,
                     "limit_points": writer.limit_points, "failed_attempts": writer.failed_attempts,
                     "phases": writer.phases, "contacts": contacts}
            self.checkpoint.save(state, w=self.model.w.x.array, **arrays)

    def _resume(self, state, arrays):
        model = self.model
        model.w.x.array[:] = arrays["w"]
        model.sync_displacement()
        for c in model.contacts:
            prefix = f"{c.name}."
            c.load_state_dict(state["contacts"][c.name],
                              {k[len(prefix):]: v for k, v in arrays.items() if k.startswith(prefix)})
        for k, s in sorted(state.get("phase_ends", {}).items()):
            model.path.end_phase_at(int(k), s)  # continuation phases that ended before s = 1
        model.phase = state.get("phase", 0)
        if state["steps"]:
            last, st = state["steps"][-1], model.path.phases[model.phase].steps
            self._progress0 = (model.path.progress(model.phase, last["load_factor"]) if st["control"] == "load" else
                               last[f"{st['stop_probe']}_u{st['stop_component']}"] / st["stop_value"])

    def __call__(self, out_dir, resume=False, phases=None):
        """Solve the load path, phase after phase (``phases``: which, by
        index; default all, or from the checkpoint's phase on); returns the
        results writer; raises StepFailure after writing everything that
        converged."""
        self._start()
        self.checkpoint = Checkpoint(Path(out_dir) / "checkpoint", self.model.comm)
        state, arrays = self.checkpoint.load() if resume else (None, {})
        model = self.model
        if state is not None:
            self._resume(state, arrays)
        if phases is None:
            phases = range(model.phase if state is not None else 0, len(model.path.phases))
        writer = ResultsWriter(out_dir, model.comm, self.scene, model.effects, model.u, model.contacts, model.probes,
                               previous=state, stress=model.stress, path=model.path)
        self.log(f"hypercontact: {', '.join(model.effects)}; "
                 f"{dfx.num_global_dofs(model.w.function_space)} unknowns on {model.comm.size} rank(s)")
        observers = Observers(self, writer)
        last = (model.phase, state["lam"] if state is not None else 0.0)
        try:
            for k in phases:
                resumed = state if state is not None and state.get("phase", 0) == k else None
                if resumed is None:
                    model.set_path(k, 0.0)  # where the previous phase ended
                self._fold_linear_counts()
                self.driver = self._driver(k)
                writer.start_phase(k)
                if not model.path.implicit:
                    spec = model.path.phases[k]
                    switched = "".join(
                        f"; contact {c.name!r} switched " + ("on (its penalty ramped in over the phase)"
                                                             if model.path.switch(k, c.index) == "on" else "off")
                        for c in model.contacts if model.path.switch(k, c.index))
                    self.log(f"phase {k + 1} {spec.name!r}: τ from {spec.start:g} to {spec.start + spec.length:g}"
                             + switched)
                if isinstance(self.driver, LoadStepping):
                    self.driver.run(observers, out_dir, resumed, arrays)
                    last = (k, 1.0)
                else:  # continuation ends where its probe reaches stop_value: the next phase starts there
                    self.driver.run(observers, out_dir, resumed, arrays)
                    last = (k, float(model.load_factor.value))
                    if not model.path.implicit:
                        model.path.end_phase_at(k, last[1])
                writer.end_phase(k, "completed")
        except BaseException as err:
            if writer.steps:
                last = (writer.steps[-1].get("phase", 1) - 1 if not model.path.implicit else model.phase,
                        writer.steps[-1]["load_factor"])
            model.set_path(*last)
            message = str(err) or type(err).__name__
            status = "interrupted" if isinstance(err, KeyboardInterrupt) else "failed"
            writer.end_phase(model.phase, status)
            writer.finish(status, message, self.split())
            raise
        writer.finish("completed", "", self.split())
        return writer


class _Aside:
    """Timers that keep one phase name's seconds to themselves (``get``) and
    pass every other name on."""

    def __init__(self, timers, name):
        self.timers, self.name, self.seconds = timers, name, 0.0

    @contextmanager
    def __call__(self, phase):
        if phase != self.name:
            with self.timers(phase):
                yield
            return
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.seconds += time.perf_counter() - t0

    def get(self, phase):
        return self.seconds if phase == self.name else self.timers.get(phase)
