"""Probes: the displacement at the mesh node at a named point."""
import numpy as np
from mpi4py import MPI

from .. import _dolfinx as dfx
from ..scene import SceneError


class Probe:
    """Displacement at the mesh node at a given point (owned by one rank)."""

    def __init__(self, name, point, V, tol):
        comm = V.mesh.comm
        X = dfx.node_coordinates(V)[: dfx.num_owned_nodes(V)]
        d = np.linalg.norm(X - np.asarray(point), axis=1) if len(X) else np.array([np.inf])
        i = int(np.argmin(d))
        best = comm.allreduce((float(d[i]), comm.rank), op=MPI.MINLOC)
        if best[0] > tol:
            raise SceneError(f"scene key 'output.probes.{name}': no mesh node at {point} "
                             f"(nearest is {best[0]:.3g} away)")
        self.comm, self.owner, self.node = comm, best[1], i

    def value(self, u):
        local = u.x.array.reshape(-1, 3)[self.node] if self.comm.rank == self.owner else np.zeros(3)
        return self.comm.allreduce(np.asarray(local), op=MPI.SUM)
