// Signed distance to a rigid axis-aligned box (a flat punch with its edges and vertices).
#pragma once

#include <hypercontact/obstacle.hpp>

namespace hypercontact {

/// Signed distance function of the box [lo, hi] at a finite point x.
///
/// Outside (x ∉ [lo, hi]): closest point c = clamp(x, lo, hi), d = x − c,
///   g = |d| > 0,  n = d/g,  ∂n/∂x = (D − n nᵀ)/g,
/// where D = diag(1 for each clamped coordinate, 0 otherwise). The number of clamped
/// coordinates (1, 2, 3) gives Face, Edge, Vertex; for an Edge with tangent t, D = I − t tᵀ.
///
/// Inside or on the surface: with the distances δ_f ≥ 0 from x to the planes of the six faces,
///   g = −min_f δ_f ≤ 0,  n = outward normal of the minimising face,  ∂n/∂x = 0,  Face.
/// Ties are resolved deterministically by the face order (−z, +z, −x, +x, −y, +y): the first
/// face in this order among those at the minimal distance wins. A point exactly on the surface
/// counts as inside, with g = 0. The result is never NaN.
ObstacleProjection project_to_box(const RigidBox& box, const Eigen::Vector3d& x);

}  // namespace hypercontact
