"""Running a scene given as a dict inside a test, and reading its results."""
import numpy as np
from mpi4py import MPI

from hypercontact import scene
from hypercontact.simulation import Simulation


def run(data, out, comm=MPI.COMM_SELF):
    """(simulation, results writer) of the scene ``data`` run into ``out``, quietly."""
    sim = Simulation(scene.load(data, [f"output.dir={out}"]), comm, log=lambda *a, **k: None)
    return sim, sim.run()


def column(writer, key):
    """One column of curves.csv over the converged steps, as an array."""
    return np.array([s[key] for s in writer.steps])
