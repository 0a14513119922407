"""The nonlinear system δW + δW_C = 0 as a PETSc SNES problem.

One Newton iteration (docs/design.md): dolfinx assembles the volume residual
and tangent; each contact is evaluated once at the iterate (prepare) and adds
its residual and tangent from that evaluation into the same Vec / Mat; the
Dirichlet conditions are applied last so constrained rows stay exact.
"""
import numpy as np
from mpi4py import MPI
from petsc4py import PETSc

from .. import _dolfinx as dfx


class Problem:
    """Residual and Jacobian callbacks for SNES, with a per-phase timer."""

    def __init__(self, u, R, J, bcs, contacts, timers):
        self.u, self.bcs, self.contacts, self.timers = u, bcs, contacts, timers
        # Rigid contacts add into the local residual array (their slave node's
        # own dofs); deformable ones add rows anywhere, by global index.
        self.local_contacts = [c for c in contacts if not c.deformable]
        self.global_contacts = [c for c in contacts if c.deformable]
        self.R = dfx.compile_form(R)
        self.J = dfx.compile_form(J)
        self.A = dfx.create_matrix(self.J)
        self.b = dfx.create_vector(self.R)
        self.x = self.b.duplicate()
        # A contact entry outside the pattern would be a silent malloc: rigid
        # contact couples a node's own dofs only, inside the volume pattern;
        # deformable contact gets its couplings in rebuild_pattern.
        self.A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, True)
        self.near_nullspace = None
        if u.function_space.num_sub_spaces == 3 and u.function_space.ufl_element().degree() == 1:
            self.near_nullspace = rigid_body_modes(u.function_space, self.A)
            self.A.setNearNullSpace(self.near_nullspace)
        self._volume_csr = None
        self._prepared_at = None  # the owned unknowns the contacts were last evaluated at
        self.pattern_builds = 0
        self.linear_kind = None  # "direct" or "iterative", set by make_snes

    def rebuild_pattern(self):
        """A new matrix whose pattern is the volume pattern plus the
        slave–master couplings of the deformable contacts' current pairing
        (self.A is replaced; the caller hands it to the solver)."""
        comm = self.A.getComm().tompi4py()
        if self._volume_csr is None:
            dfx.assemble_tangent(self.A, self.J, self.bcs)
            self.A.assemble()
            indptr, cols, _ = self.A.getValuesCSR()
            self._volume_csr = (indptr.astype(np.int64), cols.astype(np.int64))
        indptr, cols = self._volume_csr
        r0, r1 = self.A.getOwnershipRange()
        ranges = np.asarray(self.A.getOwnershipRanges(), dtype=np.int64)
        n_global = self.A.getSize()[1]
        rows = [np.repeat(np.arange(r1 - r0, dtype=np.int64), np.diff(indptr)) + r0]
        colsl = [cols]
        for c in self.global_contacts:
            cr, cc = c.couplings()
            rows.append(cr)
            colsl.append(cc)
        rows, cols_all = np.concatenate(rows), np.concatenate(colsl)
        if comm.size > 1:  # couplings in rows owned elsewhere go to their owner
            owner = np.searchsorted(ranges, rows, side="right") - 1
            outgoing = [(rows[owner == r], cols_all[owner == r]) for r in range(comm.size)]
            incoming = comm.alltoall(outgoing)
            rows = np.concatenate([i[0] for i in incoming])
            cols_all = np.concatenate([i[1] for i in incoming])
        keys = np.unique((rows - r0) * n_global + cols_all)
        local_rows = keys // n_global
        new_indptr = np.searchsorted(local_rows, np.arange(r1 - r0 + 1)).astype(PETSc.IntType)
        new_cols = (keys % n_global).astype(PETSc.IntType)
        A = PETSc.Mat().createAIJ(self.A.getSizes(), bsize=self.A.getBlockSize(), csr=(new_indptr, new_cols),
                                  comm=self.A.getComm())
        A.setLGMap(*self.A.getLGMap())
        A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, True)
        if self.near_nullspace is not None:
            A.setNearNullSpace(self.near_nullspace)
        self.A.destroy()
        self.A = A
        self.pattern_builds += 1
        return A

    def _update_u(self, x):
        x.ghostUpdate(addv=PETSc.InsertMode.INSERT, mode=PETSc.ScatterMode.FORWARD)
        x.copy(self.u.vector)
        dfx.update_ghosts(self.u)

    def prepare_contacts(self):
        """Evaluate every contact once at the current u (collective)."""
        if not self.contacts:
            return
        with self.timers("contact"):
            for c in self.contacts:
                c.prepare(self.u)
        self._prepared_at = self.u.vector.array_r.copy()

    def residual(self, snes, x, b, with_contacts=True):
        """b = R(x); ``with_contacts=False``: the body alone (volume and loads)."""
        self._update_u(x)
        contacts = self.contacts if with_contacts else []
        if contacts:
            self.prepare_contacts()
        with self.timers("volume assembly"):
            dfx.assemble_volume_residual(b, self.R)
        local = [c for c in self.local_contacts if c in contacts]
        if local:
            with self.timers("contact"), b.localForm() as bl:
                for c in local:
                    c.add_residual(bl.array_w)
        with self.timers("volume assembly"):
            dfx.finish_residual(b, self.J, self.bcs, x)
        if contacts and self.global_contacts:
            with self.timers("contact"):
                for c in self.global_contacts:
                    c.add_residual(b)
                b.assemblyBegin()
                b.assemblyEnd()

    def jacobian(self, snes, x, A, P):
        """A = ∂R/∂x at x; the contacts' tangents come from their evaluation at x
        (made again if the last residual was evaluated elsewhere)."""
        if self.contacts and (self._prepared_at is None or
                              not np.array_equal(self._prepared_at, x.array_r)):
            self._update_u(x)
            self.prepare_contacts()
        with self.timers("volume assembly"):
            dfx.assemble_tangent(A, self.J, self.bcs)
        if self.contacts:
            with self.timers("contact"):
                for c in self.contacts:
                    c.add_tangent(A)
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


