"""A scene → a running simulation: :class:`Simulation` builds the model
(:mod:`hypercontact.model`: only the effects the scene names) and solves it
(:mod:`hypercontact.solve`: incremental loading with automatic step control,
or continuation)."""
from mpi4py import MPI

from .model import Model
from .model.inversion import INVERTED_ELEMENT
from .solve.load_stepping import FORCED_FAILURE, StepFailure
from .solve.run import Run
from .timing import Timers

__all__ = ["Simulation", "StepFailure", "FORCED_FAILURE", "INVERTED_ELEMENT"]


class Simulation:
    """Everything one scene needs, built once; :meth:`run` solves it."""

    def __init__(self, scene, comm=MPI.COMM_WORLD, law=None, log=None, fail_attempt=None, map_mesh=None):
        """``law``: a Python ψ(F, **params) in place of the scene's material
        law (it gets the scene parameters it names). ``map_mesh(body)``: moves
        the mesh nodes before anything is built on them.

        ``fail_attempt``: None, or a callable ``fail_attempt(step, lam, dlam,
        attempt) -> bool`` asked once per attempt at a load-control step,
        after its Newton solve(s): ``step`` is the number the step would get
        (1 for the first), ``lam`` the load factor it starts from, ``dlam``
        the increment tried, ``attempt`` 0 for the first try and k after k
        cut-backs of this step. True makes a converged attempt fail as if
        SNES had diverged (reason FORCED_FAILURE): its state is discarded,
        its story goes to summary.json's ``failed_attempts`` and the step is
        cut back (or the run stops). For tests and what-if studies of the
        step control, independent of where rounding makes a solve fail; the
        answers of all ranks are or-ed."""
        self.scene, self.comm = scene, comm
        self.log = log if log is not None else (print if comm.rank == 0 else (lambda *a, **k: None))
        self.timers = Timers()
        with self.timers("setup"):
            self.model = Model(scene, comm, self.timers, law, map_mesh)
            self.runner = Run(self.model, scene, self.timers, self.log, fail_attempt)

    def run(self, out_dir=None, resume=False):
        """Solve the scene's load path. Returns the results writer; raises
        :class:`StepFailure` after writing everything that converged. With
        ``resume``, continue from the checkpoint in the results folder."""
        return self.runner(out_dir or self.scene["output"]["dir"], resume)

    # --- what driver scripts and tests read ------------------------------------------
    @property
    def driver(self):
        """The load-stepping or path-following driver."""
        return self.runner.driver

    @property
    def newton(self):
        """The Newton solver of load control (None before a run or under continuation)."""
        return getattr(self.runner.driver, "newton", None)

    @property
    def snes(self):
        return self.newton.snes if self.newton is not None else None

    @property
    def bordered(self):
        """The bordered solves of continuation (None before a run or under load control)."""
        return getattr(self.runner.driver, "bordered", None)

    @property
    def linear_iterations(self):
        return self.newton.linear_iterations if self.newton is not None else []

    def set_load_factor(self, lam):
        self.model.set_load_factor(lam)

    def __getattr__(self, name):
        """The model's parts: u, w, V, body, contacts, bcs, probes, problem, effects, stress, q_form…"""
        if name in ("model", "runner"):
            raise AttributeError(name)
        return getattr(self.model, name)
