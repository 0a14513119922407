"""Wall-time split of a run into named phases."""
import time
from contextlib import contextmanager


class Timers:
    """Accumulates wall time per phase: ``with timers("contact"): ...``."""

    def __init__(self):
        self.seconds = {}
        self.calls = {}
        #: what the linear solver did (load control; inside "linear solve", not a phase of its own):
        #: preconditioner set-ups (or factorisations), their time and the Krylov (or triangular) solves' time
        self.linear = {}

    @contextmanager
    def __call__(self, phase):
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.seconds[phase] = self.seconds.get(phase, 0.0) + time.perf_counter() - t0
            self.calls[phase] = self.calls.get(phase, 0) + 1

    def get(self, phase):
        return self.seconds.get(phase, 0.0)