#: the iterative solver's relative tolerance: at most KRYLOV_RTOL_MAX, at least KRYLOV_RTOL_MIN,
#: in between what the Newton iteration needs (krylov_forcing)
KRYLOV_RTOL_MIN, KRYLOV_RTOL_MAX = 1e-8, 1e-4


def krylov_forcing(fnorm, target):
    """The relative tolerance η of the Krylov solve of a Newton iteration at |R| = fnorm whose
    solve stops at |R| ≤ target (inexact Newton): the linearised residual η |R| it leaves is
    a tenth of the target, so it cannot hold the last iteration back, and never more than
    KRYLOV_RTOL_MAX |R|, a reduction per iteration that none of the contact paths measured
    beats while the active set settles (140.9 → 0.39 → 0.040 → 0.0094 … at 1.1M unknowns);
    never tighter than KRYLOV_RTOL_MIN, the fixed tolerance it replaces. Far from the
    solution this halves the Krylov iterations (AMG reduces the residual about 0.5× per
    iteration: 29 iterations to 1e-8, about 15 to 1e-4)."""
    if not (fnorm > 0 and np.isfinite(fnorm)):
        return KRYLOV_RTOL_MIN
    return float(min(KRYLOV_RTOL_MAX, max(KRYLOV_RTOL_MIN, 0.1 * target / fnorm)))


# Where "auto" stops factorising: the measured crossovers (bench/crossover.py,
# docs/performance.md §2). On the punch against rigid obstacles the whole path
# with GMRES + GAMG took 1.17x the direct solver's time at 13 125 unknowns, 0.81x
# (frictionless) and 0.95x (mu1 = 0.3) at 20 184, 0.82x and 0.72x at 29 403;
# the limit sits where both are clearly past it. Two deformable bodies in contact
# (Hertz) took 1.40x with GAMG at 21 330 unknowns and 1.27x at 40 071, its Krylov
# count growing with the mesh (94 and 118 per tangent, against the punch's 20-34):
# there the old limit stays; where the two cross is not measured.
DIRECT_MAX_UNKNOWNS = {"rigid": 25_000, "deformable": 200_000}


