// Rigid obstacles: analytic master surfaces, and the projection of a slave point onto them.
#pragma once

#include <Eigen/Core>
#include <variant>

namespace hypercontact {

/// Which feature of the obstacle is closest to the slave point.
enum class Feature { Face, Edge, Vertex };

/// Closest-point projection of a slave point x onto an obstacle.
struct ObstacleProjection {
  /// Signed distance g(x): > 0 open, < 0 penetration.
  double gap;
  /// Unit outward normal n of the obstacle at the closest point (points from the obstacle
  /// towards x when open); ∂g/∂x = n.
  Eigen::Vector3d normal;
  /// ∂n/∂x: zero on a flat face, (I − n nᵀ − t tᵀ)/g on an edge with unit tangent t,
  /// (I − n nᵀ)/g at a vertex; (I − a aᵀ − n nᵀ)/ρ on a cylinder of axis a, (I − n nᵀ)/ρ on a
  /// sphere (ρ the distance from the axis or the centre).
  Eigen::Matrix3d dnormal_dx;
  Feature feature;
};

/// Half-space bounded by the plane through `point`; `normal` is unit and points out of the
/// obstacle into the admissible half-space.
struct RigidPlane {
  Eigen::Vector3d point;
  Eigen::Vector3d normal;
};

/// Axis-aligned box occupying [lo, hi] (current position); requires lo < hi componentwise.
/// With `radius` r > 0 its edges and corners are rounded: the box is the set of points within
/// r of the inner box [lo + r, hi − r] (a flat punch whose edges are quarter cylinders of radius
/// r and whose corners are eighth spheres); requires 2r ≤ hi − lo (where 2r is a side, to
/// round-off, the inner box is flat in that direction). r = 0: sharp edges.
/// With `blended` the rounding's curvature is continuous: it rises from 0 where a flat face
/// ends instead of jumping to 1/r (project_to_box).
struct RigidBox {
  Eigen::Vector3d lo;
  Eigen::Vector3d hi;
  double radius = 0.0;
  bool blended = false;
};

/// Circular cylinder of infinite length: axis through `point` along the unit vector `axis`,
/// radius `radius` > 0; the admissible region is outside it (a smooth rigid die), or with
/// `inside` the region inside it (a bore, the outer wall of a groove).
struct RigidCylinder {
  Eigen::Vector3d point;
  Eigen::Vector3d axis;
  double radius;
  bool inside = false;
};

/// Ball of centre `center` and radius `radius` > 0; the admissible region is outside it (a
/// spherical indenter).
struct RigidSphere {
  Eigen::Vector3d center;
  double radius;
};

using Obstacle = std::variant<RigidPlane, RigidBox, RigidCylinder, RigidSphere>;

/// Projection of a finite point x onto any obstacle: dispatches to project_to_plane,
/// project_to_box, project_to_cylinder or project_to_sphere.
ObstacleProjection project(const Obstacle& obstacle, const Eigen::Vector3d& x);

}  // namespace hypercontact
