#include <hypercontact/assemble_friction.hpp>
#include <hypercontact/assembly.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {
RigidFrictionEvaluation friction_part(const Obstacle& obstacle, std::span<const double> x,
                                      std::span<const double> area, double eps_n, double eps_t,
                                      double mu, std::span<const double> xi_old,
                                      std::span<const double> t_old,
                                      std::span<const std::int32_t> dofs,
                                      std::span<const double> multipliers, double smoothing) {
  return evaluate_rigid_friction({{obstacle, x, area, dofs, eps_n, multipliers, smoothing},
                                  xi_old,
                                  t_old,
                                  eps_t,
                                  mu,
                                  /*with_normal=*/false});
}
}  // namespace

RigidFrictionState assemble_rigid_friction_residual(
    const Obstacle& obstacle, std::span<const double> x, std::span<const double> area, double eps_n,
    double eps_t, double mu, std::span<const double> xi_old, std::span<const double> t_old,
    std::span<const std::int32_t> dofs, std::span<double> b, std::span<const double> multipliers,
    double smoothing) {
  RigidFrictionEvaluation e = friction_part(obstacle, x, area, eps_n, eps_t, mu, xi_old, t_old,
                                            dofs, multipliers, smoothing);
  for (std::int32_t dof : dofs)  // every node's, open ones included
    if (dof >= static_cast<std::int64_t>(b.size()))
      throw std::out_of_range("assemble_rigid_friction_residual: dof " + std::to_string(dof) +
                              " outside the local residual array");
  add_residual(e, b);
  return {std::move(e.traction), std::move(e.slip_increment), std::move(e.dissipation),
          std::move(e.state), e.friction_force};
}

void assemble_rigid_friction_tangent(const Obstacle& obstacle, std::span<const double> x,
                                     std::span<const double> area, double eps_n, double eps_t,
                                     double mu, std::span<const double> xi_old,
                                     std::span<const double> t_old,
                                     std::span<const std::int32_t> dofs, Mat A,
                                     std::span<const double> multipliers, double smoothing) {
  add_tangent(friction_part(obstacle, x, area, eps_n, eps_t, mu, xi_old, t_old, dofs, multipliers,
                            smoothing),
              A);
}

}  // namespace hypercontact
