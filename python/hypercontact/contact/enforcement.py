"""How the normal contact condition is enforced: a penalty ε_N, or an
augmented Lagrangian with one multiplier λ_N per slave point.

The kernels' pressure is ⟨λ_N − ε_N g⟩ (smoothed over the band δ), so
λ_N = 0 is the penalty exactly. The augmented Lagrangian holds λ_N fixed in a
Newton solve and updates it between solves (Uzawa: λ_N ← the current
pressures) until the largest penetration is within the gap tolerance; the
multipliers are committed with the step and restored on a cut-back. They
belong to the slave point: a new master facet or a rebuilt pairing keeps them.
"""
import numpy as np


class Penalty:
    augmented = False
    gap_tolerance = None
    max_augmentations = 0

    def __init__(self, num_points):
        self.multipliers = np.zeros(0)

    def augment(self, state):
        pass

    def commit(self):
        pass

    def forget(self):
        pass

    def restore(self):
        pass

    def state_dict(self):
        return {}, {}

    def load_state_dict(self, meta, arrays):
        pass


class AugmentedLagrangian:
    augmented = True

    def __init__(self, num_points, gap_tolerance, max_augmentations):
        self.gap_tolerance, self.max_augmentations = float(gap_tolerance), int(max_augmentations)
        self.multipliers = np.zeros(num_points)
        self.committed = self.multipliers.copy()

    def augment(self, state):
        """Uzawa: λ_N ← ⟨λ_N − ε_N g⟩, the pressures of the evaluation."""
        self.multipliers = np.ascontiguousarray(state.pressure, dtype=float)

    def commit(self):
        self.committed = self.multipliers.copy()

    def forget(self):
        """The pair is switched off: no multiplier carries over."""
        self.multipliers = np.zeros_like(self.multipliers)

    def restore(self):
        self.multipliers = self.committed.copy()

    def state_dict(self):
        return {}, {"multipliers": self.committed}

    def load_state_dict(self, meta, arrays):
        self.multipliers = np.asarray(arrays["multipliers"], dtype=float).copy()
        self.committed = self.multipliers.copy()
