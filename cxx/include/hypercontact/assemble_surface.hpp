// Deformable–deformable contact: narrow phase over the broad phase's candidate facets, the
// node-to-surface (or Gauss-point-to-surface) normal penalty element, and its assembly into
// PETSc objects with global indices (rows of master nodes may be owned by another rank).
#pragma once

#include <petscmat.h>
#include <petscvec.h>

#include <hypercontact/surface_contact.hpp>

namespace hypercontact {

/// Evaluates every slave point: closest point over its candidate facets (ties: face before edge
/// before vertex, then the lower facet index); the sign of the gap from the facet normal (face),
/// the sum of the two facets' centroid normals (inner edge) or of all facets' centroid normals
/// around the node (inner vertex); a point whose closest point is on the master surface's
/// boundary is OffSurface (open) unless it lies within the facet's extent
/// (|r − (r·n) n| ≤ 1e-8 |r|, r = x_p − x_M). A closed point (g ≤ 0; with a multiplier λ_N > 0:
/// ⟨λ_N − ε_N ĝ⟩ > 0, see node_to_surface) adds the element residual
/// and tangent of node_to_surface (energy ½ w ε_N g² with all curvature terms) into b and A
/// (either may be null) with VecSetValues / MatSetValues, global indices, ADD_VALUES; the caller
/// assembles them. Throws std::invalid_argument on inconsistent sizes or indices out of range,
/// std::runtime_error if PETSc reports an error.
SurfaceContactState assemble_surface_contact(const SurfaceContactInput& in, Vec b, Mat A);

}  // namespace hypercontact
