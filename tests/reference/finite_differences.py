"""The assembled Newton matrix of a Problem against central differences of
its assembled residual (the whole system: volume, contact, Dirichlet rows)."""
import numpy as np


def assembled_and_fd_jacobians(problem, x, free, h=1e-7):
    """(J, J_fd) as dense arrays at x; J_fd's columns only for the ``free``
    dofs (perturbing a Dirichlet dof would also move the lifting term)."""
    b = problem.b.duplicate()
    problem.residual(None, x, b)
    problem.jacobian(None, x, problem.A, problem.A)
    # convert() without a target converts in place: keep the solver's sparse matrix as it is
    J = problem.A.copy().convert("dense").getDenseArray().copy()
    J_fd = np.zeros_like(J)
    bp, bm = b.duplicate(), b.duplicate()
    for j in free:
        xp = x.copy()
        xp.array[j] += h
        problem.residual(None, xp, bp)
        xm = x.copy()
        xm.array[j] -= h
        problem.residual(None, xm, bm)
        J_fd[:, j] = (bp.array - bm.array) / (2 * h)
    return J, J_fd
