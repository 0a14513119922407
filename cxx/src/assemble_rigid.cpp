#include <hypercontact/assemble_rigid.hpp>
#include <hypercontact/assembly.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

RigidContactState assemble_rigid_residual(const Obstacle& obstacle, std::span<const double> x,
                                          std::span<const double> area, double eps_n,
                                          std::span<const std::int32_t> dofs, std::span<double> b,
                                          std::span<const double> multipliers, double smoothing) {
  RigidContactEvaluation e =
      evaluate_rigid_contact({obstacle, x, area, dofs, eps_n, multipliers, smoothing});
  for (std::int32_t dof : dofs)  // every node's, open ones included
    if (dof >= static_cast<std::int64_t>(b.size()))
      throw std::out_of_range("assemble_rigid_residual: dof " + std::to_string(dof) +
                              " outside the local residual array of size " +
                              std::to_string(b.size()));
  add_residual(e, b);
  return std::move(static_cast<RigidContactState&>(e));
}

void assemble_rigid_tangent(const Obstacle& obstacle, std::span<const double> x,
                            std::span<const double> area, double eps_n,
                            std::span<const std::int32_t> dofs, Mat A,
                            std::span<const double> multipliers, double smoothing) {
  add_tangent(evaluate_rigid_contact({obstacle, x, area, dofs, eps_n, multipliers, smoothing}), A);
}

}  // namespace hypercontact
