#include <array>
#include <hypercontact/assemble_friction.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {
/// coulomb_friction for every slave node, after checking the sizes of the arrays.
std::vector<FrictionResult> evaluate(const Obstacle& obstacle, std::span<const double> x,
                                     std::span<const double> area, double eps_n, double eps_t,
                                     double mu, std::span<const double> xi_old,
                                     std::span<const double> t_old,
                                     std::span<const std::int32_t> dofs,
                                     std::span<const double> multipliers, double smoothing) {
  const std::size_t n = area.size();
  if (!multipliers.empty() && multipliers.size() != n)
    throw std::invalid_argument("assemble_rigid_friction: multipliers has " +
                                std::to_string(multipliers.size()) + " entries, expected " +
                                std::to_string(n) + " or none");
  for (auto [name, size] : {std::pair{"x", x.size()}, std::pair{"xi_old", xi_old.size()},
                            std::pair{"t_old", t_old.size()}, std::pair{"dofs", dofs.size()}})
    if (size != 3 * n)
      throw std::invalid_argument(std::string("assemble_rigid_friction: ") + name + " has " +
                                  std::to_string(size) + " entries, expected 3 × " +
                                  std::to_string(n));
  std::vector<FrictionResult> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d xi(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    if (!xi.allFinite())
      throw std::runtime_error("assemble_rigid_friction: coordinates of slave node " +
                               std::to_string(i) + " are not finite");
    ObstacleProjection p = project(obstacle, xi);
    if (!multipliers.empty()) p.gap -= multipliers[i] / eps_n;  // augmented: p_N = ⟨λ − ε_N g⟩
    out.push_back(coulomb_friction(p, xi, Eigen::Vector3d(&xi_old[3 * i]),
                                   Eigen::Vector3d(&t_old[3 * i]), area[i], eps_n, eps_t, mu,
                                   smoothing));
  }
  return out;
}
}  // namespace

RigidFrictionState assemble_rigid_friction_residual(
    const Obstacle& obstacle, std::span<const double> x, std::span<const double> area, double eps_n,
    double eps_t, double mu, std::span<const double> xi_old, std::span<const double> t_old,
    std::span<const std::int32_t> dofs, std::span<double> b, std::span<const double> multipliers,
    double smoothing) {
  const auto nodes =
      evaluate(obstacle, x, area, eps_n, eps_t, mu, xi_old, t_old, dofs, multipliers, smoothing);
  RigidFrictionState s{{}, {}, {}, {}, Eigen::Vector3d::Zero()};
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const FrictionResult& f = nodes[i];
    for (int k = 0; k < 3; ++k) {
      s.traction.push_back(f.traction[k]);
      s.slip_increment.push_back(f.slip_increment[k]);
      if (const std::int32_t dof = dofs[3 * i + k]; dof >= 0) {
        if (dof >= static_cast<std::int64_t>(b.size()))
          throw std::out_of_range("assemble_rigid_friction_residual: dof " + std::to_string(dof) +
                                  " outside the local residual array");
        b[dof] += f.residual[k];
      }
    }
    s.dissipation.push_back(f.dissipation);
    s.state.push_back(static_cast<std::int8_t>(f.state));
    s.force -= f.residual;
  }
  return s;
}

void assemble_rigid_friction_tangent(const Obstacle& obstacle, std::span<const double> x,
                                     std::span<const double> area, double eps_n, double eps_t,
                                     double mu, std::span<const double> xi_old,
                                     std::span<const double> t_old,
                                     std::span<const std::int32_t> dofs, Mat A,
                                     std::span<const double> multipliers, double smoothing) {
  const auto nodes =
      evaluate(obstacle, x, area, eps_n, eps_t, mu, xi_old, t_old, dofs, multipliers, smoothing);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].state == StickSlip::Open) continue;
    const std::array<PetscInt, 3> rows{dofs[3 * i], dofs[3 * i + 1], dofs[3 * i + 2]};
    const Eigen::Matrix<PetscScalar, 3, 3, Eigen::RowMajor> K = nodes[i].tangent;
    if (MatSetValuesLocal(A, 3, rows.data(), 3, rows.data(), K.data(), ADD_VALUES) != 0)
      throw std::runtime_error(
          "assemble_rigid_friction_tangent: MatSetValuesLocal failed for "
          "slave node " +
          std::to_string(i));
  }
}

}  // namespace hypercontact
