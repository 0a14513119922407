"""The effects a scene built, in words: the first line of a run and the
``effects`` of summary.json."""
from ..solve.newton import linear_solver_options

CONTROL = {"load": "load control", "arclength": "arc-length continuation", "displacement": "displacement control"}


def describe_effects(scene, material, settings, num_moving, num_unknowns, symmetric=False):
    """[material, contacts, automatic penalties, loads, control, linear solver]."""
    contacts = scene["contact"]
    n_rigid = sum(c["obstacle"] != "surface" for c in contacts)
    mus = sorted({c["mu"] for c in contacts if c["mu"] > 0})
    friction = f"Coulomb friction μ = {', '.join(f'{m:g}' for m in mus)}" if mus else "frictionless"
    effects = [material, (f"{n_rigid} rigid contact{'s' if n_rigid != 1 else ''} ({friction})" if n_rigid
                          else "no rigid contact" if contacts else "no contact")]
    for c in contacts:
        if c["obstacle"] == "surface":
            effects.append(f"contact {c['surface']} → {c['master']} ("
                           f"{'two-pass' if c['passes'] == 2 else 'single-pass'}, "
                           f"{'nodal' if c['integration'] == 'nodal' else 'Gauss-point'} integration, "
                           f"{'frictionless' if c['mu'] == 0 else 'μ = %g' % c['mu']})")
    notes = [s.penalty_note for s in settings if s.penalty_note]
    if notes:
        effects.append("automatic penalty (" + "; ".join(notes) + ")")
    for n, what in [(len(scene["pressure"]), "follower pressure"), (len(scene["traction"]), "traction"),
                    (len(scene["body_force"]), "body force"), (num_moving, "prescribed displacement")]:
        if n:
            effects.append(f"{n} {what}{'s' if n > 1 else ''}")
    effects.append(CONTROL[scene["steps"]["control"]])
    if scene["steps"]["control"] == "load":
        kind, options = linear_solver_options(scene["solver"], num_unknowns, symmetric)
        pc = {**options, **scene["solver"]["petsc"]}.get("pc_type")  # the scene's PETSc options win
        direct = {"cholesky": "LDLᵀ, symmetric tangent", "lu": "LU"}.get(pc, pc)
        effects.append(f"direct linear solver (MUMPS {direct})" if kind == "direct" else
                       "iterative linear solver (GMRES + GAMG, rigid-body near-nullspace)")
    return effects
