"""Phases from the Python API, one at a time (a scene's [[phase]] tables
run them all: :mod:`hypercontact.scene.phases`): each call appends a phase
to the model's load path that moves the [[bc]] prescribed displacements and
the rigid obstacles linearly from where the previous phase left them, and
runs it, continuing from the previous phase's solution and contact history."""
import numpy as np

from .scene.path import AXIS


def run_phase(sim, motions, out_dir, obstacle_motions=None):
    """One phase: bc entry i (a key of ``motions``) ends at displacement
    motions[i] = [ux, uy, uz] (only its fixed components are used); other
    entries stay where they are. Rigid contact j (a key of
    ``obstacle_motions``) moves by obstacle_motions[j] over the phase, from
    where it is; the others stay. Returns the results writer of the phase."""
    model = sim.model
    path = model.path
    now = path.values(model.phase, float(model.load_factor.value))
    ends = {("bc", i, a): float(motions[i][AXIS[a]]) for (i, a) in model.constraints.values if i in motions}
    for j, motion in (obstacle_motions or {}).items():
        c = model.contacts[j]
        if c.deformable:
            raise ValueError(f"obstacle_motions[{j}]: contact {c.name!r} is not a rigid obstacle")
        key = ("motion", c.index)
        ends[key] = (np.asarray(now[key]) + np.asarray(motion, dtype=float)).tolist()
    k = path.append_phase(f"phase {len(path.phases) + 1}", now, ends)
    return sim.runner(str(out_dir), phases=[k])
