// Signed distance to a rigid plane.
#pragma once

#include <hypercontact/obstacle.hpp>

namespace hypercontact {

/// Projection of x onto the plane (p, n), n unit:
///   g = (x − p)·n,   normal = n,   ∂n/∂x = 0,   feature = Face.
ObstacleProjection project_to_plane(const RigidPlane& plane, const Eigen::Vector3d& x);

}  // namespace hypercontact
