"""Load paths in phases through the Python API (scene keys cannot express
them yet): each phase moves the [[bc]] prescribed displacements and the rigid
obstacles linearly from where the previous phase left them to new end values
as λ goes 0 → 1, continuing from the previous phase's solution and contact
history."""
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


def move_obstacle(contact, motion):
    """Start a phase of a rigid obstacle: its position at the end of the last
    phase (λ = its current load factor) becomes its rest position and it moves
    by ``motion`` over the new phase. Friction history (ξ carried with the
    obstacle) stays consistent: ξ was committed at the old position."""
    spec = contact.spec
    shift = contact.load_factor * np.asarray(spec["motion"], dtype=float)
    for key in ("point", "lo", "hi"):
        spec[key] = [float(v) for v in np.asarray(spec[key], dtype=float) + shift]
    spec["motion"] = [float(v) for v in motion]
    if hasattr(contact, "motion"):
        contact.motion = np.asarray(motion, dtype=float)
        contact.lam_committed = 0.0
    contact.set_load_factor(0.0)


def run_phase(sim, motions, out_dir, obstacle_motions=None):
    """One phase: bc entry i (a key of ``motions``) ends at displacement
    motions[i] = [ux, uy, uz] (only its fixed components are used); other
    entries stay where they are. Rigid contact j (a key of
    ``obstacle_motions``) moves by obstacle_motions[j] over the phase, from
    where it is (others keep moving by their scene motion per phase).
    Returns the results writer of the phase."""
    for j, motion in (obstacle_motions or {}).items():
        c = sim.contacts[j]
        if c.spec["obstacle"] not in ("plane", "box", "cylinder"):
            raise ValueError(f"obstacle_motions[{j}]: contact {c.name!r} is not a rigid obstacle")
        move_obstacle(c, motion)
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
