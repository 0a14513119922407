#include <hypercontact/obstacle.hpp>
#include <hypercontact/rigid_box.hpp>
#include <hypercontact/rigid_cylinder.hpp>
#include <hypercontact/rigid_plane.hpp>
#include <hypercontact/rigid_sphere.hpp>

namespace hypercontact {

namespace {
struct Projector {
  const Eigen::Vector3d& x;
  ObstacleProjection operator()(const RigidPlane& plane) const {
    return project_to_plane(plane, x);
  }
  ObstacleProjection operator()(const RigidBox& box) const { return project_to_box(box, x); }
  ObstacleProjection operator()(const RigidCylinder& cylinder) const {
    return project_to_cylinder(cylinder, x);
  }
  ObstacleProjection operator()(const RigidSphere& sphere) const {
    return project_to_sphere(sphere, x);
  }
};
}  // namespace

ObstacleProjection project(const Obstacle& obstacle, const Eigen::Vector3d& x) {
  return std::visit(Projector{x}, obstacle);
}

}  // namespace hypercontact
