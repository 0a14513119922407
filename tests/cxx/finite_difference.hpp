// Central finite differences and error measures for the tangent checks.
#pragma once

#include <Eigen/Core>
#include <algorithm>

namespace hypercontact::test {

/// Step h = 1e-6 · max(1, |x|∞).
inline double fd_step(const Eigen::Vector3d& x) {
  return 1e-6 * std::max(1.0, x.cwiseAbs().maxCoeff());
}

/// ∂f/∂x_j ≈ (f(x + h e_j) − f(x − h e_j)) / 2h for scalar f.
template <typename F>
Eigen::Vector3d fd_gradient(F f, const Eigen::Vector3d& x) {
  const double h = fd_step(x);
  Eigen::Vector3d g;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(j);
    g[j] = (f(x + e) - f(x - e)) / (2 * h);
  }
  return g;
}

/// Column j of the Jacobian of a vector-valued f: (f(x + h e_j) − f(x − h e_j)) / 2h.
template <typename F>
Eigen::Matrix3d fd_jacobian(F f, const Eigen::Vector3d& x) {
  const double h = fd_step(x);
  Eigen::Matrix3d J;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(j);
    J.col(j) = (f(x + e) - f(x - e)) / (2 * h);
  }
  return J;
}

/// ‖approx − exact‖∞ / ‖exact‖∞ (exact must be non-zero).
template <typename A, typename B>
double relative_error(const A& approx, const B& exact) {
  return (approx - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff();
}

}  // namespace hypercontact::test
