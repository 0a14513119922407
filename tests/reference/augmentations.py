"""Run a simulation recording the number of augmented-Lagrangian (Uzawa)
updates of every converged or failed load step."""


def run_counting_augmentations(sim, out_dir):
    """sim.run(out_dir=out_dir) with Simulation._augment wrapped: returns
    (writer, augmentations per call)."""
    augmentations = []
    solve = sim._augment

    def counting(*args):
        result = solve(*args)
        augmentations.append(sim.augmentations)
        return result

    sim._augment = counting
    return sim.run(out_dir=str(out_dir)), augmentations
