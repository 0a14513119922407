"""Load control: λ goes 0 → 1 in steps, a Newton solve per step, Δλ cut
back on failure (:mod:`.step_control`). One attempt at a step is the Newton
solve, solved again while a deformable contact's pairing grows, then the
augmented Lagrangian's updates, then the ``fail_attempt`` hook."""
from mpi4py import MPI

from ..model.inversion import describe_inverted
from .augmented import augment_until_within
from .monitor import describe_residual, largest_residuals
from .newton_solver import NewtonSolver
from .step_control import LoadStepper

#: reason of an attempt made to fail by the fail_attempt hook
FORCED_FAILURE = "FORCED_FAILURE"


class StepFailure(RuntimeError):
    """A load step did not converge after the allowed cut-backs."""


def unstable(negative):
    """The stop message's diagnosis of a last converged state whose tangent had
    ``negative`` negative eigenvalues (None: not known)."""
    if not negative:
        return ""
    return (f"; the last converged step's tangent had {negative} negative eigenvalue{'s' * (negative != 1)}: that "
            "equilibrium is unstable, past a bifurcation or a limit point of the path, which load control cannot "
            "follow (negative_eigenvalues per step in summary.json)")


class LoadStepping:
    """The load-control driver of a model. ``fail_attempt(step, lam, dlam,
    attempt) -> bool``: see Simulation."""

    def __init__(self, model, scene, timers, log, fail_attempt=None):
        self.model, self.scene, self.timers, self.log = model, scene, timers, log
        self.fail_attempt = fail_attempt
        self.newton = NewtonSolver(model, scene["solver"], timers)
        self.augmentations = 0
        self.linear_its = 0  # Krylov iterations of the last attempt, all its Newton solves
        self.reference = 0.0  # the last attempt's reference |R_0| (attempt): 0 unless it was predicted
        # negative eigenvalues of the last attempt's last factorised tangent, and of the last
        # converged step's (NewtonSolver.negative_eigenvalues; None where unknown)
        self.negative_eigenvalues = self.converged_negative_eigenvalues = None

    def update_pairing(self, fresh):
        """The model's pairing (Model.update_pairing); a new matrix goes to the solver."""
        with self.timers("contact search"):
            changed = self.model.update_pairing(fresh)
            if changed:
                self.newton.use_matrix(self.model.problem.A)
        return changed

    def attempt(self, step, lam, dlam, attempt, prediction=None):
        """One attempt at λ → λ + Δλ from the last converged state, or from
        ``prediction`` (an array of the unknown): (converged, Newton iterations,
        last norms, reason)."""
        model = self.model
        model.set_load_factor(lam + dlam)
        self.newton.solves.clear()  # the attempt's own solves: its story and its Krylov count
        reference = 0.0
        if prediction is not None:
            # the relative tolerance measures against |R| at the last converged state under the new
            # load, the |R_0| of the same solve without the prediction: the predictor changes where
            # Newton starts, not where it stops (one residual evaluation per step)
            self.update_pairing(fresh=True)
            reference = self.newton.residual_norm()
            model.w.x.array[:] = prediction
            model.sync_displacement()
        self.reference = reference
        self.update_pairing(fresh=True)
        ok, its, norms, reason = self.newton.solve(reference)
        for _ in range(5 if ok else 0):
            # a point found a master facet outside the pattern: solve again with it
            if not self.update_pairing(fresh=False):
                break
            ok, more, norms, reason = self.newton.solve(reference)
            its += more
            if not ok:
                break
        self.augmentations = 0
        if ok:
            ok, more, self.augmentations, n, r = augment_until_within(
                self.model.contacts, self.model.problem.prepare_contacts, self.newton.solve, self.log)
            its += more
            norms, reason = (n if n is not None else norms), (r if r is not None else reason)
        forced = self.fail_attempt is not None and bool(self.fail_attempt(step, lam, dlam, attempt))
        if self.model.comm.allreduce(forced, op=MPI.LOR) and ok:
            ok, reason = False, FORCED_FAILURE
        self.linear_its = sum(s["linear_iterations"] for s in self.newton.solves)
        self.negative_eigenvalues = self.newton.negative_eigenvalues()
        return ok, its, norms, reason

    def failure_story(self, step, lam, dlam, attempt, reason, norms):
        """What a failed attempt did, for summary.json. Collective."""
        h = self.newton.history
        story = {"step": step, "attempt": attempt, "load_factor": lam, "dlam": dlam, "reason": reason,
                 "snes_reason": self.newton.last_snes_reason, "newton_iterations": self.newton.iterations(),
                 "linear_iterations": self.linear_its, "residual_norms": list(norms), "update_norms": list(h.update_norms),
                 "active_set_changes": h.active_set_changes(), "stick_slip_changes": h.stick_slip_changes(),
                 "augmentations": self.augmentations}
        story["solves"] = list(self.newton.solves)  # every Newton solve of the attempt; the norms and flips above are the last's
        story["attempt_newton_iterations"] = sum(s["newton_iterations"] for s in story["solves"])
        story.update(h.flip_story(self.model.u, self.model.comm))
        story["largest_residuals"] = largest_residuals(self.model, self.newton.snes.getFunction()[0])
        if self.newton.inverted is not None:
            story["inverted_element"] = self.newton.inverted
        if self.negative_eigenvalues is not None:
            story["negative_eigenvalues"] = self.negative_eigenvalues
        return story

    def run(self, observer, out_dir, state=None, arrays=None):
        """Solve the load path; ``observer.converged(lam, its, norms, reason,
        history, controller_state, **arrays)`` after each converged step (what a
        checkpoint needs to resume it: ``state`` and ``arrays``), ``observer.failed(story)``
        after each failed attempt. Raises StepFailure when no cut-back is left."""
        model, steps = self.model, self.scene["steps"]
        stepper = LoadStepper.from_scene(steps)
        # the secant predictor: a step's first attempt starts from the last two converged states
        # extrapolated to its load, u_n + (Δλ/Δλ_n)(u_n − u_n−1), not from u_n (none for a path's
        # first step, nor for the retries after a cut-back)
        secant = steps["predictor"] == "secant"
        u_step = dlam_step = None  # the last converged step's increment of the unknown and its Δλ
        if state is not None:
            stepper.load_state_dict(state)
            model.set_load_factor(stepper.lam)
            if secant and state.get("predictor_dlam") and arrays and "predictor_step" in arrays:
                u_step, dlam_step = arrays["predictor_step"], state["predictor_dlam"]
        u_saved = model.w.x.array.copy()
        while not stepper.done():
            lam, dlam = stepper.lam, stepper.increment()
            number = observer.steps_written() + 1
            # a step's first attempt only: a retry after a cut-back starts from u_n, where the previous
            # step converged, not from an extrapolation that may have led it astray
            prediction = (u_saved + (dlam / dlam_step) * u_step
                          if u_step is not None and stepper.cuts == 0 else None)
            ok, its, norms, reason = self.attempt(number, lam, dlam, stepper.cuts, prediction)
            if ok:
                self.converged_negative_eigenvalues = self.negative_eigenvalues
                # the step's size follows the iterations its Newton path took from the step's start: a
                # fallback that did not take the full steps again saved their work, the step was no easier
                stepper.converged(its + self.newton.iterations_not_repeated())
                model.problem.prepare_contacts()  # the converged state: commit and results read it
                for c in model.contacts:
                    c.commit()
                if secant:
                    u_step, dlam_step = model.w.x.array - u_saved, dlam
                u_saved[:] = model.w.x.array
                controller, saved = stepper.state_dict(), {}
                if u_step is not None:
                    controller["predictor_dlam"], saved["predictor_step"] = dlam_step, u_step
                observer.converged(stepper.lam, its, norms, reason, self.newton.history, controller, **saved)
                continue
            stop = not stepper.can_cut()
            story = self.failure_story(number, lam, dlam, stepper.cuts, reason, norms)
            story["outcome"] = "stopped" if stop else "cut back"
            observer.failed(story)
            model.w.x.array[:] = u_saved
            model.sync_displacement()
            for c in model.contacts:
                c.restore()
            self._log_failure(story, lam, dlam, its, reason, stop)
            if stop:
                where = f"; {describe_inverted(story['inverted_element'])}" if "inverted_element" in story else ""
                where += unstable(self.converged_negative_eigenvalues)
                cuts = stepper.cuts
                raise StepFailure(
                    f"load step from λ = {lam:.6g} did not converge after {cuts} cut-back{'s' * (cuts != 1)} "
                    f"(last Δλ = {dlam:.3g}, reason {reason}{where}); {observer.steps_written()} converged "
                    f"step(s) are in {out_dir} (what each failed attempt did: failed_attempts in summary.json)")
            stepper.failed()

    def _log_failure(self, story, lam, dlam, its, reason, stop):
        warn = self.scene["steps"]["chatter_warning"]
        chatter = "".join(f"; the {what} changed in {story[key]} Newton iterations (chattering)"
                          for what, key in (("contact active set", "active_set_changes"),
                                            ("stick/slip status", "stick_slip_changes"))
                          if story[key] >= warn)
        switching = sum(1 for n in story["master_facet_flips_per_iteration"] if n > 0)
        if switching >= warn:
            first = story["most_master_facet_flips"][0]
            chatter += (f"; slave points switched master facet in {switching} Newton iterations (on a kink of "
                        f"the master, e.g. over an edge between two facets: {first['contact']!r} at "
                        f"{tuple(round(v, 4) for v in first['point'])})")
        where = f"; {describe_inverted(story['inverted_element'])}" if "inverted_element" in story else ""
        if story.get("largest_residuals"):
            where += "; " + describe_residual(story["largest_residuals"][0])
        self.log(f"   step at λ = {lam:.4f} + {dlam:.3g} failed ({reason}, {its} its{chatter}{where}); "
                 + ("no cut-back left" if stop else f"cut back to Δλ = {0.5 * dlam:.3g}"))
