"""Load paths in phases through the Python API (scene keys cannot express
them yet): each phase moves the [[bc]] prescribed displacements linearly
from where the previous phase left them to new end values as λ goes 0 → 1,
continuing from the previous phase's solution and contact history."""
import numpy as np

from .simulation import AXIS, Simulation


def bc_constants(sim):
    """{(bc entry index, axis letter): the dolfinx Constant of its value}."""
    out, k = {}, 0
    for i, bc in enumerate(sim.scene["bc"]):
        for a in bc["fix"]:
            out[(i, a)] = sim.bcs[k].value
            k += 1
    return out


def run_phase(sim, motions, out_dir):
    """One phase: bc entry i (a key of ``motions``) ends at displacement
    motions[i] = [ux, uy, uz] (only its fixed components are used); other
    entries stay where they are. Returns the results writer of the phase."""
    consts = bc_constants(sim)
    start = {key: float(c.value) for key, c in consts.items()}
    end = {(i, a): (float(motions[i][AXIS[a]]) if i in motions else start[(i, a)]) for (i, a) in consts}

    def set_load_factor(lam):
        Simulation.set_load_factor(sim, lam)
        for key, c in consts.items():
            np.copyto(c.value, start[key] + lam * (end[key] - start[key]))  # the C++ Constant: in place

    sim.set_load_factor = set_load_factor
    try:
        return sim.run(out_dir=str(out_dir))
    finally:
        del sim.set_load_factor
