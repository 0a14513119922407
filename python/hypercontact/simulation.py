"""A scene → a running simulation: build only the effects the scene names,
then solve by incremental loading with automatic step control."""
import importlib.util
import inspect
import time
from pathlib import Path

import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc

from . import _dolfinx as dfx
from . import geometry
from .checkpoint import Checkpoint
from .contact import RigidContact
from .friction import FrictionalRigidContact
from .surface_contact import SurfaceContact
from .surface_friction import FrictionalSurfaceContact
from .continuation import ArcLengthConstraint, Bordered, ContinuationFailure, DisplacementConstraint
from .continuation import step as continuation_step
from . import penalty
from .forms import loads, materials, volume
from .problem import (Problem, converged_reason_name, linear_solver_options, make_snes, residual_norms_of,
                      set_line_search)
from .results import ResultsWriter, first_piola_stress
from .scene import SceneError
from .timing import Timers

AXIS = {"x": 0, "y": 1, "z": 2}
#: contacts with a friction history (checkpointed: xi, t_old, lam_committed, dissipation, history_arrays)
FRICTIONAL = (FrictionalRigidContact, FrictionalSurfaceContact)


class StepFailure(RuntimeError):
    """A load step did not converge after the allowed cut-backs."""


#: reason of an attempt made to fail by Simulation(fail_attempt=...)
FORCED_FAILURE = "FORCED_FAILURE"
#: reason of a solve SNES called converged with det F ≤ 0 at a volume quadrature point
INVERTED_ELEMENT = "INVERTED_ELEMENT"
#: slave points listed per kind of flip in a failed attempt's story
TOP_FLIPPERS = 5


class InversionCheck:
    """The smallest J = det F over the volume quadrature points of every
    cell (all ranks), at the displacement u: None if it is > 0, else where.
    The kernel is compiled at the first call (FFCx JIT)."""

    def __init__(self, u, quadrature_degree):
        self.u, self.degree = u, quadrature_degree
        self.mesh, self.comm = u.function_space.mesh, u.function_space.mesh.comm
        self.expression = None

    def __call__(self):
        """None, or {"cell": input index, "centroid": reference midpoint,
        "min_J": J} of the cell with the smallest J ≤ 0 (of cells whose J
        ties to 1e-9, the lowest input index: the same cell whatever the
        rounding or the number of ranks). Collective; non-finite values (a
        NaN iterate) are left out."""
        if self.expression is None:
            F = ufl.Identity(3) + ufl.grad(self.u)
            self.expression = dfx.fem.Expression(ufl.det(F), dfx.quadrature_points(self.mesh, self.degree))
        J = dfx.eval_on_owned_cells(self.expression, self.mesh)
        per_cell = np.where(np.isfinite(J), J, np.inf).min(axis=1)
        min_J = self.comm.allreduce(float(per_cell.min()) if len(per_cell) else np.inf, op=MPI.MIN)
        if not min_J <= 0.0:
            return None
        cells = np.flatnonzero(per_cell <= min_J + 1e-9 * abs(min_J))
        index = {int(dfx.cell_description(self.mesh, c)[0]): int(c) for c in cells}
        first, owner = self.comm.allreduce((min(index, default=np.iinfo(np.int64).max), self.comm.rank), op=MPI.MINLOC)
        cell = index.get(first)
        where = (dfx.cell_description(self.mesh, cell)[1], float(per_cell[cell])) if self.comm.rank == owner else None
        centroid, J_cell = self.comm.bcast(where, root=owner)
        return {"cell": first, "centroid": [float(v) for v in centroid], "min_J": J_cell}


def describe_inverted(element):
    """'inverted element: cell N at (x, y, z), min J = j' of InversionCheck's answer."""
    x = ", ".join(f"{v:.4g}" for v in element["centroid"])
    return f"inverted element: cell {element['cell']} at ({x}), min J = {element['min_J']:.3g}"


def flip_story(contacts, histories, u, comm, top=TOP_FLIPPERS):
    """What the slave points did during one Newton solve, from their status
    at each iterate (``histories[k][i]``: contact i's point_status() at
    iterate k; 0 open, 1 stick, 2 slip or closed without friction): per
    iteration the number of points (all ranks) that changed open ↔ closed
    and stick ↔ slip, and the ``top`` points that did so most often, with
    their reference and current coordinates. Collective."""
    per_iteration = np.zeros((2, max(len(histories) - 1, 0)), dtype=np.int64)
    found = {"open_closed": [], "stick_slip": []}
    for i, c in enumerate(contacts):
        s = np.array([h[i] for h in histories]) if len(histories) > 1 else np.zeros((1, 0), np.int8)
        before, after = s[:-1], s[1:]
        flips = {"open_closed": (before > 0) != (after > 0),
                 "stick_slip": (before > 0) & (after > 0) & (before != after)}
        per_iteration += np.array([f.sum(axis=1) for f in flips.values()], dtype=np.int64)
        reference, current = c.point_coordinates(u)  # collective for deformable masters
        for kind, f in flips.items():
            counts = f.sum(axis=0)
            found[kind] += [(int(counts[p]), c.name, reference[p].tolist(), current[p].tolist())
                            for p in np.argsort(-counts, kind="stable")[:top] if counts[p] > 0]
    comm.Allreduce(MPI.IN_PLACE, per_iteration, op=MPI.SUM)
    story = {"open_closed_flips_per_iteration": per_iteration[0].tolist(),
             "stick_slip_flips_per_iteration": per_iteration[1].tolist()}
    for kind, local in found.items():
        every = sorted((e for part in comm.allgather(local) for e in part), key=lambda e: (-e[0], e[1], e[2]))
        story[f"most_{kind}_flips"] = [{"contact": name, "flips": n, "point": point, "current": now}
                                       for n, name, point, now in every[:top]]
    return story


