#include <cmath>
#include <hypercontact/rigid_contact.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

std::vector<RigidContactNode> evaluate_rigid_contact(const Obstacle& obstacle,
                                                     std::span<const double> x,
                                                     std::span<const double> area, double eps_n,
                                                     std::span<const double> multipliers,
                                                     double smoothing) {
  if (x.size() != 3 * area.size())
    throw std::invalid_argument(
        "evaluate_rigid_contact: x has " + std::to_string(x.size()) +
        " entries, expected 3 × len(area) = " + std::to_string(3 * area.size()));
  if (!multipliers.empty() && multipliers.size() != area.size())
    throw std::invalid_argument("evaluate_rigid_contact: multipliers has " +
                                std::to_string(multipliers.size()) + " entries, expected " +
                                std::to_string(area.size()) + " (one per slave node) or none");
  std::vector<RigidContactNode> nodes;
  nodes.reserve(area.size());
  for (std::size_t i = 0; i < area.size(); ++i) {
    const Eigen::Vector3d xi(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    if (!xi.allFinite())
      throw std::runtime_error("evaluate_rigid_contact: coordinates of slave node " +
                               std::to_string(i) + " are not finite");
    const ObstacleProjection projection = project(obstacle, xi);
    if (multipliers.empty()) {
      nodes.push_back({projection, normal_penalty(projection, area[i], eps_n, smoothing)});
      continue;
    }
    if (!(multipliers[i] >= 0) || !std::isfinite(multipliers[i]))
      throw std::invalid_argument("evaluate_rigid_contact: multiplier of slave node " +
                                  std::to_string(i) + " must be finite and >= 0");
    ObstacleProjection shifted = projection;
    shifted.gap -= multipliers[i] / eps_n;
    nodes.push_back({projection, normal_penalty(shifted, area[i], eps_n, smoothing)});
  }
  return nodes;
}

}  // namespace hypercontact
