"""What the load factor λ drives: Dirichlet conditions u_a = λ × motion_a on
the fixed components, and loads proportional to λ (follower pressures, dead
tractions, body forces) with q = ∂R/∂λ for continuation."""
import numpy as np
import ufl

from .. import _dolfinx as dfx
from ..forms import loads

AXIS = {"x": 0, "y": 1, "z": 2}


class Constraints:
    """The scene's [[bc]] entries: ``bcs`` (dolfinx DirichletBCs, one per fixed
    component), ``values`` {(entry index, axis letter): its Constant} and the
    mask of constrained process-local dofs of the unknown. Each value goes
    from ``start`` to ``end`` as λ goes 0 → 1: from 0 to the scene's motion,
    or along a phase (:meth:`start_phase`)."""

    def __init__(self, scene, w, displacement_space, facet_tags, tag_of, mesh):
        self.bcs, self.values, self.paths = [], {}, {}
        for i, bc in enumerate(scene["bc"]):
            facets = dfx.facets_with_tag(facet_tags, tag_of(bc["surface"], f"bc[{i}].surface"))
            for a in bc["fix"]:
                value = dfx.constant(mesh, 0.0)
                self.bcs.append(dfx.dirichlet_component(displacement_space, AXIS[a], facets, value))
                self.values[(i, a)] = value
                self.paths[(i, a)] = (0.0, float(bc["motion"][AXIS[a]]))
        self.num_moving = sum(end != 0.0 for _, end in self.paths.values())
        self.constrained = np.zeros(w.x.array.size, dtype=bool)
        for bc in self.bcs:
            self.constrained[dfx.bc_dofs(bc)] = True

    def start_phase(self, ends):
        """A new phase from where every value is now: value (i, a) ends at
        ``ends[(i, a)]`` (the others stay where they are)."""
        for key, value in self.values.items():
            start = float(value.value)
            self.paths[key] = (start, float(ends.get(key, start)))

    def set_load_factor(self, lam):
        for key, (start, end) in self.paths.items():
            if start != 0.0 or end != 0.0:
                np.copyto(self.values[key].value, start + lam * (end - start))


def load_terms(scene, mesh, facet_tags, tag_of, trial_u, test_u):
    """q = Σ the loads per unit load factor (a UFL form), or None."""
    qdeg = scene["discretisation"]["quadrature_degree"]
    ds = dfx.facet_integration_measure(mesh, facet_tags, qdeg)
    terms = [loads.follower_pressure(trial_u, test_u, pr["value"], ds(tag_of(pr["surface"], f"pressure[{i}].surface")))
             for i, pr in enumerate(scene["pressure"])]
    terms += [loads.dead_load(test_u, tr["value"], ds(tag_of(tr["surface"], f"traction[{i}].surface")))
              for i, tr in enumerate(scene["traction"])]
    dx = ufl.dx(domain=mesh, metadata={"quadrature_degree": qdeg})
    terms += [loads.dead_load(test_u, bf["value"], dx) for bf in scene["body_force"]]
    return sum(terms[1:], terms[0]) if terms else None
