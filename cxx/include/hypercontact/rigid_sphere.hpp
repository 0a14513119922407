// Signed distance to a rigid ball (a spherical indenter).
#pragma once

#include <hypercontact/obstacle.hpp>

namespace hypercontact {

/// Signed distance function of the ball {y : |y − c| ≤ R} at a finite point x, with c the
/// centre and R > 0 the radius:
///   d = x − c,  ρ = |d|,  g = ρ − R,  n = d/ρ,  ∂n/∂x = (I − n nᵀ)/ρ.
/// The same formulas hold inside (g < 0: the closest surface point is radially outward), so the
/// gap, the normal and its derivative are smooth everywhere except at the centre, where the
/// normal is undefined: there (ρ below 1e-12 R) n is a fixed unit vector (+z), ∂n/∂x = 0.
/// Always Feature::Face. The result is never NaN.
ObstacleProjection project_to_sphere(const RigidSphere& sphere, const Eigen::Vector3d& x);

}  // namespace hypercontact
