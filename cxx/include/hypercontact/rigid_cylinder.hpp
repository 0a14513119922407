// Signed distance to a rigid circular cylinder of infinite length (a smooth curved die).
#pragma once

#include <hypercontact/obstacle.hpp>

namespace hypercontact {

/// Signed distance function of the cylinder {y : |(I − a aᵀ)(y − p)| ≤ R} at a finite point x,
/// with p a point on the axis, a the unit axis and R > 0 the radius:
///   d = (I − a aᵀ)(x − p),  ρ = |d|,  g = ρ − R,  n = d/ρ,  ∂n/∂x = (I − a aᵀ − n nᵀ)/ρ.
/// The same formulas hold inside (g < 0: the closest surface point is radially outward), so the
/// gap, the normal and its derivative are smooth everywhere except on the axis, where the
/// normal is undefined: there (ρ below 1e-12 R) n is any unit vector normal to a, ∂n/∂x = 0.
/// A bore (cylinder.inside) is the same surface seen from within: g = R − ρ, n = −d/ρ,
/// ∂n/∂x = −(I − a aᵀ − n nᵀ)/ρ; its axis is the point farthest from the wall, where any
/// radial n is as good as another. Always Feature::Face. The result is never NaN.
ObstacleProjection project_to_cylinder(const RigidCylinder& cylinder, const Eigen::Vector3d& x);

}  // namespace hypercontact
