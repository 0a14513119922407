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
///
/// Blended (box.blended, r > 0): the circular rounding's curvature jumps from 0 on a face to 1/r
/// on the edge, and so does the contact tangent of a point sliding over the junction. The
/// blended box is instead the set of points within r/2 of the solid S = {y : ρ₄(e(y)) ≤ r/2},
/// where e(y) = |y − clamp(y, B)| componentwise and ρ₄(e) = (Σ eᵢ⁴)^¼: S rounds B's edges by
/// quarter-superellipses y₁⁴ + y₂⁴ = (r/2)⁴, whose curvature is 0 where they meet the faces,
/// and the offset by r/2 keeps every curvature below 2/r. The faces end at the same line as the
/// circular rounding's, r from the edge. Outside B, with e = |x − c| and s = sign(x − c):
///  - one clamped coordinate (Face): as above, g = ρ − r, n = s, ∂n/∂x = 0;
///  - ρ₄(e) > r/2 (a point outside S, or less than r/2 into the box): the closest point y of
///    S's surface solves yᵢ + 4λ yᵢ³ = eᵢ, Σ yᵢ⁴ = (r/2)⁴ with λ ≥ 0 (a monotone scalar equation
///    in λ, solved by safeguarded Newton); g = |e − y| − r/2, n = s ⊙ y³/|y³| (so ∂g/∂x = n),
///    and ∂n/∂x = S (I − n̂ n̂ᵀ) diag(3yᵢ²)/|y³| ∂y/∂e S with ∂y/∂e from the implicit function
///    theorem (S = diag(s), n̂ = y³/|y³|);
///  - ρ₄(e) ≤ r/2 (deeper than r/2 into the rounding): the level set of ρ₄ stands in for the
///    distance, g = ρ₄(e) − r, n = s ⊙ e³/|e³|, ∂n/∂x = S P diag(3eᵢ²) P S/|e³|, P = I − n̂n̂ᵀ.
///    Continuous with the branches around it, but there ∂g/∂x ≠ n: the contact tangent is
///    exact only up to r/2 of penetration, far beyond any penalty's.
/// Inside B as above.
ObstacleProjection project_to_box(const RigidBox& box, const Eigen::Vector3d& x);

}  // namespace hypercontact
