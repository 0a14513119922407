"""Load paths in phases through the Python API (scene keys cannot express
them yet): each phase moves the [[bc]] prescribed displacements and the rigid
obstacles linearly from where the previous phase left them to new end values
as λ goes 0 → 1, continuing from the previous phase's solution and contact
history."""
from .model.loading import AXIS


def run_phase(sim, motions, out_dir, obstacle_motions=None):
    """One phase: bc entry i (a key of ``motions``) ends at displacement
    motions[i] = [ux, uy, uz] (only its fixed components are used); other
    entries stay where they are. Rigid contact j (a key of
    ``obstacle_motions``) moves by obstacle_motions[j] over the phase, from
    where it is (others keep moving by their scene motion per phase; the
    friction history, committed where the obstacle is, stays consistent).
    Returns the results writer of the phase."""
    model = sim.model
    for j, motion in (obstacle_motions or {}).items():
        c = model.contacts[j]
        if c.deformable:
            raise ValueError(f"obstacle_motions[{j}]: contact {c.name!r} is not a rigid obstacle")
        c.geometry.move(motion)
        if c.frictional:
            c.law.history.rebase()
    constraints = model.constraints
    constraints.start_phase({(i, a): float(motions[i][AXIS[a]]) for (i, a) in constraints.values if i in motions})
    return sim.run(out_dir=str(out_dir))
