#include <cmath>
#include <hypercontact/penetration.hpp>
#include <hypercontact/rigid_contact.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace detail {

void check_rigid_sizes(std::span<const double> x, std::span<const double> area,
                       std::span<const double> multipliers, const char* who) {
  const std::size_t n = area.size();
  if (x.size() != 3 * n)
    throw std::invalid_argument(std::string(who) + ": x has " + std::to_string(x.size()) +
                                " entries, expected 3 × len(area) = " + std::to_string(3 * n));
  if (!multipliers.empty() && multipliers.size() != n)
    throw std::invalid_argument(std::string(who) + ": multipliers has " +
                                std::to_string(multipliers.size()) + " entries, expected " +
                                std::to_string(n) + " (one per slave node) or none");
}

int check_rigid_input(const RigidContactInput& in, const char* who) {
  check_rigid_sizes(in.x, in.area, in.multipliers, who);
  const std::size_t n = in.area.size();
  std::size_t k = 1;
  if (!in.point_weights.empty()) {
    if (n == 0 || in.point_weights.size() % n != 0)
      throw std::invalid_argument(
          std::string(who) + ": point_weights has " + std::to_string(in.point_weights.size()) +
          " entries, expected k × " + std::to_string(n) + " (k nodes per slave point)");
    k = in.point_weights.size() / n;
  }
  if (in.dofs.size() != 3 * k * n)
    throw std::invalid_argument(
        std::string(who) + ": dofs has " + std::to_string(in.dofs.size()) + " entries, expected " +
        std::to_string(3 * k * n) + " (3 per node of " +
        (k == 1 ? std::string("each slave node") : std::to_string(k) + " per slave point") + ")");
  return static_cast<int>(k);
}

void append_point_element(ContactElements& elements, const RigidContactInput& in, int k,
                          std::size_t i, const Eigen::Vector3d& r, const Eigen::Matrix3d& K) {
  ContactElements::Slot e = elements.append(static_cast<std::int32_t>(i), 3 * k, 3 * k);
  for (int j = 0; j < 3 * k; ++j) e.rows[j] = e.columns[j] = in.dofs[3 * k * i + j];
  if (in.point_weights.empty()) {
    e.residual = r;
    e.tangent = K;
    return;
  }
  const double* M = &in.point_weights[k * i];
  for (int a = 0; a < k; ++a) {
    e.residual.segment<3>(3 * a) = M[a] * r;
    for (int b = 0; b < k; ++b) e.tangent.block<3, 3>(3 * a, 3 * b) = (M[a] * M[b]) * K;
  }
}

Eigen::Vector3d slave_node(std::span<const double> x, std::size_t i, const char* who) {
  const Eigen::Vector3d xi(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
  if (!xi.allFinite())
    throw std::runtime_error(std::string(who) + ": coordinates of slave node " + std::to_string(i) +
                             " are not finite");
  return xi;
}

double multiplier(std::span<const double> multipliers, std::size_t i, const char* who) {
  if (multipliers.empty()) return 0.0;
  if (!(multipliers[i] >= 0) || !std::isfinite(multipliers[i]))
    throw std::invalid_argument(std::string(who) + ": multiplier of slave node " +
                                std::to_string(i) + " must be finite and >= 0");
  return multipliers[i];
}

}  // namespace detail

RigidContactNode rigid_contact_node(const Obstacle& obstacle, const Eigen::Vector3d& x, double area,
                                    double eps_n, double lambda, double smoothing) {
  const ObstacleProjection projection = project(obstacle, x);
  return {projection,
          normal_penalty(augmented_projection(projection, lambda, eps_n), area, eps_n, smoothing)};
}

std::vector<RigidContactNode> evaluate_rigid_contact(const Obstacle& obstacle,
                                                     std::span<const double> x,
                                                     std::span<const double> area, double eps_n,
                                                     std::span<const double> multipliers,
                                                     double smoothing) {
  constexpr const char* who = "evaluate_rigid_contact";
  detail::check_rigid_sizes(x, area, multipliers, who);
  std::vector<RigidContactNode> nodes;
  nodes.reserve(area.size());
  for (std::size_t i = 0; i < area.size(); ++i) {
    const Eigen::Vector3d xi = detail::slave_node(x, i, who);
    const double lambda = detail::multiplier(multipliers, i, who);
    nodes.push_back(rigid_contact_node(obstacle, xi, area[i], eps_n, lambda, smoothing));
  }
  return nodes;
}

