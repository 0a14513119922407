#include <hypercontact/rigid_contact_friction.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {

void check_history(const RigidFrictionInput& in, const char* who) {
  const std::size_t n = in.contact.area.size();
  for (auto [name, size] :
       {std::pair{"xi_old", in.xi_old.size()}, std::pair{"t_old", in.t_old.size()}})
    if (size != 3 * n)
      throw std::invalid_argument(std::string(who) + ": " + name + " has " + std::to_string(size) +
                                  " entries, expected 3 × " + std::to_string(n));
}

RigidFrictionEvaluation empty_evaluation(std::size_t n) {
  RigidFrictionEvaluation out;
  out.gap.reserve(n);
  out.pressure.reserve(n);
  out.force.setZero();
  out.num_closed = 0;
  out.traction.reserve(3 * n);
  out.slip_increment.reserve(3 * n);
  out.dissipation.reserve(n);
  out.state.reserve(n);
  out.friction_force.setZero();
  out.elements.numbering = DofNumbering::Local;
  return out;
}

}  // namespace

RigidFrictionEvaluation evaluate_rigid_friction(const RigidFrictionInput& in) {
  constexpr const char* who = "evaluate_rigid_friction";
  const RigidContactInput& c = in.contact;
  if (c.points_per_facet != 0)
    throw std::invalid_argument(std::string(who) +
                                ": facet integration (points_per_facet > 0) is frictionless: a "
                                "facet's mean gap has no slip of its own");
  const int k = detail::check_rigid_input(c, who);
  check_history(in, who);
  const std::size_t n = c.area.size();
  RigidFrictionEvaluation out = empty_evaluation(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d xi = detail::slave_node(c.x, i, who);
    const double lambda = detail::multiplier(c.multipliers, i, who);
    const RigidContactNode node =
        rigid_contact_node(c.obstacle, xi, c.area[i], c.eps_n, lambda, c.smoothing);
    const FrictionResult f =
        coulomb_friction(augmented_projection(node.projection, lambda, c.eps_n), xi,
                         Eigen::Vector3d(&in.xi_old[3 * i]), Eigen::Vector3d(&in.t_old[3 * i]),
                         c.area[i], c.eps_n, in.eps_t, in.mu, c.smoothing);
    const NodalContact& normal = node.contact;
    out.gap.push_back(node.projection.gap);
    out.pressure.push_back(normal.pressure);
    for (int k = 0; k < 3; ++k) {
      out.traction.push_back(f.traction[k]);
      out.slip_increment.push_back(f.slip_increment[k]);
    }
    out.dissipation.push_back(f.dissipation);
    out.state.push_back(static_cast<std::int8_t>(f.state));
    if (!normal.closed) continue;  // then f.state is Open, and f is zero
    ++out.num_closed;
    out.force -= normal.residual;
    out.friction_force -= f.residual;
    if (in.with_normal)
      detail::append_point_element(out.elements, c, k, i, normal.residual + f.residual,
                                   normal.tangent + f.tangent);
    else
      detail::append_point_element(out.elements, c, k, i, f.residual, f.tangent);
  }
  out.total_force = out.force + out.friction_force;
  return out;
}

}  // namespace hypercontact