def direct_max_unknowns(solver, deformable=False):
    """The size up to which "auto" factorises: the scene's solver.direct_max_unknowns,
    or the measured crossover for its kind of contact (``deformable``: a deformable
    master, whose coupling of the bodies makes AMG need three times the iterations)."""
    limit = solver.get("direct_max_unknowns")
    return limit if limit is not None else DIRECT_MAX_UNKNOWNS["deformable" if deformable else "rigid"]


def linear_solver_options(solver, num_unknowns, symmetric=False, deformable=False, amg=True):
    """PETSc options of the linear solver the scene asks for: "direct"
    (MUMPS: LDLᵀ where the tangent is ``symmetric``, measured 0.74× the LU's
    linear-solve time on the 32×32×8 punch, else LU), "iterative" (GMRES,
    right-preconditioned by smoothed-aggregation AMG with the rigid-body modes
    as near-nullspace, set up afresh at every Newton iteration: reusing the
    first iteration's interpolation doubled the Krylov count on the punch
    (51 → 34 and 59 → 31 per Newton iteration at 29k and 215k unknowns) and
    cost 10–20 % more time than the set-ups it saved (docs/performance.md);
    GMRES because friction and follower loads make the tangent
    non-symmetric, and a symmetric one is indefinite past a limit point), or
    "auto": direct up to direct_max_unknowns(solver, deformable), iterative
    above (a direct factorisation's memory and time grow faster than linearly
    in 3D) — where ``amg``: the unknowns are a linear displacement field, whose
    rigid-body modes the AMG is given; quadratic and mixed (u–p) spaces get no
    near-nullspace, and "auto" factorises them at any size.

    GAMG coarsens until a level has at most 3000 equations and solves that
    one directly: with 1000, the 32×32×8 punch's hierarchy was 29 403 →
    1 044 → 144 equations, and that last, 24-aggregate level took the
    frictional solves from 40 to 60 Krylov iterations per Newton iteration
    (docs/performance.md §2)."""
    kind = solver["linear"]
    if kind == "auto":
        kind = "iterative" if amg and num_unknowns > direct_max_unknowns(solver, deformable) else "direct"
    if kind == "direct":
        return kind, {"ksp_type": "preonly", "pc_type": "cholesky" if symmetric else "lu",
                      "pc_factor_mat_solver_type": "mumps"}
    return kind, {"ksp_type": "gmres", "ksp_gmres_restart": 200, "ksp_pc_side": "right",
                  "ksp_rtol": KRYLOV_RTOL_MIN, "ksp_max_it": 1000, "pc_type": "gamg",
                  "pc_gamg_coarse_eq_limit": 3000, "mg_levels_ksp_type": "chebyshev",
                  "mg_levels_pc_type": "jacobi", "mg_levels_ksp_max_it": 3,
                  "pc_gamg_reuse_interpolation": False}


def rigid_body_modes(V, A):
    """The six rigid-body modes of the displacement space V (three
    translations, three rotations about the centroid), orthonormalised, as a
    PETSc near-nullspace for A (what GAMG needs to coarsen elasticity)."""
    X = dfx.node_coordinates(V)[: dfx.num_owned_nodes(V)]
    comm = V.mesh.comm
    centre = comm.allreduce(X.sum(axis=0), op=MPI.SUM) / max(comm.allreduce(len(X), op=MPI.SUM), 1)
    Y = X - centre
    vecs = [A.createVecLeft() for _ in range(6)]
    for k in range(3):
        a = vecs[k].getArray()
        a[k::3] = 1.0
    for v, (i, j) in zip(vecs[3:], [(0, 1), (1, 2), (2, 0)]):
        a = v.getArray()
        a[i::3], a[j::3] = -Y[:, j], Y[:, i]
    basis = []
    for v in vecs:  # Gram–Schmidt (the PETSc nullspace must be orthonormal)
        for q in basis:
            v.axpy(-v.dot(q), q)
        v.normalize()
        basis.append(v)
    return PETSc.NullSpace().create(vectors=basis, comm=A.getComm())


