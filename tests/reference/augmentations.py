"""Run a simulation recording the number of augmented-Lagrangian (Uzawa)
updates of every converged or failed load step."""


def run_counting_augmentations(sim, out_dir):
    """sim.run(out_dir=out_dir): returns (writer, augmentations of each
    converged step and failed attempt, from the results)."""
    writer = sim.run(out_dir=str(out_dir))
    return writer, [s["augmentations"] for s in writer.steps + writer.failed_attempts]
