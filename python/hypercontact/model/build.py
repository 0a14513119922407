"""A scene → the :class:`Model`: everything that is built, built once, in
the order it depends on: body (mesh and named surfaces), volume forms,
constraints, loads, contacts, probes, the Newton problem."""
import numpy as np
import ufl
from mpi4py import MPI

from .. import _dolfinx as dfx
from .. import geometry
from ..contact import build_contacts
from ..scene import SceneError
from ..scene.path import LoadPath
from ..solve.newton import Problem
from .effects import describe_effects
from .inversion import InversionCheck
from .loading import Constraints, Loads
from .material import body_materials
from .probes import Probe
from .volume import build_volume


class Model:
    """What a scene builds. ``law``: a Python ψ(F, **params) from a driver
    script in place of the scene's material law."""

    def __init__(self, scene, comm, timers, law=None, map_mesh=None):
        """``map_mesh(body)``: moves the mesh nodes (body.mesh.geometry.x) before
        anything is built on it (e.g. a box bent into a shell)."""
        self.scene, self.comm = scene, comm
        self.body = geometry.build_mesh(comm, scene["mesh"], scene["body"])
        if map_mesh is not None:
            map_mesh(self.body)
        if scene["mesh"]["perturbation"] > 0:
            dfx.perturb_coordinates(self.body.mesh, scene["mesh"]["perturbation"])
        vol = self.volume = build_volume(scene, self.body, law)
        self.w, self.V, self.u, self._u_dofs, self.stress = vol.w, vol.V, vol.u, vol.u_dofs, vol.stress
        space = self.w.function_space.sub(0) if vol.u_dofs is not None else self.w.function_space
        self.constraints = Constraints(scene, self.w, space, self.body.facet_tags, self.tag, self.body.mesh)
        self.bcs = self.constraints.bcs
        R, J = self._with_loads(vol)
        self.path = LoadPath(scene)
        self.phase = 0  # the phase the load factor runs in
        self.contacts, self.contact_settings = build_contacts(
            scene, self.V, self.body.facet_tags, self.tag, self.constraints.constrained, self.material_of,
            self.path, vol.u_dofs,
            None if vol.u_dofs is None else dfx.global_dofs(self.w.function_space, vol.u_dofs))
        size = comm.allreduce(np.ptp(self.body.mesh.geometry.x, axis=0).max(), op=MPI.MAX)
        self.probes = {name: Probe(name, p, self.V, 1e-6 * size) for name, p in scene["output"]["probes"].items()}
        self.problem = Problem(self.w, R, J, self.bcs, self.contacts, timers)
        self.inversion_check = InversionCheck(self.u, scene["discretisation"]["quadrature_degree"])
        self.effects = describe_effects(scene, vol.description, self.contact_settings, self.path.moving_bcs(),
                                        dfx.num_global_dofs(self.w.function_space), self.symmetric_tangent,
                                        self.path, dfx.element_description(self.V),
                                        sum(getattr(c.geometry, "integration", None) == "gauss"
                                            for c in self.contacts),
                                        sum(getattr(c.geometry, "integration", None) == "facet"
                                            for c in self.contacts))

    @property
    def pressure_unknowns(self):
        """The global number of unknowns that are not displacements: the mixed formulation's
        pressure, 0 otherwise. Its tangent is a saddle point: each pressure unknown gives one
        negative eigenvalue at a stable equilibrium (Sylvester's law on the block factorisation
        with the negative definite Schur complement −C/K − BᵀA⁻¹B)."""
        if self._u_dofs is None:
            return 0
        return dfx.num_global_dofs(self.w.function_space) - dfx.num_global_dofs(self.V)

    @property
    def symmetric_tangent(self):
        """Whether the tangent is symmetric: the second derivative of an
        energy — hyperelastic volume (every formulation), dead loads, Dirichlet
        conditions (dolfinx zeroes rows and columns) and frictionless contact
        with rigid obstacles (penalty or augmented Lagrangian with its
        multipliers fixed in a solve: ∂n/∂x is symmetric on every obstacle).
        Not with follower pressure, friction or a deformable master (whose
        node-to-surface tangent is not symmetrised); tested entry by entry in
        tests/behaviour/test_symmetric_tangent.py."""
        return not self.scene["pressure"] and all(not (c.deformable or c.frictional)
                                                  for c in self.contacts)

    def _with_loads(self, vol):
        """R + the loads and its tangent; q = ∂R/∂λ (kept for continuation) and
        the λ Constant (the load factor of the phase: what drivers and tests read)."""
        self.load_factor = dfx.constant(self.body.mesh, 0.0)
        self.loads = Loads(self.scene, self.body.mesh, self.body.facet_tags, self.tag, vol.trial_u, vol.test_u)
        self.q_form = self.loads.q if not self.scene.get("phase") else self.loads.q_rates
        if self.loads.form is None:
            return vol.R, vol.J
        dw = ufl.TrialFunction(self.w.function_space)
        return vol.R + self.loads.form, vol.J + ufl.derivative(self.loads.form, self.w, dw)

    def tag(self, surface, key):
        """The facet tag of a named surface; SceneError naming ``key`` if there is none."""
        if surface not in self.body.surfaces:
            raise SceneError(f"scene key '{key}': the mesh has no surface {surface!r} "
                             f"(it has {', '.join(sorted(self.body.surfaces))})")
        return self.body.surfaces[surface]

    def material_of(self, surface):
        """The material entry of the body a surface ('<body>.<surface>' or the [mesh] body's; of a mesh
        file: the physical volume its facets bound) belongs to."""
        if self.scene["mesh"]["builder"] == "file" and self.scene["body"]:
            regions = geometry.surface_regions(self.body, self.tag(surface, "contact.surface"))
            if len(regions) != 1:
                raise SceneError(f"surface {surface!r} bounds the physical volumes {', '.join(regions) or 'none'}: "
                                 "the automatic penalty (eps_n = 0) takes the modulus of one body; give eps_n")
            return body_materials(self.scene).get(regions[0], self.scene["material"])
        prefix = surface.split(".")[0] if "." in surface else None
        return next((b["material"] for b in self.scene["body"] if b["name"] == prefix), self.scene["material"])

    def update_pairing(self, fresh):
        """Deformable contacts: search at u (``fresh``: a new pairing; else grow
        it after a converged solve); a changed pairing rebuilds the matrix
        pattern (problem.A is replaced). Returns whether it changed."""
        changed = False
        for c in self.problem.global_contacts:
            changed |= c.update_pairing(self.u, fresh)
        if changed:
            self.problem.rebuild_pattern()
        return changed

    def set_load_factor(self, lam):
        """The load factor of the current phase (``phase``): s = λ."""
        self.set_path(self.phase, lam)

    def set_path(self, phase, s):
        """Everything the load path drives, at parameter s of ``phase``: bcs,
        loads, obstacles' poses, μ."""
        self.phase = phase
        values = self.path.values(phase, s)
        self.load_factor.value = s
        self.constraints.set_values(values)
        self.loads.set_values(values)
        for c in self.contacts:
            c.set_load_factor(s)
            c.set_path_values(values[("motion", c.index)] if ("motion", c.index) in values else None,
                              values.get(("rotation", c.index), 0.0), values[("mu", c.index)],
                              values[("active", c.index)])

    def set_rates(self, phase):
        """q_form = ∂R/∂s of ``phase`` (continuation inside phases; a no-op without phases)."""
        if not self.path.implicit:
            self.loads.set_rates(self.path.rates(phase))

    def sync_displacement(self):
        """u from the unknown (a no-op unless the formulation is mixed)."""
        if self._u_dofs is not None:
            self.u.x.array[:] = self.w.x.array[self._u_dofs]

    def displacement_rows(self):
        """(owned nodes of V, 3): each owned displacement node's three positions in the
        process-local unknown vector (its residual's rows)."""
        dofs = np.arange(3 * dfx.num_owned_nodes(self.V))
        return (dofs if self._u_dofs is None else np.asarray(self._u_dofs)[dofs]).reshape(-1, 3)

    def unknown_dof(self, node, axis):
        """Process-local index in the unknown vector of u_axis at a node of V."""
        dof = 3 * node + axis
        return int(self._u_dofs[dof]) if self._u_dofs is not None else dof
