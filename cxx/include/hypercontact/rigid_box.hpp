// Signed distance to a rigid axis-aligned box (a flat punch with its edges and vertices).
#pragma once

#include <hypercontact/obstacle.hpp>

namespace hypercontact {

/// Signed distance function of the box [lo, hi], with its edges rounded by r = box.radius, at a
/// finite point x. The box is the set of points within r of the inner box B = [lo + r, hi − r],
/// so its signed distance is that of B minus r (B is convex).
///
/// Outside B (x ∉ B): closest point of B c = clamp(x, lo + r, hi − r), d = x − c, ρ = |d| > 0,
///   g = ρ − r,  n = d/ρ,  ∂n/∂x = (D − n nᵀ)/ρ,
/// where D = diag(1 for each clamped coordinate, 0 otherwise). The number of clamped
/// coordinates (1, 2, 3) gives Face, Edge, Vertex; for an Edge with tangent t, D = I − t tᵀ.
/// With r > 0 this holds also for a point that has penetrated less than r into a rounded edge
/// or corner (g < 0): the normal turns with the point, as on a cylinder or a sphere. With r = 0
/// (sharp edges) ρ = g.
///
/// Inside B or on its surface: with the distances δ_f ≥ 0 from x to the planes of B's faces,
///   g = −min_f δ_f − r ≤ 0,  n = outward normal of the minimising face,  ∂n/∂x = 0,  Face.
/// Ties are resolved deterministically by the face order (−z, +z, −x, +x, −y, +y): the first
/// face in this order among those at the minimal distance wins. With r = 0 a point exactly on
/// the surface counts as inside, with g = +0. The result is never NaN.
ObstacleProjection project_to_box(const RigidBox& box, const Eigen::Vector3d& x);

}  // namespace hypercontact
