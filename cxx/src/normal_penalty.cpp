#include <algorithm>
#include <hypercontact/normal_penalty.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {
void check_parameters(double area, double eps_n) {
  if (!(area >= 0))
    throw std::invalid_argument("normal_penalty: area must be >= 0, got " + std::to_string(area));
  if (!(eps_n > 0))
    throw std::invalid_argument("normal_penalty: eps_n must be > 0, got " + std::to_string(eps_n));
}
}  // namespace

double normal_penalty_energy(const ObstacleProjection& p, double area, double eps_n) {
  check_parameters(area, eps_n);
  const double penetration = std::max(0.0, -p.gap);
  return 0.5 * area * eps_n * penetration * penetration;
}

NodalContact normal_penalty(const ObstacleProjection& p, double area, double eps_n) {
  check_parameters(area, eps_n);
  if (p.gap > 0) return {Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero(), 0.0, false};
  const double k = area * eps_n;
  return {k * p.gap * p.normal, k * (p.normal * p.normal.transpose() + p.gap * p.dnormal_dx),
          eps_n * std::max(0.0, -p.gap), true};
}

}  // namespace hypercontact
