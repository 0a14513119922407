"""Inverted elements: the smallest J = det F over the volume quadrature
points, and where it is."""
import numpy as np
import ufl
from mpi4py import MPI

from .. import _dolfinx as dfx

#: reason of a solve SNES called converged with det F ≤ 0 at a volume quadrature point
INVERTED_ELEMENT = "INVERTED_ELEMENT"


class InversionCheck:
    """The smallest J = det F over the volume quadrature points of every
    cell (all ranks), at the displacement u: None if it is > 0, else where.
    The kernel is compiled at the first call (FFCx JIT)."""

    def __init__(self, u, quadrature_degree):
        self.u, self.degree = u, quadrature_degree
        self.mesh, self.comm = u.function_space.mesh, u.function_space.mesh.comm
        self.expression = None

    def __call__(self):
        """None, or {"cell": input index, "centroid": reference midpoint,
        "min_J": J} of the cell with the smallest J ≤ 0 (of cells whose J
        ties to 1e-9, the lowest input index: the same cell whatever the
        rounding or the number of ranks). Collective; non-finite values (a
        NaN iterate) are left out."""
        if self.expression is None:
            F = ufl.Identity(3) + ufl.grad(self.u)
            self.expression = dfx.fem.Expression(ufl.det(F), dfx.quadrature_points(self.mesh, self.degree))
        J = dfx.eval_on_owned_cells(self.expression, self.mesh)
        per_cell = np.where(np.isfinite(J), J, np.inf).min(axis=1)
        min_J = self.comm.allreduce(float(per_cell.min()) if len(per_cell) else np.inf, op=MPI.MIN)
        if not min_J <= 0.0:
            return None
        cells = np.flatnonzero(per_cell <= min_J + 1e-9 * abs(min_J))
        index = {int(dfx.cell_description(self.mesh, c)[0]): int(c) for c in cells}
        first, owner = self.comm.allreduce((min(index, default=np.iinfo(np.int64).max), self.comm.rank), op=MPI.MINLOC)
        cell = index.get(first)
        where = (dfx.cell_description(self.mesh, cell)[1], float(per_cell[cell])) if self.comm.rank == owner else None
        centroid, J_cell = self.comm.bcast(where, root=owner)
        return {"cell": first, "centroid": [float(v) for v in centroid], "min_J": J_cell}


def describe_inverted(element):
    """'inverted element: cell N at (x, y, z), min J = j' of InversionCheck's answer."""
    x = ", ".join(f"{v:.4g}" for v in element["centroid"])
    return f"inverted element: cell {element['cell']} at ({x}), min J = {element['min_J']:.3g}"


class InversionDamping:
    """A line-search pre-check for SNES: a Newton correction whose full step
    would leave J = det F ≤ 0 at a volume quadrature point is halved until
    it does not (at most ``max_halvings`` times; if every trial inverts, the
    correction is left as it was and the solve fails as before).

    Why: a hyperelastic residual is not a number where J ≤ 0 (J^(-2/3) in
    the Mooney law), so such a full step fails the whole Newton solve
    (DIVERGED_FNORM_NAN), the backtracking fallback then crawls from the
    same start, and the load step is cut back. On the punch that happens
    once the punch's motion in a step exceeds the cells at its edge (a grown
    step of 0.45 mm over cells of 0.36 mm at 1.1M unknowns). Halving only
    until the trial is admissible keeps full Newton steps everywhere else.
    Measured (docs/performance.md §2), it removes the NaN but not always
    the failure: the damped solve can wander while the contact active set
    at the punch edge settles, so solver.damp_inversion is off by default.

    ``w``: the unknown; ``u``: its displacement (w itself, or a collapsed
    copy whose values are w's at ``u_dofs``)."""

    def __init__(self, w, u, u_dofs, quadrature_degree, max_halvings=10):
        self.trial_w = dfx.fem.Function(w.function_space)
        self.u_dofs = u_dofs
        self.trial_u = self.trial_w if u_dofs is None else dfx.fem.Function(u.function_space)
        self.check = InversionCheck(self.trial_u, quadrature_degree)
        self.max_halvings = int(max_halvings)
        self.halvings = []  # per halved correction, how many halvings it took

    def admissible(self, x, y, alpha):
        """Whether x − alpha·y has J > 0 at every volume quadrature point (collective)."""
        x.copy(self.trial_w.vector)
        self.trial_w.vector.axpy(-alpha, y)
        dfx.update_ghosts(self.trial_w)
        if self.u_dofs is not None:
            self.trial_u.x.array[:] = self.trial_w.x.array[self.u_dofs]
        return self.check() is None

    def __call__(self, x, y):
        """SNES's pre-check (x: the iterate, y: the correction, x − y the full
        step): scales y in place; True if it did."""
        for k in range(self.max_halvings + 1):
            if self.admissible(x, y, 0.5 ** k):
                if k:
                    y.scale(0.5 ** k)
                    self.halvings.append(k)
                return k > 0
        return False
