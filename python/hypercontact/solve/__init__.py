"""Solving a model: the Newton problem (:mod:`.newton`), one Newton solve
(:mod:`.newton_solver`), the pure load-step controller (:mod:`.step_control`),
load stepping (:mod:`.load_stepping`), the augmented Lagrangian
(:mod:`.augmented`), continuation (:mod:`.continuation`,
:mod:`.path_following`) and the run loop with its observers (:mod:`.run`)."""