def make_snes(problem, comm, solver, prefix="hc_", deformable=False, symmetric=False):
    """A newtonls SNES with MUMPS by default (``symmetric``: the tangent is, see
    Model.symmetric_tangent); solver["petsc"] options
    (without prefix) override anything. Line search "auto": full Newton steps
    ("basic"), except with deformable–deformable contact (``deformable``), where
    a changing active set on a curved master makes full steps cycle (measured
    on Hertz: a period-3 cycle) and the backtracking "bt" converges. With rigid
    obstacles and friction full steps are the robust choice: on the paper's
    punch, bt crawls at steps of 0.1 of the Newton correction through the
    kinks of the Coulomb cone (|R| falling by 0.9 per iteration), cuts the
    load step back and can end on another of the frictional equilibria
    (bench/results/robustness.md)."""
    snes = PETSc.SNES().create(comm)
    snes.setOptionsPrefix(prefix)
    defaults = {
        "snes_type": "newtonls",
        "snes_linesearch_type": (("bt" if deformable else "basic") if solver["linesearch"] == "auto"
                                 else solver["linesearch"]),
    }
    problem.linear_kind, linear = linear_solver_options(solver, problem.A.getSize()[0], symmetric, deformable,
                                                        amg=problem.near_nullspace is not None)
    defaults.update(linear)
    set_prefixed_options(prefix, {**defaults, **solver["petsc"]})
    snes.setFunction(problem.residual, problem.b)
    snes.setJacobian(problem.jacobian, problem.A)
    snes.setTolerances(rtol=solver["rtol"], atol=solver["atol"], stol=0.0, max_it=solver["max_it"])
    snes.setFromOptions()
    snes.getKSP().setFromOptions()
    return snes


def set_line_search(snes, kind):
    """Make ``kind`` the SNES's line search (through its options: petsc4py
    3.18 has no line-search object); returns the one it had."""
    previous = line_search_of(snes)
    PETSc.Options()[(snes.getOptionsPrefix() or "") + "snes_linesearch_type"] = kind
    snes.setFromOptions()
    return previous


def line_search_of(snes):
    """The line search the SNES solves with (its options value, see set_line_search)."""
    key = (snes.getOptionsPrefix() or "") + "snes_linesearch_type"
    return PETSc.Options().getString(key, "bt")


def converged_reason_name(reason):
    names = {v: k for k, v in PETSc.SNES.ConvergedReason.__dict__.items() if isinstance(v, int)}
    return names.get(reason, str(reason))


def residual_norms_of(snes):
    """Residual norm history of the last solve."""
    hist = snes.getConvergenceHistory()
    norms = hist[0] if isinstance(hist, tuple) else hist
    return np.asarray(norms).tolist()


#: reason of a solve ended by StallTest
STALLED = "STALLED"


