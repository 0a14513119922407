#include <hypercontact/rigid_plane.hpp>

namespace hypercontact {

ObstacleProjection project_to_plane(const RigidPlane& plane, const Eigen::Vector3d& x) {
  return {(x - plane.point).dot(plane.normal), plane.normal, Eigen::Matrix3d::Zero(),
          Feature::Face};
}

}  // namespace hypercontact
