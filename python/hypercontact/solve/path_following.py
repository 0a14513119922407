"""The continuation driver: arc-length or displacement control
(:mod:`.continuation`) until the stop probe's displacement component reaches
steps.stop_value; the step size follows the Newton iterations of the last
step (× √(target / iterations), clipped to [0.5, 2]; held within two iterations
above the target: :func:`step_factor`)."""
import numpy as np

from .. import _dolfinx as dfx
from ..model.inversion import INVERTED_ELEMENT, describe_inverted
from .continuation import ArcLengthConstraint, Bordered, ContinuationFailure, DisplacementConstraint
from .continuation import step as continuation_step
from .load_stepping import StepFailure

AXIS = {"x": 0, "y": 1, "z": 2}

#: Converged steps of up to this many Newton iterations above the target keep their size.
HOLD_BAND = 2


def step_factor(its, target):
    """The next step's size over this one's after a step converged in ``its`` Newton iterations:
    √(target / its) clipped to [0.5, 2], except that a step up to HOLD_BAND iterations above the target
    keeps its size. Where the iteration count does not fall with the step — sliding points on the Coulomb
    cone, whose stick/slip test sits on a knife edge at any step size — shrinking on every step would
    take the size to nothing without making a step cheaper (the sphere against a plane with friction,
    ε_T = 10 G/h: 200 steps of 7 iterations, stalled 12 mm short of its end, before this band); steps
    that take more than that still shrink, and a failed one is halved."""
    if target < its <= target + HOLD_BAND:
        return 1.0
    return float(np.clip(np.sqrt(target / max(its, 1)), 0.5, 2.0))


class PathFollowing:
    def __init__(self, model, scene, timers, log):
        self.model, self.scene, self.timers, self.log = model, scene, timers, log
        self.bordered = Bordered(model.problem, model.q_form, model.bcs, model.comm, scene["solver"]["petsc"],
                                 timers=timers)

    def _constraint(self, state, probe, axis, target):
        st, model = self.scene["steps"], self.model
        if st["control"] == "arclength":
            if state is not None:
                return ArcLengthConstraint(state["size0"])
            model.set_load_factor(0.0)
            self.bordered.assemble(model.problem.x)
            size = st["initial"] * self.bordered.tangent_direction().norm()
            if not size > 0.0:
                raise StepFailure("arc length cannot start: the [[pressure]] loads do no work on the free "
                                  "degrees of freedom (their load vector is zero once the boundary "
                                  "conditions are applied)")
            return ArcLengthConstraint(size)
        owner_dof = model.unknown_dof(probe.node, axis) if model.comm.rank == probe.owner else -1
        return DisplacementConstraint(owner_dof, probe.owner, model.comm, st["initial"] * target)

    def _refuse_inverted(self, x, Du, lam):
        """A converged step (x = x0 + Du) whose state has det F ≤ 0 somewhere
        is undone (x, λ as before) and fails, naming the element."""
        self._take(x)
        with self.timers("inversion check"):
            inverted = self.model.inversion_check()
        if inverted is not None:
            x.axpy(-1.0, Du)
            self.model.set_load_factor(lam)
            raise ContinuationFailure(f"{INVERTED_ELEMENT}, {describe_inverted(inverted)}")

    def _take(self, x):
        x.copy(self.model.w.vector)
        dfx.update_ghosts(self.model.w)
        self.model.sync_displacement()

    def run(self, observer, out_dir, state=None, arrays=None):
        st, sv, model = self.scene["steps"], self.scene["solver"], self.model
        x = model.problem.x
        model.w.vector.copy(x)
        probe = model.probes[st["stop_probe"]]
        axis, target = AXIS[st["stop_component"]], st["stop_value"]
        constraint = self._constraint(state, probe, axis, target)
        size0 = constraint.size
        lam, du_prev, cuts, last_dlam = 0.0, None, 0, None
        if state is not None:
            lam, last_dlam, size0, constraint.size = state["lam"], state["last_dlam"], state["size0"], state["size"]
            model.set_load_factor(lam)
            if "du_prev" in arrays:
                du_prev = x.duplicate()
                du_prev.array[:] = arrays["du_prev"]
        while observer.steps_written() < st["max_steps"]:
            reached = probe.value(model.u)[axis]
            if (reached - target) * np.sign(target) >= -1e-12 * abs(target):
                return
            if st["control"] == "displacement":
                constraint.size = np.sign(target) * min(abs(constraint.size), abs(target - reached))
            try:
                Du, dlam, its, norms = continuation_step(self.bordered, constraint, x, lam, du_prev,
                                                         model.set_load_factor, sv["rtol"], sv["atol"], sv["max_it"])
                self._refuse_inverted(x, Du, lam)
            except ContinuationFailure as err:
                self._take(x)  # the failed iterates passed through the unknown
                too_small = 0.5 * abs(constraint.size) < st["min"] * abs(size0)
                if cuts >= st["max_cutbacks"] or too_small:
                    self.log(f"   {constraint.name} step from λ = {lam:.5g} failed ({err}); no cut-back left")
                    why = ("its size would fall below steps.min × the first step's" if too_small
                           else f"after {cuts} cut-back{'s' * (cuts != 1)}")
                    raise StepFailure(
                        f"{constraint.name} step from λ = {lam:.6g} did not converge, {why} ({err}); "
                        f"{observer.steps_written()} converged step(s) are in {out_dir}") from None
                cuts += 1
                constraint.scale(0.5)
                self.log(f"   {constraint.name} step from λ = {lam:.5g} failed ({err}); size halved")
                continue
            cuts = 0
            lam += dlam
            du_prev = Du
            self._take(x)
            model.problem.prepare_contacts()
            for c in model.contacts:
                c.commit()
            if last_dlam is not None and dlam * last_dlam < 0:
                observer.limit_point(observer.steps_written(), lam - dlam)
                self.log(f"   limit point: the load factor turned at λ ≈ {lam - dlam:.6g}")
            last_dlam = dlam
            factor = step_factor(its, st["target_iterations"])
            if st["control"] == "arclength":
                constraint.size = min(constraint.size * factor, size0 * st["max"] / st["initial"])
            else:
                constraint.size = np.sign(target) * min(abs(constraint.size) * factor, abs(target) * st["max"])
            reached = probe.value(model.u)[axis]
            observer.converged_path(lam, its, norms, reached, target,
                                    {"lam": lam, "last_dlam": last_dlam, "size": constraint.size, "size0": size0},
                                    du_prev.array_r)
        raise StepFailure(f"steps.max_steps = {st['max_steps']} reached before {st['stop_probe']} "
                          f"u{st['stop_component']} = {target}; {observer.steps_written()} steps are in {out_dir}")
