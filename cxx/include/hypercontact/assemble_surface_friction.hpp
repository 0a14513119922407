// Coulomb friction against a deformable master surface, assembled: per slave point the normal
// penalty of assemble_surface_contact (same pairing, same element) plus the return mapping of
// surface_friction with the point's history, into PETSc objects with global indices.
#pragma once

#include <hypercontact/assemble_surface.hpp>
#include <hypercontact/surface_contact_friction.hpp>

namespace hypercontact {

/// Evaluates every slave point as assemble_surface_contact; a closed point (Paired, g ≤ touch)
/// adds the normal element (node_to_surface) and the friction of surface_friction against its
/// current facet at ξ* with the history (old facet's CURRENT nodes at ξ_old, t_old). A point
/// without history (old_facet = −1) uses old facet = current facet, ξ_old = ξ*, t_old = 0: its
/// trial traction ε_T P_T (x_s − x_M(ξ*)) vanishes, so it adds its (zero) friction residual but
/// no friction tangent (the consistent derivative of a residual that is zero for every x).
/// Rows: [slave nodes, current facet]; columns: [slave, current facet, old facet] (duplicates
/// of shared nodes are summed by ADD_VALUES); constrained dofs (−1) skipped. Throws as
/// assemble_surface_contact, and std::invalid_argument if the history is inconsistent.
SurfaceFrictionState assemble_surface_friction(const SurfaceFrictionInput& in, Vec b, Mat A);

}  // namespace hypercontact