def load_user_law(spec):
    """'python:path/to/file.py:function' → the function ψ(F, **params)."""
    try:
        _, path, func = spec.split(":")
    except ValueError:
        raise SceneError(f"scene key 'material.law': expected a built-in law ({', '.join(materials.LAWS)}) "
                         f"or 'python:FILE.py:FUNCTION', found {spec!r}") from None
    if not Path(path).is_file():
        raise SceneError(f"scene key 'material.law': file '{path}' does not exist")
    module_spec = importlib.util.spec_from_file_location("user_law", path)
    module = importlib.util.module_from_spec(module_spec)
    try:
        module_spec.loader.exec_module(module)
    except Exception as err:
        raise SceneError(f"scene key 'material.law': '{path}' raised on import: {err!r}") from None
    if not callable(getattr(module, func, None)):
        raise SceneError(f"scene key 'material.law': '{path}' has no function '{func}'")
    return getattr(module, func)


def resolve_material(mat, law=None):
    """(psi, params, description) of the scene's material; ``law`` is a
    Python function ψ(F, **params) given by a driver script."""
    params = dict(mat["parameters"])
    name = mat["law"]
    if law is None and name in materials.LAWS:
        law, expected = materials.LAWS[name]
        for key, default in expected.items():
            if key not in params:
                if default is None:
                    raise SceneError(f"scene key 'material.parameters.{key}': missing (required by {name})")
                params[key] = default
        unknown = set(params) - set(expected)
        if unknown:
            raise SceneError(f"scene key 'material.parameters.{sorted(unknown)[0]}': unknown parameter "
                             f"of {name} (expected {', '.join(expected)})")
    elif law is None:
        law = load_user_law(name)
    else:  # a driver's law gets the scene parameters it names (the scene fills the built-in law's defaults)
        accepted = inspect.signature(law).parameters.values()
        if not any(a.kind == a.VAR_KEYWORD for a in accepted):
            params = {k: v for k, v in params.items() if k in {a.name for a in accepted}}
    # Evaluate once on a symbolic F so that a broken law fails here, clearly.
    try:
        cell = ufl.hexahedron
        F = ufl.variable(ufl.Identity(3) + ufl.grad(ufl.Coefficient(ufl.VectorElement("Lagrange", cell, 1))))
        psi = law(F, **params)
        if not isinstance(psi, ufl.core.expr.Expr) or psi.ufl_shape != ():
            raise TypeError(f"must return a scalar UFL expression, returned {type(psi).__name__}")
    except SceneError:
        raise
    except Exception as err:
        raise SceneError(f"material law '{name}' with parameters {params} raised: {err}") from None
    desc = name if name in materials.LAWS else f"user law {getattr(law, '__name__', name)}"
    if name == "mooney_rivlin":
        desc = f"Mooney–Rivlin ({params['i2']} I2)"
    if name in materials.LAWS and params.get("volumetric", "quadratic") != "quadratic":
        desc += f", volumetric {params['volumetric']}"
    return law, params, desc


class Probe:
    """Displacement at the mesh node at a given point (owned by one rank)."""

    def __init__(self, name, point, V, tol):
        comm = V.mesh.comm
        X = dfx.node_coordinates(V)[: dfx.num_owned_nodes(V)]
        d = np.linalg.norm(X - np.asarray(point), axis=1) if len(X) else np.array([np.inf])
        i = int(np.argmin(d))
        best = comm.allreduce((float(d[i]), comm.rank), op=MPI.MINLOC)
        if best[0] > tol:
            raise SceneError(f"scene key 'output.probes.{name}': no mesh node at {point} "
                             f"(nearest is {best[0]:.3g} away)")
        self.comm, self.owner, self.node = comm, best[1], i

    def value(self, u):
        local = u.x.array.reshape(-1, 3)[self.node] if self.comm.rank == self.owner else np.zeros(3)
        return self.comm.allreduce(np.asarray(local), op=MPI.SUM)


