#include <cmath>
#include <hypercontact/rigid_cylinder.hpp>

namespace hypercontact {

ObstacleProjection project_to_cylinder(const RigidCylinder& cylinder, const Eigen::Vector3d& x) {
  const Eigen::Vector3d& a = cylinder.axis;
  const Eigen::Matrix3d A = Eigen::Matrix3d::Identity() - a * a.transpose();
  const Eigen::Vector3d d = A * (x - cylinder.point);
  const double rho = d.norm();
  const double side = cylinder.inside ? -1.0 : 1.0;  // a bore: the gap and normal turn round
  if (!(rho > 1e-12 * cylinder.radius)) {  // on the axis: any radial direction
    const Eigen::Vector3d e = std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX()
                                                    : Eigen::Vector3d::UnitY();
    return {side * (rho - cylinder.radius), (A * e).normalized(), Eigen::Matrix3d::Zero(),
            Feature::Face};
  }
  const Eigen::Vector3d n = side * d / rho;
  return {side * (rho - cylinder.radius), n, side * (A - n * n.transpose()) / rho, Feature::Face};
}

}  // namespace hypercontact
