"""What the load path drives (:mod:`hypercontact.scene.path`): Dirichlet
conditions on the fixed components and the loads (follower pressures, dead
tractions, body forces), each value a Constant; q = ∂R/∂λ for continuation."""
import numpy as np
import ufl
from mpi4py import MPI

from .. import _dolfinx as dfx
from ..forms import loads
from ..scene import SceneError
from ..scene.path import AXIS, LOADS


class Constraints:
    """The scene's [[bc]] entries: ``bcs`` (dolfinx DirichletBCs, one per fixed
    component), ``values`` {(entry index, axis letter): its Constant} and the
    mask of constrained process-local dofs of the unknown. The values follow
    the load path (:meth:`set_values`)."""

    def __init__(self, scene, w, displacement_space, facet_tags, tag_of, mesh):
        self.bcs, self.values = [], {}
        for i, bc in enumerate(scene["bc"]):
            if bc.get("point") is not None:
                entities, nearest = dfx.vertices_at(mesh, bc["point"])
                if mesh.comm.allreduce(len(entities), MPI.SUM) == 0:
                    raise SceneError(f"scene key 'bc[{i}].point': no mesh node at {bc['point']} "
                                     f"(nearest is {nearest:.3g} away)")
                dim = 0
            else:
                entities = dfx.facets_with_tag(facet_tags, tag_of(bc["surface"], f"bc[{i}].surface"))
                dim = mesh.topology.dim - 1
            for a in bc["fix"]:
                value = dfx.constant(mesh, 0.0)
                self.bcs.append(dfx.dirichlet_component(displacement_space, AXIS[a], entities, value, dim))
                self.values[(i, a)] = value
        self.constrained = np.zeros(w.x.array.size, dtype=bool)
        for bc in self.bcs:
            self.constrained[dfx.bc_dofs(bc)] = True

    def set_values(self, values):
        """u_a on bc entry i = values[("bc", i, a)]."""
        for (i, a), constant in self.values.items():
            constant.value = values[("bc", i, a)]


class Loads:
    """The scene's loads, each with its value a Constant that follows the
    load path: R_loads = Σ_k L_k(u; value_k) (follower pressures, dead
    tractions, dead body forces: each linear in its value). ``q`` = ∂R/∂λ
    of the scene without phases (value_k = λ × the scene's value), for
    continuation; None without loads. ``q_rates``: the same with each
    value's rate in a phase (:meth:`set_rates`)."""

    def __init__(self, scene, mesh, facet_tags, tag_of, trial_u, test_u):
        qdeg = scene["discretisation"]["quadrature_degree"]
        ds = dfx.facet_integration_measure(mesh, facet_tags, qdeg)
        dx = ufl.dx(domain=mesh, metadata={"quadrature_degree": qdeg})
        self.constants, self.rates, terms, reference, rate_terms = {}, {}, [], [], []
        for section, size in LOADS.items():
            for i, load in enumerate(scene[section]):
                c = dfx.constant(mesh, 0.0 if size == 1 else np.zeros(3))
                self.constants[(section, i)] = c
                if section == "body_force":
                    measure = dx
                else:
                    measure = ds(tag_of(load["surface"], f"{section}[{i}].surface"))
                term = (loads.follower_pressure if section == "pressure" else
                        (lambda u, v, value, m: loads.dead_load(v, value, m)))
                terms.append(term(trial_u, test_u, c, measure))
                r = dfx.constant(mesh, 0.0 if size == 1 else np.zeros(3))
                self.rates[(section, i)] = r
                rate_terms.append(term(trial_u, test_u, r, measure))
                if load["value"] is not None:
                    reference.append(term(trial_u, test_u, load["value"], measure))
        self.form = sum(terms[1:], terms[0]) if terms else None
        self.q = sum(reference[1:], reference[0]) if reference and len(reference) == len(terms) else None
        #: ∂R/∂s of a phase: the loads at their rates (set_rates), for continuation inside phases
        self.q_rates = sum(rate_terms[1:], rate_terms[0]) if rate_terms else None

    def set_rates(self, rates):
        for key, c in self.rates.items():
            c.value = rates[key]

    def set_values(self, values):
        for key, c in self.constants.items():
            c.value = values[key]