class Simulation:
    """Everything one scene needs, built once; :meth:`run` solves it."""

    def __init__(self, scene, comm=MPI.COMM_WORLD, law=None, log=None, fail_attempt=None):
        """``fail_attempt``: None, or a callable ``fail_attempt(step, lam,
        dlam, attempt) -> bool`` asked once per attempt at a load-control
        step, after its Newton solve(s): ``step`` is the number the step
        would get (1 for the first), ``lam`` the load factor it starts from,
        ``dlam`` the increment tried, ``attempt`` 0 for the first try and k
        after k cut-backs of this step. True makes a converged attempt fail
        as if SNES had diverged (reason FORCED_FAILURE): its state is
        discarded, its story goes to summary.json's ``failed_attempts`` and
        the step is cut back (or the run stops). For tests and what-if
        studies of the step control, independent of where rounding makes a
        solve fail; the answers of all ranks are or-ed."""
        self.scene, self.comm = scene, comm
        self.fail_attempt = fail_attempt
        self.log = log if log is not None else (print if comm.rank == 0 else (lambda *a, **k: None))
        self.timers = Timers()
        with self.timers("setup"):
            self._build(law)

    def _build(self, law):
        """Build exactly the effects the scene names, in the order they depend
        on each other: body, volume forms, constraints, loads, contacts."""
        sc = self.scene
        self.body = self._build_body(sc["mesh"])
        if sc["mesh"]["perturbation"] > 0:
            dfx.perturb_coordinates(self.body.mesh, sc["mesh"]["perturbation"])
        R, J, u_unknown, v_unknown, mat_desc, self.stress = self._build_volume(law)
        self.bcs, constrained = self._build_constraints()
        R, J = self._add_loads(R, J, u_unknown, v_unknown)
        self.contacts = []
        self.penalties = []
        for i, c in enumerate(sc["contact"]):
            slave = self._tag(c["surface"], f"contact[{i}].surface")
            if c["eps_n"] == 0:
                self._automatic_penalty(c, slave)
            if c["obstacle"] != "surface":
                kind = FrictionalRigidContact if c["mu"] > 0 else RigidContact
                self.contacts.append(kind(c, self.V, self.body.facet_tags, slave, constrained))
                if c["enforcement"] == "augmented_lagrangian" and c["gap_tolerance"] == 0:
                    # automatic: 1e-3 of the first element layer's thickness
                    c["gap_tolerance"] = 1e-3 * penalty.layer_thickness(self.V, self.body.facet_tags, slave)
                continue
            if sc["steps"]["control"] != "load":
                raise SceneError(f"scene key 'contact[{i}].obstacle': contact with a deformable surface needs "
                                 "steps.control = \"load\" (continuation with it is not supported yet)")
            master = [self._tag(m, f"contact[{i}].master") for m in c["master"].split("+")]
            kind = FrictionalSurfaceContact if c["mu"] > 0 else SurfaceContact  # μ > 0: single pass, nodal
            self.contacts.append(kind(c, self.V, self.body.facet_tags, [slave], master, constrained))
            if c["passes"] == 2:  # two-pass: each surface is slave once
                self.contacts.append(SurfaceContact(c, self.V, self.body.facet_tags, master, [slave], constrained,
                                                    name=f"{c['name']}_pass2"))
        size = self.comm.allreduce(np.ptp(self.body.mesh.geometry.x, axis=0).max(), op=MPI.MAX)
        self.probes = {name: Probe(name, p, self.V, 1e-6 * size) for name, p in sc["output"]["probes"].items()}
        self.problem = Problem(self.w, R, J, self.bcs, self.contacts, self.timers)
        self.inversion_check = InversionCheck(self.u, sc["discretisation"]["quadrature_degree"])
        self.inverted = None  # InversionCheck's answer at the end of the last solve
        self.last_snes_reason = None
        self.snes = None  # built by the load-control driver only
        self._fallback_linesearch = None  # the line search a failed solve is tried again with (solve_step)
        self.bordered = None  # built by the continuation driver only
        self._reset_iteration_history()
        n_rigid, n_p = sum(c["obstacle"] != "surface" for c in sc["contact"]), len(sc["pressure"])
        n_t, n_b, n_m = len(sc["traction"]), len(sc["body_force"]), len(self._bc_motion)
        mus = sorted({c["mu"] for c in sc["contact"] if c["mu"] > 0})
        friction = f"Coulomb friction μ = {', '.join(f'{m:g}' for m in mus)}" if mus else "frictionless"
        self.effects = [mat_desc, (f"{n_rigid} rigid contact{'s' if n_rigid != 1 else ''} ({friction})"
                                   if n_rigid else "no rigid contact")]
        for c in sc["contact"]:
            if c["obstacle"] == "surface":
                self.effects.append(f"contact {c['surface']} → {c['master']} ("
                                    f"{'two-pass' if c['passes'] == 2 else 'single-pass'}, "
                                    f"{'nodal' if c['integration'] == 'nodal' else 'Gauss-point'} integration, "
                                    f"{'frictionless' if c['mu'] == 0 else 'μ = %g' % c['mu']})")
        if not sc["contact"]:
            self.effects[1] = "no contact"
        if self.penalties:
            self.effects.append("automatic penalty (" + "; ".join(self.penalties) + ")")
        for n, what in [(n_p, "follower pressure"), (n_t, "traction"), (n_b, "body force"),
                        (n_m, "prescribed displacement")]:
            if n:
                self.effects.append(f"{n} {what}{'s' if n > 1 else ''}")
        self.effects.append({"load": "load control", "arclength": "arc-length continuation",
                             "displacement": "displacement control"}[sc["steps"]["control"]])
        if sc["steps"]["control"] == "load":
            kind, _ = linear_solver_options(sc["solver"], dfx.num_global_dofs(self.w.function_space))
            self.effects.append("direct linear solver (MUMPS LU)" if kind == "direct" else
                                "iterative linear solver (GMRES + GAMG, rigid-body near-nullspace)")
        self.linear_iterations = []  # Krylov iterations of each load step's Newton solve

    def _automatic_penalty(self, c, slave_tag):
        """ε_N = penalty_factor × M / h from the slave body's material (see
        penalty.py), written into the contact's scene entry."""
        prefix = c["surface"].split(".")[0] if "." in c["surface"] else None
        material = next((b["material"] for b in self.scene["body"] if b["name"] == prefix), self.scene["material"])
        eps, M, h = penalty.automatic_penalty(c["penalty_factor"], material["law"], material["parameters"],
                                              self.V, self.body.facet_tags, slave_tag)
        c["eps_n"] = eps
        self.penalties.append(f"{c['name']}: ε_N = {eps:.4g} = {c['penalty_factor']:g} × M {M:.4g} / h {h:.4g}")

    def _build_body(self, mesh):
        if self.scene["body"] or any(g != 1.0 for g in mesh["grading"]):
            names = ["body"] + [b["name"] for b in self.scene["body"]]
            if "body" in names[1:]:
                raise SceneError("scene key 'body': the name 'body' is taken by the [mesh] body")
            return geometry.build_bodies(self.comm, [("body", mesh)] + [(b["name"], b) for b in self.scene["body"]])
        if mesh["builder"] == "file":
            return geometry.read_msh(self.comm, mesh["file"])
        if mesh["builder"] == "shell_octant":
            from .shell import build_shell_octant

            return build_shell_octant(self.comm, mesh["inner_radius"], mesh["thickness"], mesh["n"], mesh["m"])
        return geometry.build_box(self.comm, mesh["size"], mesh["n"], mesh["m"], mesh["origin"])

    def _tag(self, surface, key):
        if surface not in self.body.surfaces:
            raise SceneError(f"scene key '{key}': the mesh has no surface {surface!r} "
                             f"(it has {', '.join(sorted(self.body.surfaces))})")
        return self.body.surfaces[surface]

    def _build_volume(self, law):
        """The unknown, the displacement view of it, and the volume forms of
        the chosen formulation: (R, J, u, v, description)."""
        sc, mesh = self.scene, self.body.mesh
        psi, params, desc = resolve_material(sc["material"], law)
        disc = sc["discretisation"]
        name = sc["material"]["law"]
        if disc["formulation"] != "displacement" and (law is not None or name not in materials.ISOCHORIC):
            raise SceneError(f"scene key 'discretisation.formulation': {disc['formulation']!r} needs a built-in "
                             f"law ({', '.join(materials.ISOCHORIC)}), found {name!r}")
        if np.isinf(params.get("K", 0.0)) and disc["formulation"] != "mixed":
            raise SceneError("scene key 'material.parameters.K': K = inf (incompressible) needs "
                             "discretisation.formulation = \"mixed\"")
        if sc["contact"] and (disc["degree"] != 1 or disc["formulation"] == "mixed"):
            raise SceneError("scene key 'discretisation': contact needs the displacement or sri "
                             "formulation with degree 1")
        iso_params, K, vol = materials.split_volumetric(params)
        qdeg = disc["quadrature_degree"]
        if disc["formulation"] == "mixed":
            if qdeg < 4:
                raise SceneError("scene key 'discretisation.quadrature_degree': the mixed formulation's "
                                 f"quadratic hexahedra need 3×3×3 Gauss points (degree >= 4), found {qdeg}: "
                                 "fewer leave zero-energy modes")
            # The unknown is w = (u, p); self.u is its displacement part, refreshed after each solve.
            self.w = dfx.fem.Function(dfx.taylor_hood_space(mesh), name="solution")
            self.V, self._u_dofs = dfx.collapse(self.w.function_space.sub(0))
            self.u = dfx.fem.Function(self.V, name="displacement")
            u, v = ufl.split(self.w)[0], ufl.split(ufl.TestFunction(self.w.function_space))[0]
            R, J = volume.mixed_up_forms(self.w, materials.ISOCHORIC[name], iso_params, K, qdeg, vol)
            p = ufl.split(self.w)[1]

            def stress(u_out):
                """P = ∂ψ_iso/∂F + p J G'(J) F⁻ᵀ with the pressure unknown p."""
                F = ufl.variable(ufl.Identity(3) + ufl.grad(u_out))
                P_iso = ufl.diff(materials.ISOCHORIC[name](F, **iso_params), F)
                return P_iso + volume.mixed_pressure_stress(F, p, K, vol)

            return R, J, u, v, desc + ", mixed u–p (Taylor–Hood Q2–Q1)", stress
        self.V = dfx.vector_space(mesh, disc["degree"])
        self.u = self.w = dfx.fem.Function(self.V, name="displacement")
        self._u_dofs = None
        if sc["body"]:
            return self._build_several_volumes(law, psi, params, desc)
        if disc["formulation"] == "sri":
            R, J = volume.selective_reduced_forms(self.u, materials.ISOCHORIC[name], iso_params, K, qdeg,
                                                  volumetric=vol)
            desc += ", selective reduced integration"
        else:
            R, J = volume.displacement_forms(self.u, psi, params, qdeg)
        return R, J, self.u, ufl.TestFunction(self.V), desc, first_piola_stress(psi, **params)

    def _build_several_volumes(self, law, psi, params, desc):
        """Volume forms summed over the bodies, each with its own law on its
        own cells; the stress for the results picked per cell by body."""
        sc = self.scene
        disc = sc["discretisation"]
        dx = ufl.Measure("dx", domain=self.body.mesh, subdomain_data=self.body.cell_tags)
        laws = [(law, psi, params, sc["material"]["law"], desc)]
        for b in sc["body"]:
            b_psi, b_params, b_desc = resolve_material(b["material"])
            laws.append((None, b_psi, b_params, b["material"]["law"], b_desc))
        R = J = None
        stresses = []
        DG0 = dfx.fem.FunctionSpace(self.body.mesh, ("DG", 0))
        for (user_law, b_psi, b_params, name, _), (region, tag) in zip(laws, self.body.regions.items()):
            if disc["formulation"] == "sri":
                iso, K, vol = materials.split_volumetric(b_params)
                Rb, Jb = volume.selective_reduced_forms(self.u, materials.ISOCHORIC[name], iso, K,
                                                        disc["quadrature_degree"], dx(tag), vol)
            else:
                Rb, Jb = volume.displacement_forms(self.u, b_psi, b_params, disc["quadrature_degree"], dx(tag))
            R, J = (Rb, Jb) if R is None else (R + Rb, J + Jb)
            chi = dfx.fem.Function(DG0)
            chi.x.array[:] = 0.0
            chi.x.array[self.body.cell_tags.indices[self.body.cell_tags.values == tag]] = 1.0
            chi.x.scatter_forward()
            stresses.append((chi, first_piola_stress(b_psi, **b_params)))

        def stress(u):
            return sum(chi * P(u) for chi, P in stresses)

        text = "; ".join(f"{region}: {d}" for (_, _, _, _, d), region in zip(laws, self.body.regions))
        if disc["formulation"] == "sri":
            text += ", selective reduced integration"
        return R, J, self.u, ufl.TestFunction(self.V), f"{len(laws)} bodies ({text})", stress

    def _build_constraints(self):
        """Dirichlet conditions u_a = λ × motion_a on the fixed components,
        and the mask of constrained local dofs."""
        W = self.w.function_space
        displacement_space = W.sub(0) if self._u_dofs is not None else W
        bcs, self._bc_motion = [], []
        for i, bc in enumerate(self.scene["bc"]):
            facets = dfx.facets_with_tag(self.body.facet_tags, self._tag(bc["surface"], f"bc[{i}].surface"))
            for a in bc["fix"]:
                value = dfx.constant(self.body.mesh, 0.0)
                bcs.append(dfx.dirichlet_component(displacement_space, AXIS[a], facets, value))
                if bc["motion"][AXIS[a]] != 0.0:
                    self._bc_motion.append((value, bc["motion"][AXIS[a]]))
        constrained = np.zeros(self.w.x.array.size, dtype=bool)
        for bc in bcs:
            constrained[dfx.bc_dofs(bc)] = True
        return bcs, constrained

    def _add_loads(self, R, J, u, v):
        """Loads proportional to λ: follower pressures, dead tractions and body
        forces; their residual terms, and q = ∂R/∂λ (kept for continuation)."""
        sc = self.scene
        self.load_factor = dfx.constant(self.body.mesh, 0.0)
        qdeg = sc["discretisation"]["quadrature_degree"]
        ds = dfx.facet_integration_measure(self.body.mesh, self.body.facet_tags, qdeg)
        terms = [loads.follower_pressure(u, v, pr["value"], ds(self._tag(pr["surface"], f"pressure[{i}].surface")))
                 for i, pr in enumerate(sc["pressure"])]
        terms += [loads.dead_load(v, tr["value"], ds(self._tag(tr["surface"], f"traction[{i}].surface")))
                  for i, tr in enumerate(sc["traction"])]
        dx = ufl.dx(domain=self.body.mesh, metadata={"quadrature_degree": qdeg})
        terms += [loads.dead_load(v, bf["value"], dx) for bf in sc["body_force"]]
        self.q_form = None
        for term in terms:
            self.q_form = term if self.q_form is None else self.q_form + term
        if self.q_form is None:
            return R, J
        dw = ufl.TrialFunction(self.w.function_space)
        return R + self.load_factor * self.q_form, J + self.load_factor * ufl.derivative(self.q_form, self.w, dw)

    def _reset_iteration_history(self):
        """Empty what _monitor collects per Newton iterate."""
        self.active_sets, self.stick_slip_sets, self.update_norms, self.point_states = [], [], [], []

    def _monitor(self, snes, its, norm):
        """Per Newton iteration: the norm of the Newton correction, the
        contact active set and stick/slip signatures of the current iterate,
        and each contact's per-point status (this rank's points: a failed
        attempt's story counts their flips)."""
        if its == 0:
            self._reset_iteration_history()
        else:
            self.update_norms.append(snes.getSolutionUpdate().norm())
        self.active_sets.append([c.active_set_signature() for c in self.contacts])
        self.stick_slip_sets.append([c.stick_slip_signature() for c in self.contacts if isinstance(c, FRICTIONAL)])
        self.point_states.append([c.point_status() for c in self.contacts])

    def _eta(self, progress):
        """'  ~N s left', extrapolating the time since this run (or resume)
        started over the fraction of the load path still to go."""
        if not 0 < progress < 1:
            return ""
        elapsed = time.perf_counter() - self._started
        done = progress - self._progress0
        return f"  ~{elapsed * (1 - progress) / done:.0f} s left" if done > 0 else ""

    def _save_checkpoint(self, writer, controller, **arrays):
        """The state after a converged step: solution, step controller, results so far."""
        with self.timers("output"):
            friction = {c.name: {"lam_committed": c.lam_committed, "dissipation": c.dissipation}
                        for c in self.contacts if isinstance(c, FRICTIONAL)}
            for c in self.contacts:
                if getattr(c, "augmented", False):
                    arrays[f"multipliers_{c.name}"] = c.multipliers_committed
                if isinstance(c, FRICTIONAL):
                    arrays[f"xi_{c.name}"], arrays[f"t_{c.name}"] = c.xi, c.t_old
                    arrays.update({f"{k}_{c.name}": v for k, v in c.history_arrays().items()})
            state = {**controller, "steps": writer.steps, "limit_points": writer.limit_points,
                     "failed_attempts": writer.failed_attempts, "friction": friction}
            self.checkpoint.save(state, w=self.w.x.array, **arrays)

    def sync_displacement(self):
        """self.u from the unknown (a no-op unless the formulation is mixed)."""
        if self._u_dofs is not None:
            self.u.x.array[:] = self.w.x.array[self._u_dofs]

    def unknown_dof(self, node, axis):
        """Process-local index in the unknown vector of u_axis at a node of V."""
        dof = 3 * node + axis
        return int(self._u_dofs[dof]) if self._u_dofs is not None else dof

    def set_load_factor(self, lam):
        self.load_factor.value = lam
        for value, motion in self._bc_motion:
            value.value = lam * motion
        for c in self.contacts:
            c.set_load_factor(lam)

    def _refuse_inverted(self, x, Du, lam):
        """Continuation: a converged step (x = x0 + Du) whose state has det F
        ≤ 0 somewhere is undone (x, λ as before) and fails, naming the element."""
        x.copy(self.w.vector)
        dfx.update_ghosts(self.w)
        self.sync_displacement()
        with self.timers("inversion check"):
            inverted = self.inversion_check()
        if inverted is not None:
            x.axpy(-1.0, Du)
            self.set_load_factor(lam)
            raise ContinuationFailure(f"{INVERTED_ELEMENT}, {describe_inverted(inverted)}")

    def _attempt(self, step, lam, dlam, attempt):
        """One attempt at the load step λ → λ + Δλ: the Newton solve, solved
        again while a deformable contact's pairing grows, the augmented
        Lagrangian's updates, then the fail_attempt hook. Returns
        (converged, Newton iterations, last solve's norms, reason)."""
        self.set_load_factor(lam + dlam)
        self.update_pairing(fresh=True)
        ok, its, norms, reason = self.solve_step()
        for _ in range(5 if ok else 0):
            # a point found a master facet outside the pattern: solve again with it
            if not self.update_pairing(fresh=False):
                break
            ok, more, norms, reason = self.solve_step()
            its += more
            if not ok:
                break
        if ok:
            ok, more, norms, reason = self._augment(norms, reason)
            its += more
        forced = self.fail_attempt is not None and bool(self.fail_attempt(step, lam, dlam, attempt))
        if self.comm.allreduce(forced, op=MPI.LOR) and ok:
            ok, reason = False, FORCED_FAILURE
        return ok, its, norms, reason

    def _failure_story(self, step, lam, dlam, attempt, reason, norms):
        """What a failed attempt did, for summary.json: its last Newton
        solve's SNES reason, residual norms (one per iterate), active-set and
        stick/slip changes, the points that flipped most, and the inverted
        element of its last iterate, if any. Collective."""
        story = {"step": step, "attempt": attempt, "load_factor": lam, "dlam": dlam, "reason": reason,
                 "snes_reason": self.last_snes_reason, "newton_iterations": self.snes.getIterationNumber(),
                 "residual_norms": list(norms), "update_norms": list(self.update_norms),
                 "active_set_changes": self.active_set_changes(), "stick_slip_changes": self.stick_slip_changes()}
        story.update(flip_story(self.contacts, self.point_states, self.u, self.comm))
        if self.inverted is not None:
            story["inverted_element"] = self.inverted
        return story

    def _augment(self, norms, reason):
        """Augmented Lagrangian (Uzawa) around the Newton solve of a step:
        while a contact's largest penetration exceeds its gap_tolerance,
        set its multipliers to the current pressures and solve again (from
        the converged state), at most max_augmentations times. Returns
        (converged, extra Newton iterations, norms, reason); the number of
        augmentations is kept in self.augmentations."""
        contacts = [c for c in self.contacts if getattr(c, "augmented", False)]
        self.augmentations, extra = 0, 0
        if not contacts:
            return True, 0, norms, reason
        limit = max(c.spec["max_augmentations"] for c in contacts)
        while True:
            over = [c for c in contacts if c.max_penetration(self.u) > c.spec["gap_tolerance"]]
            if not over:
                return True, extra, norms, reason
            if self.augmentations >= limit:
                worst = max(over, key=lambda c: c.max_penetration(self.u) / c.spec["gap_tolerance"])
                self.log(f"   augmented Lagrangian: contact {worst.name!r} still penetrates "
                         f"{worst.max_penetration(self.u):.3g} > gap_tolerance {worst.spec['gap_tolerance']:.3g} "
                         f"after {self.augmentations} augmentations (raise max_augmentations or eps_n)")
                return False, extra, norms, "AUGMENTATION_LIMIT"
            for c in contacts:
                c.augment(self.u)
            self.augmentations += 1
            ok, its, norms, reason = self.solve_step()
            extra += its
            if not ok:
                return False, extra, norms, reason

    def update_pairing(self, fresh):
        """Deformable contacts: with ``fresh``, search at the current state
        and make it the pairing; otherwise (after a converged solve) check
        whether a point has a candidate facet outside the pairing and add it.
        A changed pairing rebuilds the matrix pattern. Returns whether it
        changed."""
        surface = self.problem.global_contacts
        if not surface:
            return False
        changed = False
        with self.timers("contact search"):
            for c in surface:
                if fresh:
                    new = c.search(c.current_coordinates(self.u))
                    same = c.candidates is not None and all(
                        np.array_equal(a, b) for a, b in zip(new, c.candidates))
                    if not self.comm.allreduce(bool(same), op=MPI.LAND):
                        c.candidates = new
                        changed = True
                else:
                    changed |= c.refresh_pairing(self.u)
            if changed:
                A = self.problem.rebuild_pattern()
                if self.snes is not None:
                    self.snes.setJacobian(self.problem.jacobian, A)
        return changed

    def solve_step(self):
        """One Newton solve at the current load factor: (converged, its, norms,
        reason). With solver.linesearch = "auto", a solve that fails with one
        line search is tried again from the same start with the other (full
        steps ↔ backtracking) before the step is cut back: which one converges
        depends on the contact (full steps on the paper's punch, where
        backtracking crawls; backtracking where full steps cycle, on Hertz or
        the ironing die's rim). Its count includes both solves; the norms and
        reason are the last solve's."""
        start = self.w.x.array.copy() if self._fallback_linesearch else None
        ok, its, norms, reason = self._newton_solve()
        fallback = self._fallback_linesearch
        if ok or fallback is None or reason == INVERTED_ELEMENT:
            return ok, its, norms, reason
        self.w.x.array[:] = start  # a failed solve leaves its last iterate in the unknown
        self.sync_displacement()
        primary = set_line_search(self.snes, fallback)
        try:
            ok, more, norms, reason = self._newton_solve()
        finally:
            set_line_search(self.snes, primary)
        return ok, its + more, norms, reason

    def _newton_solve(self):
        """One SNES solve at the current load factor: (converged, its, norms,
        reason). A solve SNES calls converged whose state has det F ≤ 0 at a
        volume quadrature point fails with reason INVERTED_ELEMENT. After
        the solve the unknown holds its end state (converged) or the last
        iterate SNES evaluated (failed), self.inverted says which element of
        it is inverted (or None) and self.last_snes_reason what SNES said."""
        x = self.problem.x
        self.w.vector.copy(x)
        self._reset_iteration_history()
        self.snes.solve(None, x)
        self.linear_iterations.append(self.snes.getLinearSolveIterations())
        reason = self.snes.getConvergedReason()
        norms = residual_norms_of(self.snes)
        self.last_snes_reason = name = converged_reason_name(reason)
        # every rank must take the same branch: a NaN on one rank fails the step on all
        finite = self.comm.allreduce(int(np.all(np.isfinite(x.array))), op=MPI.MIN)
        converged = reason > 0 and bool(finite)
        if converged:
            x.copy(self.w.vector)
            dfx.update_ghosts(self.w)
        self.sync_displacement()
        with self.timers("inversion check"):
            self.inverted = self.inversion_check()
        if converged and self.inverted is not None:
            converged, name = False, INVERTED_ELEMENT
        return converged, self.snes.getIterationNumber(), norms, name

    def active_set_changes(self):
        """Newton iterations of the last solve in which some contact's active
        set (closed nodes) changed: the chattering count of the step."""
        sets = self.active_sets
        return sum(1 for a, b in zip(sets, sets[1:]) if a != b)

    def stick_slip_changes(self):
        """Newton iterations of the last solve in which some frictional
        contact's stick/slip status set changed."""
        sets = self.stick_slip_sets
        return sum(1 for a, b in zip(sets, sets[1:]) if a != b)

    def last_active_set_change(self):
        """Index of the first Newton iterate from which the active set stayed
        fixed in the last solve."""
        k = len(self.active_sets) - 1
        while k > 0 and self.active_sets[k - 1] == self.active_sets[-1]:
            k -= 1
        return k

    def run(self, out_dir=None, resume=False):
        """Solve the scene's load path. Returns the results writer; raises
        :class:`StepFailure` after writing everything that converged. With
        ``resume``, continue from the checkpoint in the results folder."""
        st = self.scene["steps"]
        out_dir = out_dir or self.scene["output"]["dir"]
        self.checkpoint = Checkpoint(Path(out_dir) / "checkpoint", self.comm)
        state, arrays = self.checkpoint.load() if resume else (None, {})
        if state is not None:
            self.w.x.array[:] = arrays["w"]
            self.sync_displacement()
            for c in self.contacts:
                if getattr(c, "augmented", False):
                    c.multipliers = np.asarray(arrays[f"multipliers_{c.name}"], dtype=float).copy()
                    c.multipliers_committed = c.multipliers.copy()
                if isinstance(c, FRICTIONAL):
                    c.xi, c.t_old = arrays[f"xi_{c.name}"], arrays[f"t_{c.name}"]
                    c.lam_committed = state["friction"][c.name]["lam_committed"]
                    c.dissipation = state["friction"][c.name]["dissipation"]
                    c.restore_history_arrays({k: arrays[f"{k}_{c.name}"] for k in c.history_arrays()
                                              if f"{k}_{c.name}" in arrays})
        PETSc.Log.begin()
        events = {name: PETSc.Log.Event(name) for name in ("SNESSolve", "SNESFunctionEval", "SNESJacobianEval")}
        t0 = {name: e.getPerfInfo()["time"] for name, e in events.items()}
        writer = ResultsWriter(out_dir, self.comm, self.scene, self.effects, self.u, self.contacts, self.probes,
                               previous=state, stress=self.stress)
        self.log(f"hypercontact: {', '.join(self.effects)}; "
                 f"{dfx.num_global_dofs(self.w.function_space)} unknowns on {self.comm.size} rank(s)")

        def split():
            """Linear solve = SNES time less residual and Jacobian evaluation
            (factorisation, triangular solves and line-search vector work);
            continuation times its own solves."""
            if st["control"] == "load":
                t = {name: e.getPerfInfo()["time"] - t0[name] for name, e in events.items()}
                self.timers.seconds["linear solve"] = max(
                    t["SNESSolve"] - t["SNESFunctionEval"] - t["SNESJacobianEval"], 0.0)
            return self.timers

        self._lam = state["lam"] if state is not None else 0.0
        self._started = time.perf_counter()
        self._progress0 = 0.0
        if state is not None and state["steps"]:
            last = state["steps"][-1]
            self._progress0 = (last["load_factor"] if st["control"] == "load" else
                               last[f"{st['stop_probe']}_u{st['stop_component']}"] / st["stop_value"])
        try:
            if st["control"] == "load":
                self._load_control(writer, split, out_dir, state)
            else:
                self._continuation(writer, split, out_dir, state, arrays)
        except BaseException as err:
            self.set_load_factor(self._lam)
            message = str(err) or type(err).__name__
            writer.finish("interrupted" if isinstance(err, KeyboardInterrupt) else "failed", message, split())
            raise
        writer.finish("completed", "", split())
        return writer

    def _load_control(self, writer, split, out_dir, state=None):
        """λ: 0 → 1 in steps; Newton (SNES) per step; cut back on failure."""
        st = self.scene["steps"]
        deformable = any(c["obstacle"] == "surface" for c in self.scene["contact"])
        self.snes = make_snes(self.problem, self.comm, self.scene["solver"], deformable=deformable)
        if self.scene["solver"]["linesearch"] == "auto" and self.scene["contact"]:
            self._fallback_linesearch = "basic" if deformable else "bt"
        self.snes.setConvergenceHistory(length=self.scene["solver"]["max_it"] + 1, reset=True)
        self.snes.setMonitor(self._monitor)
        lam, dlam, cuts = 0.0, st["initial"], 0
        # converged steps since the last cut-back or growth, and the Δλ that failed before the last cut-back
        streak, regrow_to = 0, 0.0
        if state is not None:
            lam, dlam = state["lam"], state["dlam"]
            streak, regrow_to = state.get("streak", 0), state.get("regrow_to", 0.0)
            self._lam = lam
            self.set_load_factor(lam)
        u_saved = self.w.x.array.copy()

        while lam < 1.0 - 1e-12:
            dlam = min(dlam, 1.0 - lam)
            ok, its, norms, reason = self._attempt(len(writer.steps) + 1, lam, dlam, cuts)
            if ok:
                lam += dlam
                self._lam = lam
                cuts = 0
                for c in self.contacts:
                    c.commit(self.u)
                u_saved[:] = self.w.x.array
                with self.timers("output"):
                    changes, flips = self.active_set_changes(), self.stick_slip_changes()
                    row = writer.write_step(lam, its, norms, split(), self.last_active_set_change(),
                                            self.update_norms, changes, flips)
                if changes >= st["chatter_warning"]:
                    self.log(f"   the contact active set changed in {changes} Newton iterations of this step "
                             "(chattering): smaller steps or a backtracking line search damp it")
                if flips >= st["chatter_warning"]:
                    self.log(f"   the stick/slip status changed in {flips} Newton iterations of this step "
                             "(chattering): smaller steps or a backtracking line search damp it")
                self.log(f"step {row['step']:3d}  λ = {lam:.4f}  Newton {its:2d}  "
                         f"|R| = {norms[-1]:.2e}  ({reason}){self._eta(lam)}")
                streak += 1
                if its <= st["grow_below"]:
                    dlam, streak = min(dlam * st["growth"], st["max"]), 0
                elif st["grow_after"] and streak >= st["grow_after"] and dlam < regrow_to:
                    # recovery after a cut-back: steps that always take more than grow_below iterations
                    # (friction, deformable masters) would otherwise keep the cut Δλ to the end
                    dlam, streak = min(dlam * st["growth"], regrow_to, st["max"]), 0
                self._save_checkpoint(writer, {"lam": lam, "dlam": dlam, "streak": streak, "regrow_to": regrow_to})
                continue
            stop = cuts >= st["max_cutbacks"] or 0.5 * dlam < st["min"]
            story = self._failure_story(len(writer.steps) + 1, lam, dlam, cuts, reason, norms)
            story["outcome"] = "stopped" if stop else "cut back"
            writer.record_failed_attempt(story, split())
            self.w.x.array[:] = u_saved
            self.sync_displacement()
            for c in self.contacts:
                if getattr(c, "augmented", False):
                    c.restore_multipliers()
            chatter = "".join(f"; the {what} changed in {story[key]} Newton iterations (chattering)"
                              for what, key in (("contact active set", "active_set_changes"),
                                                ("stick/slip status", "stick_slip_changes"))
                              if story[key] >= st["chatter_warning"])
            where = f"; {describe_inverted(story['inverted_element'])}" if "inverted_element" in story else ""
            self.log(f"   step at λ = {lam:.4f} + {dlam:.3g} failed ({reason}, {its} its{chatter}{where}); "
                     + ("no cut-back left" if stop else f"cut back to Δλ = {0.5 * dlam:.3g}"))
            if stop:
                raise StepFailure(
                    f"load step from λ = {lam:.6g} did not converge after {cuts} cut-back{'s' * (cuts != 1)} "
                    f"(last Δλ = {dlam:.3g}, reason {reason}{where}); {len(writer.steps)} converged step(s) "
                    f"are in {out_dir} (what each failed attempt did: failed_attempts in summary.json)")
            if cuts == 0:
                regrow_to = dlam
            cuts, streak = cuts + 1, 0
            dlam *= 0.5

    def _continuation(self, writer, split, out_dir, state=None, arrays=None):
        """Arc-length or displacement control (see continuation.py) until the
        stop probe's displacement component reaches steps.stop_value."""
        st, sv = self.scene["steps"], self.scene["solver"]
        bordered = self.bordered = Bordered(self.problem, self.q_form, self.bcs, self.comm, sv["petsc"],
                                            timers=self.timers)
        x = self.problem.x
        self.w.vector.copy(x)
        probe = self.probes[st["stop_probe"]]
        axis = AXIS[st["stop_component"]]
        target = st["stop_value"]
        if st["control"] == "arclength":
            if state is None:
                self.set_load_factor(0.0)
                bordered.assemble(x)
                size = st["initial"] * bordered.tangent_direction().norm()
                if not size > 0.0:
                    raise StepFailure("arc length cannot start: the [[pressure]] loads do no work on the free "
                                      "degrees of freedom (their load vector is zero once the boundary "
                                      "conditions are applied)")
            else:
                size = state["size0"]
            constraint = ArcLengthConstraint(size)
        else:
            owner_dof = self.unknown_dof(probe.node, axis) if self.comm.rank == probe.owner else -1
            constraint = DisplacementConstraint(owner_dof, probe.owner, self.comm, st["initial"] * target)
        size0 = constraint.size
        lam, du_prev, cuts, last_dlam = 0.0, None, 0, None
        if state is not None:
            lam, last_dlam, size0, constraint.size = state["lam"], state["last_dlam"], state["size0"], state["size"]
            self._lam = lam
            if "du_prev" in arrays:
                du_prev = x.duplicate()
                du_prev.array[:] = arrays["du_prev"]
        while len(writer.steps) < st["max_steps"]:
            reached = probe.value(self.u)[axis]
            if (reached - target) * np.sign(target) >= -1e-12 * abs(target):
                return
            if st["control"] == "displacement":
                constraint.size = np.sign(target) * min(abs(constraint.size), abs(target - reached))
            try:
                Du, dlam, its, norms = continuation_step(
                    bordered, constraint, x, lam, du_prev, self.set_load_factor,
                    sv["rtol"], sv["atol"], sv["max_it"])
                self._refuse_inverted(x, Du, lam)
            except ContinuationFailure as err:
                x.copy(self.w.vector)  # the failed iterates passed through the unknown
                dfx.update_ghosts(self.w)
                self.sync_displacement()
                too_small = 0.5 * abs(constraint.size) < st["min"] * abs(size0)
                if cuts >= st["max_cutbacks"] or too_small:
                    self.log(f"   {constraint.name} step from λ = {lam:.5g} failed ({err}); no cut-back left")
                    why = ("its size would fall below steps.min × the first step's" if too_small
                           else f"after {cuts} cut-back{'s' * (cuts != 1)}")
                    raise StepFailure(
                        f"{constraint.name} step from λ = {lam:.6g} did not converge, {why} ({err}); "
                        f"{len(writer.steps)} converged step(s) are in {out_dir}") from None
                cuts += 1
                constraint.scale(0.5)
                self.log(f"   {constraint.name} step from λ = {lam:.5g} failed ({err}); size halved")
                continue
            cuts = 0
            lam += dlam
            self._lam, du_prev = lam, Du
            x.copy(self.w.vector)
            dfx.update_ghosts(self.w)
            self.sync_displacement()
            for c in self.contacts:
                c.commit(self.u)
            if last_dlam is not None and dlam * last_dlam < 0:
                writer.limit_points.append({"after_step": len(writer.steps), "load_factor": lam - dlam})
                self.log(f"   limit point: the load factor turned at λ ≈ {lam - dlam:.6g}")
            last_dlam = dlam
            with self.timers("output"):
                row = writer.write_step(lam, its, norms, split())
            reached = probe.value(self.u)[axis]
            self.log(f"step {row['step']:3d}  λ = {lam:.5f}  {st['stop_probe']} u{st['stop_component']} = "
                     f"{reached:.4g}  Newton {its:2d}  |R| = {norms[-1]:.2e}{self._eta(reached / target)}")
            factor = float(np.clip(np.sqrt(st["target_iterations"] / max(its, 1)), 0.5, 2.0))
            if st["control"] == "arclength":
                constraint.size = min(constraint.size * factor, size0 * st["max"] / st["initial"])
            else:
                constraint.size = np.sign(target) * min(abs(constraint.size) * factor, abs(target) * st["max"])
            self._save_checkpoint(writer, {"lam": lam, "last_dlam": last_dlam, "size": constraint.size, "size0": size0},
                                  du_prev=du_prev.array_r)
        raise StepFailure(f"steps.max_steps = {st['max_steps']} reached before {st['stop_probe']} "
                          f"u{st['stop_component']} = {target}; {len(writer.steps)} steps are in {out_dir}")
