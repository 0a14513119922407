"""The patch test's measure, written with UFL independently of the code under
test: the spread of the Cauchy stress σ_zz over the cells."""
import ufl
from dolfinx import fem
from mpi4py import MPI

from hypercontact import _dolfinx as dfx


def sigma_zz_spread(sim):
    """(max − min)/|mean| of the Cauchy stress σ_zz over all cells (midpoint)."""
    Q = fem.FunctionSpace(sim.body.mesh, ("DG", 0))
    s = fem.Function(Q)
    F = ufl.Identity(3) + ufl.grad(sim.u)
    sigma = sim.stress(sim.u) * F.T / ufl.det(F)
    s.interpolate(fem.Expression(sigma[2, 2], Q.element.interpolation_points()))
    comm = sim.comm
    n = dfx.num_owned_cells(sim.body.mesh)
    v = s.x.array[:n]
    lo, hi = comm.allreduce(v.min(), op=MPI.MIN), comm.allreduce(v.max(), op=MPI.MAX)
    mean = comm.allreduce(v.sum(), op=MPI.SUM) / comm.allreduce(len(v), op=MPI.SUM)
    return (hi - lo) / abs(mean)
