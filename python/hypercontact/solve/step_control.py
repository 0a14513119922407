"""Load-step control: the increment Δλ of the next step from what the last
steps did. Pure: no mesh, no solver; :class:`LoadStepper` is its whole state.

After a converged step of ``its`` Newton iterations: Δλ grows by ``growth``
(up to ``max``) when its ≤ ``grow_below``; otherwise, after a cut-back, it
grows back towards the Δλ that failed once ``grow_after`` steps in a row have
converged (steps that always take more than grow_below iterations — friction,
deformable masters — would otherwise keep the cut Δλ to the end). After a
failed attempt Δλ is halved, up to ``max_cutbacks`` times in a row and not
below ``min``.
"""
from dataclasses import asdict, dataclass


@dataclass
class LoadStepper:
    initial: float
    max: float
    min: float
    growth: float
    grow_below: int
    grow_after: int
    max_cutbacks: int
    lam: float = 0.0
    dlam: float = None
    cuts: int = 0  # cut-backs of the current step
    streak: int = 0  # converged steps since the last cut-back or growth
    regrow_to: float = 0.0  # the Δλ that failed before the last cut-back

    def __post_init__(self):
        if self.dlam is None:
            self.dlam = self.initial

    @classmethod
    def from_scene(cls, steps):
        keys = ("initial", "max", "min", "growth", "grow_below", "grow_after", "max_cutbacks")
        return cls(**{k: steps[k] for k in keys})

    def done(self):
        return self.lam >= 1.0 - 1e-12

    def increment(self):
        """The Δλ of the next attempt (never past λ = 1)."""
        self.dlam = min(self.dlam, 1.0 - self.lam)
        return self.dlam

    def converged(self, iterations):
        """Accept the attempt: λ += Δλ, and the next Δλ."""
        self.lam += self.dlam
        self.cuts = 0
        self.streak += 1
        if iterations <= self.grow_below:
            self.dlam, self.streak = min(self.dlam * self.growth, self.max), 0
        elif self.grow_after and self.streak >= self.grow_after and self.dlam < self.regrow_to:
            self.dlam, self.streak = min(self.dlam * self.growth, self.regrow_to, self.max), 0

    def can_cut(self):
        """Whether a failed attempt may be cut back (else the run stops)."""
        return self.cuts < self.max_cutbacks and 0.5 * self.dlam >= self.min

    def failed(self):
        """Cut the failed attempt's Δλ in half."""
        if self.cuts == 0:
            self.regrow_to = self.dlam
        self.cuts, self.streak = self.cuts + 1, 0
        self.dlam *= 0.5

    def state_dict(self):
        return {k: v for k, v in asdict(self).items() if k in ("lam", "dlam", "streak", "regrow_to")}

    def load_state_dict(self, state):
        self.lam, self.dlam = state["lam"], state["dlam"]
        self.streak, self.regrow_to = state.get("streak", 0), state.get("regrow_to", 0.0)
