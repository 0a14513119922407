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


def constrained_dofs(sim):
    """Mask of the Dirichlet-constrained process-local dofs of a Simulation's unknown."""
    from hypercontact import _dolfinx as dfx

    constrained = np.zeros(sim.w.x.array.size, bool)
    for bc in sim.bcs:
        constrained[dfx.bc_dofs(bc)] = True
    return constrained


def simulation_jacobian_error(sim, constrained):
    """max |J − J_fd| over the free dofs and max |J|, of the Simulation's
    Problem at its current unknown (and the dense J, J_fd)."""
    p = sim.problem
    x = p.x
    sim.w.vector.copy(x)
    free = np.flatnonzero(~constrained)
    J, J_fd = assembled_and_fd_jacobians(p, x, free)
    err = np.abs(J - J_fd)[np.ix_(free, free)]
    return err.max(), np.abs(J).max(), J, free