class StallTest:
    """A SNES convergence test: PETSc's default (SNESConvergedDefault, PETSc
    3.18: relative and absolute residual tolerances, NaN, function-evaluation
    count, divergence tolerance; the iteration limit is SNES's own) and two
    more stops, both reported as stalled:

    - a crawl (``window`` > 0): ``window`` consecutive iterations each lowered
      |R| by less than the fraction ``min_decrease``. A backtracking line
      search that follows a full step into the inverted elements at a rigid
      corner crawls so (|R| 2.50, 2.50, 2.50, 2.49 … on the 706k punch:
      0.03–0.6 % per iteration of 17 s) until max_it, when a cut-back would
      have converged. Only for the line-search fallback: a full-step solve
      may be slow for an iteration or two while the active set settles;
    - a cycle (``cycle_window`` > 0): ``cycle_window`` iterations without a
      new smallest |R| (by the fraction ``min_decrease``), and |R| back
      within that fraction of its value two or three iterations before. The
      706k frictional punch's full steps fell to 0.003 and then alternated
      0.019, 0.004, 0.019, … for 20 iterations to max_it.

    With neither stop (``window = cycle_window = 0``) it is the default test,
    and either way ``reference`` (set before a solve; 0: none) is the |R_0|
    the relative and divergence tolerances measure against when it is larger
    than the solve's own first |R|: a solve that starts from a prediction
    (steps.predictor) close to the solution stops where the same solve from
    the last converged state would have stopped, not at rtol × a |R_0| that
    may be below round-off."""

    def __init__(self, snes, min_decrease, window=2, cycle_window=0):
        self.reference = 0.0
        #: called as forcing(|R|, target) before every linear solve of the Newton solve (None: no call)
        self.forcing = None
        #: the solve's InversionDamping (None: none); with min_decrease > 0, two damped corrections in a
        #: row that each lowered |R| by less than that fraction stop the solve as stalled, whatever
        #: the line search: halving towards admissible states that do not approach equilibrium is a
        #: crawl too (the one-cell block squeezed 70 % in one step with the sharp law: damped every
        #: iteration, |R| 2.6e3, 2.1e3, 1.0e3, 1.0e3, 1.1e3, … for 25 iterations)
        self.damping = None
        self.min_decrease, self.window, self.cycle_window = float(min_decrease), int(window), int(cycle_window)
        self.rtol, self.atol = snes.getTolerances()[:2]
        self.max_funcs = snes.getMaxFunctionEvaluations()
        self.divtol = PETSc.Options().getReal((snes.getOptionsPrefix() or "") + "snes_divergence_tolerance", 1e4)
        self.reset()

    def reset(self):
        self.norms, self.stalled, self.ttol, self.rnorm0 = [], False, 0.0, 0.0
        self.best, self.since_best = np.inf, 0
        self.damped, self._damped_seen = [], 0  # per iterate: whether the correction that led to it was halved

    def __call__(self, snes, it, norms):
        xnorm, ynorm, fnorm = norms  # (how petsc4py passes them)
        R = PETSc.SNES.ConvergedReason
        if it == 0:
            self.reset()
            self.rnorm0 = max(fnorm, self.reference)
            self.ttol = self.rnorm0 * self.rtol
        halvings = len(self.damping.halvings) if self.damping is not None else 0
        self.damped.append(it > 0 and halvings > self._damped_seen)
        self._damped_seen = halvings
        self.norms.append(fnorm)
        if fnorm < (1.0 - self.min_decrease) * self.best or it == 0:
            self.best, self.since_best = fnorm, 0
        else:
            self.since_best += 1
        if not np.isfinite(fnorm):
            return R.DIVERGED_FNORM_NAN
        if fnorm < self.atol:
            return R.CONVERGED_FNORM_ABS
        if 0 <= self.max_funcs <= snes.getFunctionEvaluations():
            return R.DIVERGED_FUNCTION_COUNT
        if it == 0:
            return self._iterating(fnorm)
        if fnorm <= self.ttol:
            return R.CONVERGED_FNORM_RELATIVE
        if self.divtol > 0 and fnorm > self.divtol * self.rnorm0:
            return R.DIVERGED_DTOL
        recent = self.norms[-self.window - 1:]
        crawl = self.window > 0 and len(recent) == self.window + 1 and all(
            b > (1.0 - self.min_decrease) * a for a, b in zip(recent, recent[1:]))
        damped_crawl = self.min_decrease > 0 and len(self.norms) >= 3 and all(self.damped[-2:]) and all(
            b > (1.0 - self.min_decrease) * a for a, b in zip(self.norms[-3:], self.norms[-2:]))
        # a cycle revisits: |R| within the fraction of its value two or three iterations back (a period-2
        # or -3 cycle; a steady recovery from an overshoot, e.g. 80, 4e4, 1.1e4, 3.3e3, 957, does not)
        cycle = 0 < self.cycle_window <= self.since_best and any(
            abs(fnorm - self.norms[-1 - p]) <= self.min_decrease * self.norms[-1 - p]
            for p in (2, 3) if len(self.norms) > p)
        if crawl or cycle or damped_crawl:
            self.stalled = True
            return R.DIVERGED_MAX_IT
        return self._iterating(fnorm)

    def _iterating(self, fnorm):
        """Newton goes on: the linear solve that follows is told |R| and the target."""
        if self.forcing is not None:
            self.forcing(fnorm, max(self.ttol, self.atol))
        return PETSc.SNES.ConvergedReason.CONVERGED_ITERATING
