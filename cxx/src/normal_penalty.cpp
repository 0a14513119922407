#include <algorithm>
#include <cmath>
#include <hypercontact/normal_penalty.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {
void check_parameters(double area, double eps_n, double smoothing) {
  if (!(smoothing >= 0) || !std::isfinite(smoothing))
    throw std::invalid_argument("normal_penalty: smoothing must be finite and >= 0, got " +
                                std::to_string(smoothing));
  if (!(area >= 0))
    throw std::invalid_argument("normal_penalty: area must be >= 0, got " + std::to_string(area));
  if (!(eps_n > 0))
    throw std::invalid_argument("normal_penalty: eps_n must be > 0, got " + std::to_string(eps_n));
}
}  // namespace

double normal_penalty_energy(const ObstacleProjection& p, double area, double eps_n,
                             double smoothing) {
  check_parameters(area, eps_n, smoothing);
  return area * eps_n * penetration_energy(p.gap, smoothing);
}

NodalContact normal_penalty(const ObstacleProjection& p, double area, double eps_n,
                            double smoothing) {
  check_parameters(area, eps_n, smoothing);
  if (!penetration_active(p.gap, smoothing))
    return {Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero(), 0.0, false};
  const double k = area * eps_n;
  const auto [P, slope] = penetration(p.gap, smoothing);
  return {(-k * P) * p.normal,
          k * ((-slope) * (p.normal * p.normal.transpose()) - P * p.dnormal_dx), eps_n * P, true};
}

}  // namespace hypercontact
