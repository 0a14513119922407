// Test helpers for evaluations with element contributions: their dense assembly (independent of
// the PETSc assembly) and the central finite differences of the assembled residual over every
// coordinate, with dofs numbered as the coordinates (dof 3 n + k = coordinate k of node n).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <hypercontact/contact_elements.hpp>
#include <numeric>
#include <span>
#include <vector>

#include "finite_difference.hpp"
#include "surface_element_fd.hpp"

namespace hypercontact::test {

/// 0, 1, …, n − 1: every coordinate its own dof.
inline std::vector<std::int32_t> identity_dofs(std::size_t n) {
  std::vector<std::int32_t> dofs(n);
  std::iota(dofs.begin(), dofs.end(), 0);
  return dofs;
}

/// Σ_e R_e into b[row dof] (rows −1 skipped), b of n entries.
inline Eigen::VectorXd dense_residual(const ContactElements& elements, Eigen::Index n) {
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  for (std::size_t k = 0; k < elements.row_dofs.size(); ++k)
    if (elements.row_dofs[k] >= 0) b[elements.row_dofs[k]] += elements.residual[k];
  return b;
}

/// Σ_e K_e into A[row dofs, column dofs] (−1 skipped, repeated columns added).
inline Eigen::MatrixXd dense_tangent(const ContactElements& elements, Eigen::Index n) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto rows = elements.rows(e), columns = elements.columns(e);
    const auto K = elements.element_tangent(e);
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t j = 0; j < columns.size(); ++j)
        if (rows[i] >= 0 && columns[j] >= 0) A(rows[i], columns[j]) += K(i, j);
  }
  return A;
}

/// Central differences of the dense residual of evaluate(x) (any evaluation with `elements`)
/// over every coordinate of x.
template <typename Evaluate>
Eigen::MatrixXd fd_dense_tangent(Evaluate evaluate, const std::vector<double>& x) {
  const auto n = static_cast<Eigen::Index>(x.size());
  const auto residual = [&](const Eigen::VectorXd& y) {
    const std::vector<double> v(y.data(), y.data() + y.size());
    return dense_residual(evaluate(std::span<const double>(v)).elements, n);
  };
  return fd_jacobian_stacked(residual, Eigen::Map<const Eigen::VectorXd>(x.data(), n));
}

/// ‖K_fd − K‖∞ / ‖K‖∞ of evaluate at x: the stored tangent against finite differences of the
/// stored residual.
template <typename Evaluate>
double dense_tangent_error(Evaluate evaluate, const std::vector<double>& x) {
  const auto n = static_cast<Eigen::Index>(x.size());
  const Eigen::MatrixXd K = dense_tangent(evaluate(std::span<const double>(x)).elements, n);
  return relative_error(fd_dense_tangent(evaluate, x), K);
}

}  // namespace hypercontact::test
