#include <hypercontact/rigid_sphere.hpp>

namespace hypercontact {

ObstacleProjection project_to_sphere(const RigidSphere& sphere, const Eigen::Vector3d& x) {
  const Eigen::Vector3d d = x - sphere.center;
  const double rho = d.norm();
  if (!(rho > 1e-12 * sphere.radius))  // at the centre: every direction is radial
    return {rho - sphere.radius, Eigen::Vector3d::UnitZ(), Eigen::Matrix3d::Zero(), Feature::Face};
  const Eigen::Vector3d n = d / rho;
  return {rho - sphere.radius, n, (Eigen::Matrix3d::Identity() - n * n.transpose()) / rho,
          Feature::Face};
}

}  // namespace hypercontact
