"""The continuation driver: arc-length or displacement control
(:mod:`.continuation`) until the stop probe's displacement component reaches
steps.stop_value; the step size follows the Newton iterations of the last
step (× √(target / iterations), clipped to [0.5, 2]; held within two iterations
above the target: :func:`step_factor`). Where λ turns, the limit point is
located between the steps around the turn (PathFollowing._locate). A
deformable master's pairing is searched at every converged point."""
import time

import numpy as np

from .. import _dolfinx as dfx
from ..model.inversion import INVERTED_ELEMENT, describe_inverted
from .continuation import ArcLengthConstraint, Bordered, ContinuationFailure, DisplacementConstraint
from .continuation import step as continuation_step
from .load_stepping import StepFailure

AXIS = {"x": 0, "y": 1, "z": 2}

#: Locating a limit point: re-solves until the bracket of the extremum of λ (or the change of the
#: best point) is below LOCATE_WIDTH of the two steps around the turn, at most LOCATE_TRIALS.
LOCATE_WIDTH, LOCATE_TRIALS = 1e-3, 12
GOLDEN = 0.381966

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

    def _constraint(self, state, probe, axis, target, t):
        """The step's constraint; a fresh arc length's first size is steps.initial × |t|, t the tangent at λ = 0."""
        st, model = self.scene["steps"], self.model
        if st["control"] == "arclength":
            if state is not None:
                return ArcLengthConstraint(state["size0"])
            size = st["initial"] * t.norm()
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

    def _converged_at(self, x, lam, commit=True):
        """At a converged point (x, λ): the contacts evaluated and (``commit``)
        their history committed, the deformable pairing searched afresh for the
        next step, and the tangent t = −K⁻¹q there (the next step's predictor)."""
        model = self.model
        self._take(x)
        model.set_load_factor(lam)
        if commit:
            model.problem.prepare_contacts()
            for c in model.contacts:
                c.commit()
        self._search(fresh=True)
        self.bordered.assemble(x)
        return self.bordered.tangent_direction().copy()

    def _search(self, fresh):
        """The deformable contacts' pairing at the current u (Model.update_pairing); whether it changed."""
        if not self.model.problem.global_contacts:
            return False
        with self.timers("contact search"):
            return self.model.update_pairing(fresh)

    def _advance(self, x, lam, du_prev, t, reference=0.0):
        """One continuation step from the converged (x, λ) whose tangent is t,
        solved again from the same point while a deformable contact's pairing
        grows (a slave point found a master facet outside it) and the grown
        pairing leaves x out of equilibrium; a converged state with det F ≤ 0
        fails. Returns (Δu, Δλ, Newton iterations, norms)."""
        sv, model = self.scene["solver"], self.model
        its = 0
        for _ in range(6):
            Du, dlam, more, norms = continuation_step(self.bordered, self.constraint, x, lam, du_prev,
                                                      model.set_load_factor, sv["rtol"], sv["atol"], sv["max_it"],
                                                      tangent=t, reference=reference)
            its += more
            self._take(x)
            if not self._search(fresh=False):
                break
            # the pairing grew (pattern rebuilt): if the new facets change nothing (they are not in
            # contact), x is still converged; else the same step again with them
            model.set_load_factor(lam + dlam)
            if self.bordered.residual_norm(x) <= self.bordered.tolerance:
                break
            x.axpy(-1.0, Du)
            self._take(x)
            model.set_load_factor(lam)
            self.bordered.assemble(x)
            t = self.bordered.tangent_direction().copy()
        self._refuse_inverted(x, Du, lam)
        return Du, dlam, its, norms

    def _snapshot(self, x, lam, du_prev, t):
        """What a step starts from, for re-solving it with other sizes (limit points)."""
        contacts = []
        for c in self.model.contacts:
            meta, data = c.state_dict()
            contacts.append((meta, {k: np.array(v, copy=True) for k, v in data.items()}))
        return {"x": x.copy(), "lam": lam, "du_prev": du_prev, "t": t, "contacts": contacts}

    def _restore(self, x, a):
        a["x"].copy(x)
        for c, (meta, data) in zip(self.model.contacts, a["contacts"]):
            c.load_state_dict(meta, {k: np.array(v, copy=True) for k, v in data.items()})
        self._take(x)
        self.model.set_load_factor(a["lam"])
        self._search(fresh=True)

    def _probes(self):
        return {name: [float(v) for v in pr.value(self.model.u)] for name, pr in self.model.probes.items()}

    def _locate(self, x, steps, sign):
        """The extremum of λ over the two steps around the turn: ``steps`` =
        [(start state, size), …] of the two converged steps a−1 → a → b, whose
        sizes add up to the path parameter s (chord arc length or controlled
        displacement) from a−1. Brent's safeguarded parabolic search on sign × λ(s),
        each λ(s) a re-solve from the step start below s with the rest of s as its
        size, from the saved state (solution, contact history, pairing): the path
        is the run's own, with friction too (no derivative of the path is needed,
        which with friction the committed states' stick tangent would not give).
        Leaves x, contacts and constraint at the second start (a); the caller
        takes the step to b again. Returns the limit's record."""
        t0 = time.perf_counter()
        (a0, size0), (a1, size1) = steps
        span = abs(size0) + abs(size1)
        lam_b = a1["lam_end"]
        # (s, λ, probes) at a−1, a, b: a is the sampled extremum
        pts = [(0.0, a0["lam"], None), (abs(size0), a1["lam"], a1["probes"]), (span, lam_b, None)]
        its, evals, why = 0, 0, "converged"
        tol = LOCATE_WIDTH * span
        # a re-solve converges to the tolerance of the steps it re-solves (relative to their predictor's
        # residual): a shorter step's predictor residual is smaller, and its own tolerance could fall below
        # the round-off floor of |R|
        reference = max(a0["reference"], a1["reference"])
        while True:
            (s0, l0, _), (s1, l1, _), (s2, l2, _) = pts
            if s2 - s0 <= tol:
                break
            v0, v1, v2 = sign * l0, sign * l1, sign * l2
            den = (s1 - s0) * (v1 - v2) - (s1 - s2) * (v1 - v0)
            num = (s1 - s0) ** 2 * (v1 - v2) - (s1 - s2) ** 2 * (v1 - v0)
            s_new = s1 - 0.5 * num / den if den != 0 else None
            if s_new is not None and s0 < s_new < s2:
                if abs(s_new - s1) <= tol:
                    break  # the parabola through the bracket peaks at the best point
                s_new = float(np.clip(s_new, s0 + tol, s2 - tol))
            else:  # golden section into the larger side
                s_new = s1 + GOLDEN * (s2 - s1) if s2 - s1 > s1 - s0 else s1 - GOLDEN * (s1 - s0)
            if evals == LOCATE_TRIALS:
                why = f"the bracket is still {(s2 - s0) / span:.1e} of the two steps after {evals} re-solves"
                break
            start, size = (a0, size0) if s_new < abs(size0) else (a1, size1)
            offset = 0.0 if start is a0 else abs(size0)
            self._restore(x, start)
            self.constraint.size = np.sign(size) * (s_new - offset)
            try:
                Du, dlam, more, _ = self._advance(x, start["lam"], start["du_prev"], start["t"], reference)
            except ContinuationFailure as err:
                self._take(x)
                why = f"a re-solve failed ({err})"
                break
            its, evals = its + more, evals + 1
            new = (s_new, start["lam"] + dlam, self._probes())
            if sign * new[1] > sign * l1:
                pts = [pts[0], new, pts[1]] if s_new < s1 else [pts[1], new, pts[2]]
            else:
                pts = [new, pts[1], pts[2]] if s_new < s1 else [pts[0], pts[1], new]
        self._restore(x, a1)
        self.constraint.size = size1
        s_best, lam_best, probes = pts[1]
        record = {"load_factor": lam_best, "located": why == "converged", "re_solves": evals,
                  "newton_iterations": its, "bracket": (pts[2][0] - pts[0][0]) / span,
                  "seconds": time.perf_counter() - t0, "probes": probes}
        if why != "converged":
            record["why_not_located"] = why
        return record

    def run(self, observer, out_dir, state=None, arrays=None):
        st, model = self.scene["steps"], self.model
        x = model.problem.x
        model.w.vector.copy(x)
        probe = model.probes[st["stop_probe"]]
        axis, target = AXIS[st["stop_component"]], st["stop_value"]
        lam, du_prev, cuts, last_dlam = 0.0, None, 0, None
        if state is not None:
            lam, last_dlam = state["lam"], state["last_dlam"]
            if "du_prev" in arrays:
                du_prev = x.duplicate()
                du_prev.array[:] = arrays["du_prev"]
        t = self._converged_at(x, lam, commit=False)  # the pairing and the first step's tangent
        self.constraint = constraint = self._constraint(state, probe, axis, target, t)
        size0 = constraint.size
        if state is not None:
            size0, constraint.size = state["size0"], state["size"]
        before = None  # the last converged step: (its start state, its size), to locate a limit point in it
        while observer.steps_written() < st["max_steps"]:
            reached = probe.value(model.u)[axis]
            if (reached - target) * np.sign(target) >= -1e-12 * abs(target):
                return
            if st["control"] == "displacement":
                constraint.size = np.sign(target) * min(abs(constraint.size), abs(target - reached))
            start = self._snapshot(x, lam, du_prev, t) if st["locate_limits"] else None
            try:
                Du, dlam, its, norms = self._advance(x, lam, du_prev, t)
            except ContinuationFailure as err:
                self._take(x)  # the failed iterates passed through the unknown
                too_small = 0.5 * abs(constraint.size) < st["min"] * abs(size0)
                stop = cuts >= st["max_cutbacks"] or too_small
                observer.failed({"step": observer.steps_written() + 1, "attempt": cuts, "load_factor": lam,
                                 "size": float(constraint.size), "reason": str(err),
                                 "outcome": "stopped" if stop else "cut back"})
                if stop:
                    self.log(f"   {constraint.name} step from λ = {lam:.5g} failed ({err}); no cut-back left")
                    why = ("its size would fall below steps.min × the first step's" if too_small
                           else f"after {cuts} cut-back{'s' * (cuts != 1)}")
                    raise StepFailure(
                        f"{constraint.name} step from λ = {lam:.6g} did not converge, {why} ({err}); "
                        f"{observer.steps_written()} converged step(s) are in {out_dir}") from None
                cuts += 1
                constraint.scale(0.5)
                self.log(f"   {constraint.name} step from λ = {lam:.5g} failed ({err}); size halved")
                self._search(fresh=True)
                continue
            cuts = 0
            if last_dlam is not None and dlam * last_dlam < 0:
                self._limit_point(observer, x, before, (start, constraint.size), lam, dlam, last_dlam)
                if before is not None and start is not None:  # the re-solves left everything at a: step to b again
                    Du, dlam, its, norms = self._advance(x, lam, du_prev, t)
            t = self._converged_at(x, lam + dlam)
            if start is not None:
                start.update(lam_end=lam + dlam, reference=self.bordered.reference)
                before = (start, constraint.size)
            lam += dlam
            du_prev = Du
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

    def _limit_point(self, observer, x, before, this, lam, dlam, last_dlam):
        """Δλ changed sign: λ turned between the start of the last converged
        step and the end of this one (x at it, λ + Δλ). Records the limit point,
        located there (steps.locate_limits) or the extreme sampled load factor."""
        maximum = last_dlam > 0
        sampled = lam  # the end of the last step: its neighbours are both below (maximum) or above it
        record = {"after_step": observer.steps_written(), "kind": "maximum" if maximum else "minimum",
                  "sampled_load_factor": sampled}
        if before is None or this[0] is None:
            why = ("steps.locate_limits = false" if this[0] is None
                   else "the turn is within the first step after a start or restart")
            record.update(load_factor=sampled, located=False, why_not_located=why, probes=None)
        else:
            before[0]["probes"] = None
            this[0].update(lam_end=lam + dlam, reference=self.bordered.reference)
            this[0]["probes"] = self._probes_at(x, this[0])
            record.update(self._locate(x, [before, this], 1.0 if maximum else -1.0))
        observer.limit_point(record)
        how = "located" if record["located"] else f"sampled ({record.get('why_not_located')})"
        self.log(f"   limit point ({record['kind']} of λ) {how} at λ = {record['load_factor']:.7g}"
                 + (f" in {record['re_solves']} re-solves, {record['newton_iterations']} Newton iterations"
                    if "re_solves" in record else ""))

    def _probes_at(self, x, start):
        """The probes' displacements at a saved start state (x is put back after)."""
        current = x.copy()
        start["x"].copy(x)
        self._take(x)
        probes = self._probes()
        current.copy(x)
        self._take(x)
        return probes
