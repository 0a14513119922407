"""The nonlinear system δW + δW_C = 0 as a PETSc SNES problem.

One Newton iteration (DESIGN.md): dolfinx assembles the volume residual and
tangent, the contact objects add theirs into the same Vec / Mat, and the
Dirichlet conditions are applied last so constrained rows stay exact.
"""
import numpy as np
from petsc4py import PETSc

from . import _dolfinx as dfx


class Problem:
    """Residual and Jacobian callbacks for SNES, with a per-phase timer."""

    def __init__(self, u, R, J, bcs, contacts, timers):
        self.u, self.bcs, self.contacts, self.timers = u, bcs, contacts, timers
        self.R = dfx.compile_form(R)
        self.J = dfx.compile_form(J)
        self.A = dfx.create_matrix(self.J)
        self.b = dfx.create_vector(self.R)
        self.x = self.b.duplicate()
        # A contact entry outside the volume pattern would be a silent malloc:
        # rigid contact couples a node's own dofs only, inside the pattern.
        self.A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, True)

    def _update_u(self, x):
        x.ghostUpdate(addv=PETSc.InsertMode.INSERT, mode=PETSc.ScatterMode.FORWARD)
        x.copy(self.u.vector)
        dfx.update_ghosts(self.u)

    def residual(self, snes, x, b):
        self._update_u(x)
        with self.timers("volume assembly"):
            dfx.assemble_volume_residual(b, self.R)
        if self.contacts:
            with self.timers("contact"), b.localForm() as bl:
                array = bl.array_w
                for c in self.contacts:
                    c.add_residual(self.u, array)
        with self.timers("volume assembly"):
            dfx.finish_residual(b, self.J, self.bcs, x)

    def jacobian(self, snes, x, A, P):
        with self.timers("volume assembly"):
            dfx.assemble_tangent(A, self.J, self.bcs)
        if self.contacts:
            with self.timers("contact"):
                for c in self.contacts:
                    c.add_tangent(self.u, A)
        with self.timers("volume assembly"):
            A.assemble()


def set_prefixed_options(prefix, options):
    """Put ``options`` into PETSc's global options under ``prefix``, first
    removing whatever an earlier simulation in this process left there."""
    opts = PETSc.Options()
    for key in list(opts.getAll()):
        if key.startswith(prefix):
            opts.delValue(key)
    for key, value in options.items():
        opts[prefix + key] = value


def make_snes(problem, comm, solver, prefix="hc_", frictional=False):
    """A newtonls SNES with MUMPS LU by default; solver["petsc"] options
    (without prefix) override anything. Line search "auto": full Newton steps
    ("basic"), except with friction, where the stick/slip switches make full
    steps cycle and the backtracking "bt" converges."""
    snes = PETSc.SNES().create(comm)
    snes.setOptionsPrefix(prefix)
    defaults = {
        "snes_type": "newtonls",
        "snes_linesearch_type": (("bt" if frictional else "basic") if solver["linesearch"] == "auto"
                                 else solver["linesearch"]),
        "ksp_type": "preonly",
        "pc_type": "lu",
        "pc_factor_mat_solver_type": "mumps",
    }
    set_prefixed_options(prefix, {**defaults, **solver["petsc"]})
    snes.setFunction(problem.residual, problem.b)
    snes.setJacobian(problem.jacobian, problem.A)
    snes.setTolerances(rtol=solver["rtol"], atol=solver["atol"], stol=0.0, max_it=solver["max_it"])
    snes.setFromOptions()
    snes.getKSP().setFromOptions()
    return snes


def converged_reason_name(reason):
    names = {v: k for k, v in PETSc.SNES.ConvergedReason.__dict__.items() if isinstance(v, int)}
    return names.get(reason, str(reason))


def residual_norms_of(snes):
    """Residual norm history of the last solve."""
    hist = snes.getConvergenceHistory()
    norms = hist[0] if isinstance(hist, tuple) else hist
    return np.asarray(norms).tolist()
