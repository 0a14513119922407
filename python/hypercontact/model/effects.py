"""The effects a scene built, in words: the first line of a run and the
``effects`` of summary.json."""
from ..solve.newton import linear_solver_options

CONTROL = {"load": "load control", "arclength": "arc-length continuation", "displacement": "displacement control"}


def _mu(scene, path, j):
    """The friction coefficient of contact j in words: '0.3', or along the
    phases '0 → 1' (the value at the start and at the end of each phase)."""
    mu = [scene["contact"][j]["mu"]]
    if path is not None and not path.implicit:
        for k in range(len(path.phases)):
            v = path.values(k, 1.0)[("mu", j)]
            if v != mu[-1]:
                mu.append(v)
    return " → ".join(f"{m:g}" for m in mu)


def describe_effects(scene, material, settings, num_moving, num_unknowns, symmetric=False, path=None,
                     elements=None, gauss_rigid=0, facet_rigid=0):
    """[material, elements (unless trilinear hexahedra), contacts, automatic
    penalties, loads, control, linear solver]; ``path``: the scene's LoadPath
    (with phases: μ along them, and the phases in words); ``elements``: e.g.
    "10-node tetrahedra"; ``gauss_rigid``, ``facet_rigid``: rigid contacts on Gauss points, with
    a pressure per facet."""
    contacts = scene["contact"]
    n_rigid = sum(c["obstacle"] != "surface" for c in contacts)
    frictional = [j for j in range(len(contacts)) if (path.max_mu(j) if path is not None else contacts[j]["mu"]) > 0]
    mus = list(dict.fromkeys(_mu(scene, path, j) for j in frictional if contacts[j]["obstacle"] != "surface"))
    friction = f"Coulomb friction μ = {', '.join(mus)}" if mus else "frictionless"
    if gauss_rigid:
        friction += f", {'Gauss-point integration' if gauss_rigid == n_rigid else f'{gauss_rigid} on Gauss points'}"
    if facet_rigid:
        friction += f", {'a pressure per facet' if facet_rigid == n_rigid else f'{facet_rigid} with a pressure per facet'}"
    effects = [material] + ([elements] if elements not in (None, "8-node hexahedra") else [])
    effects.append(f"{n_rigid} rigid contact{'s' if n_rigid != 1 else ''} ({friction})" if n_rigid
                   else "no rigid contact" if contacts else "no contact")
    for j, c in enumerate(contacts):
        if c["obstacle"] == "surface":
            effects.append(f"contact {c['surface']} → {c['master']} ("
                           f"{'two-pass' if c['passes'] == 2 else 'single-pass'}, "
                           f"{'nodal' if c['integration'] == 'nodal' else 'Gauss-point'} integration, "
                           f"{'μ = ' + _mu(scene, path, j) if j in frictional else 'frictionless'})")
    notes = [s.penalty_note for s in settings if s.penalty_note]
    if notes:
        effects.append("automatic penalty (" + "; ".join(notes) + ")")
    for n, what in [(len(scene["pressure"]), "follower pressure"), (len(scene["traction"]), "traction"),
                    (len(scene["body_force"]), "body force"), (num_moving, "prescribed displacement")]:
        if n:
            effects.append(f"{n} {what}{'s' if n > 1 else ''}")
    if path is not None and not path.implicit:
        effects.append(f"{len(path.phases)} phase{'s' if len(path.phases) > 1 else ''} ("
                       + ", ".join(repr(p.name) for p in path.phases) + ")")
    controls = [ph.steps["control"] for ph in path.phases] if path is not None else [scene["steps"]["control"]]
    in_order = [c for i, c in enumerate(controls) if i == 0 or c != controls[i - 1]]
    effects.append(", then ".join(CONTROL[c] for c in in_order))
    if "load" in controls:
        kind, options = linear_solver_options(scene["solver"], num_unknowns, symmetric)
        pc = {**options, **scene["solver"]["petsc"]}.get("pc_type")  # the scene's PETSc options win
        direct = {"cholesky": "LDLᵀ, symmetric tangent", "lu": "LU"}.get(pc, pc)
        effects.append(f"direct linear solver (MUMPS {direct})" if kind == "direct" else
                       "iterative linear solver (GMRES + GAMG, rigid-body near-nullspace)")
    return effects
