#include <array>
#include <hypercontact/assemble_rigid.hpp>
#include <hypercontact/rigid_contact.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {
std::vector<RigidContactNode> evaluate(const Obstacle& obstacle, std::span<const double> x,
                                       std::span<const double> area, double eps_n,
                                       std::span<const std::int32_t> dofs,
                                       std::span<const double> multipliers, double smoothing) {
  if (dofs.size() != x.size())
    throw std::invalid_argument("assemble_rigid: dofs has " + std::to_string(dofs.size()) +
                                " entries, expected " + std::to_string(x.size()) +
                                " (3 per slave node, like x)");
  return evaluate_rigid_contact(obstacle, x, area, eps_n, multipliers, smoothing);
}
}  // namespace

RigidContactState assemble_rigid_residual(const Obstacle& obstacle, std::span<const double> x,
                                          std::span<const double> area, double eps_n,
                                          std::span<const std::int32_t> dofs, std::span<double> b,
                                          std::span<const double> multipliers, double smoothing) {
  const std::vector<RigidContactNode> nodes =
      evaluate(obstacle, x, area, eps_n, dofs, multipliers, smoothing);
  for (std::int32_t dof : dofs)
    if (dof >= static_cast<std::int64_t>(b.size()))
      throw std::out_of_range("assemble_rigid_residual: dof " + std::to_string(dof) +
                              " outside the local residual array of size " +
                              std::to_string(b.size()));
  RigidContactState state{{}, {}, Eigen::Vector3d::Zero(), 0};
  state.gap.reserve(nodes.size());
  state.pressure.reserve(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const NodalContact& c = nodes[i].contact;
    state.gap.push_back(nodes[i].projection.gap);
    state.pressure.push_back(c.pressure);
    if (!c.closed) continue;
    ++state.num_closed;
    state.force -= c.residual;
    for (int k = 0; k < 3; ++k)
      if (const std::int32_t dof = dofs[3 * i + k]; dof >= 0) b[dof] += c.residual[k];
  }
  return state;
}

void assemble_rigid_tangent(const Obstacle& obstacle, std::span<const double> x,
                            std::span<const double> area, double eps_n,
                            std::span<const std::int32_t> dofs, Mat A,
                            std::span<const double> multipliers, double smoothing) {
  const std::vector<RigidContactNode> nodes =
      evaluate(obstacle, x, area, eps_n, dofs, multipliers, smoothing);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const NodalContact& c = nodes[i].contact;
    if (!c.closed) continue;
    const std::array<PetscInt, 3> rows{dofs[3 * i], dofs[3 * i + 1], dofs[3 * i + 2]};
    const Eigen::Matrix<PetscScalar, 3, 3, Eigen::RowMajor> K = c.tangent;
    if (MatSetValuesLocal(A, 3, rows.data(), 3, rows.data(), K.data(), ADD_VALUES) != 0)
      throw std::runtime_error("assemble_rigid_tangent: MatSetValuesLocal failed for slave node " +
                               std::to_string(i));
  }
}

}  // namespace hypercontact
