"""The volume of the body: the unknown, its displacement view and the
residual and tangent forms of the chosen formulation (displacement, selective
reduced integration, mixed u–p), one law per body."""
from dataclasses import dataclass

import ufl

from .. import _dolfinx as dfx
from ..forms import materials, volume
from ..results import first_piola_stress
from ..scene import SceneError
from .material import body_materials, resolve_material


@dataclass
class Volume:
    w: object  # the unknown (u, or (u, p) in the mixed formulation)
    V: object  # the displacement space
    u: object  # the displacement (w itself, or refreshed from w after each solve)
    u_dofs: object  # positions of u's dofs in w (None unless mixed)
    R: object
    J: object
    trial_u: object  # u in UFL (a part of w in the mixed formulation)
    test_u: object
    description: str
    stress: object  # stress(u) → P, for the results


def build_volume(scene, body, law=None):
    """The Volume of the scene's material(s) and discretisation on ``body``."""
    disc, mat = scene["discretisation"], scene["material"]
    psi, params, desc = resolve_material(mat, law)
    name = mat["law"]
    if disc["formulation"] != "displacement" and law is not None:  # the scene checked the scene's laws
        raise SceneError(f"scene key 'discretisation.formulation': {disc['formulation']!r} takes the built-in "
                         f"law's isochoric part; a driver script's law has none (use \"displacement\")")
    if disc["formulation"] == "mixed":
        return _mixed(body, name, params, desc, disc["quadrature_degree"])
    if disc["degree"] == 2 and disc["quadrature_degree"] < 4 and body.mesh.topology.cell_type.name == "hexahedron":
        # 2 × 2 × 2 points (degrees 2 and 3) see 48 strains of a 27-node hexahedron's 75 deformation modes:
        # the rest are zero-energy (hourglass) modes, and Newton fails from the first step
        raise SceneError(f"scene key 'discretisation.quadrature_degree': 27-node hexahedra (degree = 2) need "
                         f"3 × 3 × 3 Gauss points (quadrature_degree >= 4), found {disc['quadrature_degree']}: fewer "
                         f"leave zero-energy (hourglass) modes")
    V = dfx.vector_space(body.mesh, disc["degree"])
    u = dfx.fem.Function(V, name="displacement")
    if scene["body"]:
        R, J, desc, stress = _several_bodies(scene, body, u, law, psi, params, desc)
    elif disc["formulation"] == "sri":
        iso_params, K, vol = materials.split_volumetric(params)
        R, J = volume.selective_reduced_forms(u, materials.ISOCHORIC[name], iso_params, K, disc["quadrature_degree"],
                                              volumetric=vol)
        desc += ", selective reduced integration"
        stress = first_piola_stress(psi, **params)
    else:
        R, J = volume.displacement_forms(u, psi, params, disc["quadrature_degree"])
        stress = first_piola_stress(psi, **params)
    return Volume(u, V, u, None, R, J, u, ufl.TestFunction(V), desc, stress)


def _mixed(body, name, params, desc, qdeg):
    iso_params, K, vol = materials.split_volumetric(params)
    w = dfx.fem.Function(dfx.taylor_hood_space(body.mesh), name="solution")
    V, u_dofs = dfx.collapse(w.function_space.sub(0))
    u = dfx.fem.Function(V, name="displacement")
    R, J = volume.mixed_up_forms(w, materials.ISOCHORIC[name], iso_params, K, qdeg, vol)
    p = ufl.split(w)[1]

    def stress(u_out):
        """P = ∂ψ_iso/∂F + p J G'(J) F⁻ᵀ with the pressure unknown p."""
        F = ufl.variable(ufl.Identity(3) + ufl.grad(u_out))
        P_iso = ufl.diff(materials.ISOCHORIC[name](F, **iso_params), F)
        return P_iso + volume.mixed_pressure_stress(F, p, K, vol)

    return Volume(w, V, u, u_dofs, R, J, ufl.split(w)[0], ufl.split(ufl.TestFunction(w.function_space))[0],
                  desc + f", mixed u–p (Taylor–Hood {'P2–P1' if dfx.facet_type(body.mesh) == 'triangle' else 'Q2–Q1'})",
                  stress)


def _several_bodies(scene, body, u, law, psi, params, desc):
    """Volume forms summed over the regions (bodies), each with its own law on
    its own cells; the stress for the results picked per cell by region. A
    region's law is its [[body]]'s (the body of that name, or of that volume of
    a mesh file), else the scene's [material]."""
    disc = scene["discretisation"]
    dx = ufl.Measure("dx", domain=body.mesh, subdomain_data=body.cell_tags)
    own = body_materials(scene)
    laws = []
    for region in body.regions:
        if region in own:
            b_psi, b_params, b_desc = resolve_material(own[region])
            laws.append((b_psi, b_params, own[region]["law"], b_desc))
        else:
            laws.append((psi, params, scene["material"]["law"], desc))
    R = J = None
    stresses = []
    DG0 = dfx.fem.FunctionSpace(body.mesh, ("DG", 0))
    for (b_psi, b_params, name, _), (region, tag) in zip(laws, body.regions.items()):
        if disc["formulation"] == "sri":
            iso, K, vol = materials.split_volumetric(b_params)
            Rb, Jb = volume.selective_reduced_forms(u, materials.ISOCHORIC[name], iso, K,
                                                    disc["quadrature_degree"], dx(tag), vol)
        else:
            Rb, Jb = volume.displacement_forms(u, b_psi, b_params, disc["quadrature_degree"], dx(tag))
        R, J = (Rb, Jb) if R is None else (R + Rb, J + Jb)
        chi = dfx.fem.Function(DG0)
        chi.x.array[:] = 0.0
        chi.x.array[body.cell_tags.indices[body.cell_tags.values == tag]] = 1.0
        chi.x.scatter_forward()
        stresses.append((chi, first_piola_stress(b_psi, **b_params)))

    def stress(u_out):
        return sum(chi * P(u_out) for chi, P in stresses)

    def numbers(p):
        return ", ".join(f"{k} = {v:g}" for k, v in p.items() if isinstance(v, (int, float)))

    text = "; ".join(f"{region}: {d} [{numbers(p)}]" for (_, p, _, d), region in zip(laws, body.regions))
    if disc["formulation"] == "sri":
        text += ", selective reduced integration"
    return R, J, f"{len(laws)} bodies ({text})", stress