namespace {

/// evaluate_rigid_contact with points_per_facet = Q > 0: one pressure per facet, that of its
/// mean gap (rigid_contact.hpp).
RigidContactEvaluation evaluate_rigid_facets(const RigidContactInput& in) {
  constexpr const char* who = "evaluate_rigid_contact (facet integration)";
  const std::size_t n = in.area.size();
  const int Q = in.points_per_facet;
  if (n % static_cast<std::size_t>(Q) != 0)
    throw std::invalid_argument(std::string(who) + ": " + std::to_string(n) +
                                " points are not whole facets of " + std::to_string(Q));
  const std::size_t nf = n / Q;
  if (!(in.eps_n > 0))  // before anything a process without facets skips: every process throws
    throw std::invalid_argument(std::string(who) + ": eps_n must be > 0");
  RigidContactEvaluation out{{{}, {}, Eigen::Vector3d::Zero(), 0}, {}};
  out.elements.numbering = DofNumbering::Local;
  if (n == 0) return out;  // a process without slave facets
  if (in.point_weights.empty() || in.point_weights.size() % n != 0)
    throw std::invalid_argument(std::string(who) + ": point_weights must hold k weights per point");
  const int k = static_cast<int>(in.point_weights.size() / n);
  if (in.dofs.size() != 3 * k * nf)
    throw std::invalid_argument(std::string(who) + ": dofs has " + std::to_string(in.dofs.size()) +
                                " entries, expected " + std::to_string(3 * k * nf) +
                                " (3 per node of " + std::to_string(k) + " per facet)");
  if (!in.multipliers.empty() && in.multipliers.size() != nf)
    throw std::invalid_argument(std::string(who) + ": multipliers has " +
                                std::to_string(in.multipliers.size()) + " entries, expected " +
                                std::to_string(nf) + " (one per facet) or none");
  out.gap.reserve(nf);
  out.pressure.reserve(nf);
  std::vector<ObstacleProjection> proj(Q);
  Eigen::VectorXd B(3 * k);
  for (std::size_t f = 0; f < nf; ++f) {
    double area = 0, weighted_gap = 0;
    for (int q = 0; q < Q; ++q) {
      const std::size_t i = f * Q + q;
      proj[q] = project(in.obstacle, detail::slave_node(in.x, i, who));
      area += in.area[i];
      weighted_gap += in.area[i] * proj[q].gap;
    }
    if (!(area > 0))
      throw std::invalid_argument(std::string(who) + ": slave facet " + std::to_string(f) +
                                  " has area " + std::to_string(area) + ", expected > 0");
    const double gap = weighted_gap / area;
    const double lambda = detail::multiplier(in.multipliers, f, who);
    const NormalPressure law = normal_pressure(gap, in.eps_n, lambda, in.smoothing);
    out.gap.push_back(gap);
    out.pressure.push_back(law.value);
    if (!law.active) continue;
    ++out.num_closed;
    ContactElements::Slot e = out.elements.append(static_cast<std::int32_t>(f), 3 * k, 3 * k);
    for (int j = 0; j < 3 * k; ++j) e.rows[j] = e.columns[j] = in.dofs[3 * k * f + j];
    B.setZero();
    e.tangent.setZero();
    for (int q = 0; q < Q; ++q) {
      const std::size_t i = f * Q + q;
      const double* M = &in.point_weights[k * i];
      const double w = in.area[i];
      out.force += (law.value * w) * proj[q].normal;
      const Eigen::Matrix3d curvature = (-law.value * w) * proj[q].dnormal_dx;
      for (int a = 0; a < k; ++a) {
        B.segment<3>(3 * a) += (w * M[a]) * proj[q].normal;
        for (int b = 0; b < k; ++b)
          e.tangent.block<3, 3>(3 * a, 3 * b) += (M[a] * M[b]) * curvature;
      }
    }
    e.residual = -law.value * B;
    e.tangent -= (law.slope / area) * B * B.transpose();
  }
  return out;
}

}  // namespace

RigidContactEvaluation evaluate_rigid_contact(const RigidContactInput& in) {
  constexpr const char* who = "evaluate_rigid_contact";
  if (in.points_per_facet < 0)
    throw std::invalid_argument(std::string(who) + ": points_per_facet must be >= 0");
  if (in.points_per_facet > 0) return evaluate_rigid_facets(in);
  const int k = detail::check_rigid_input(in, who);
  const std::size_t n = in.area.size();
  RigidContactEvaluation out{{{}, {}, Eigen::Vector3d::Zero(), 0}, {}};
  out.gap.reserve(n);
  out.pressure.reserve(n);
  out.elements.numbering = DofNumbering::Local;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d xi = detail::slave_node(in.x, i, who);
    const double lambda = detail::multiplier(in.multipliers, i, who);
    const RigidContactNode node =
        rigid_contact_node(in.obstacle, xi, in.area[i], in.eps_n, lambda, in.smoothing);
    const NodalContact& c = node.contact;
    out.gap.push_back(node.projection.gap);
    out.pressure.push_back(c.pressure);
    if (!c.closed) continue;
    ++out.num_closed;
    out.force -= c.residual;
    detail::append_point_element(out.elements, in, k, i, c.residual, c.tangent);
  }
  return out;
}

}  // namespace hypercontact
