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
