// Test helpers for the deformable-master contact elements: stacking of the element's node
// coordinates and central finite differences over all of them.
#pragma once

#include <Eigen/Geometry>
#include <initializer_list>

#include <Eigen/Core>
#include <algorithm>
#include <hypercontact/facet_projection.hpp>
#include <vector>

namespace hypercontact::test {

/// Node sets of an element, stacked in this order: x = [set 0 columns, set 1 columns, …], each
/// column as (x, y, z).
inline Eigen::VectorXd stack(const std::vector<NodeCoordinates>& sets) {
  Eigen::Index size = 0;
  for (const NodeCoordinates& s : sets) size += s.size();
  Eigen::VectorXd x(size);
  Eigen::Index offset = 0;
  for (const NodeCoordinates& s : sets) {
    x.segment(offset, s.size()) = Eigen::Map<const Eigen::VectorXd>(s.data(), s.size());
    offset += s.size();
  }
  return x;
}

/// Inverse of stack, with the sizes of `like`.
inline std::vector<NodeCoordinates> unstack(const Eigen::VectorXd& x,
                                            const std::vector<NodeCoordinates>& like) {
  std::vector<NodeCoordinates> sets;
  Eigen::Index offset = 0;
  for (const NodeCoordinates& s : like) {
    NodeCoordinates t(3, s.cols());
    Eigen::Map<Eigen::VectorXd>(t.data(), t.size()) = x.segment(offset, s.size());
    sets.push_back(t);
    offset += s.size();
  }
  return sets;
}

inline double fd_step_stacked(const Eigen::VectorXd& x) {
  return 1e-6 * std::max(1.0, x.cwiseAbs().maxCoeff());
}

/// Central differences of a scalar f over every entry of x.
template <typename F>
Eigen::VectorXd fd_gradient_stacked(F f, const Eigen::VectorXd& x) {
  const double h = fd_step_stacked(x);
  Eigen::VectorXd g(x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    g[j] = (f(xp) - f(xm)) / (2 * h);
  }
  return g;
}

/// Central differences of a vector-valued f over every entry of x: column j = ∂f/∂x_j.
template <typename F>
Eigen::MatrixXd fd_jacobian_stacked(F f, const Eigen::VectorXd& x) {
  const double h = fd_step_stacked(x);
  const Eigen::VectorXd f0 = f(x);
  Eigen::MatrixXd J(f0.size(), x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    J.col(j) = (f(xp) - f(xm)) / (2 * h);
  }
  return J;
}

/// Rotation and shift that put test facets off every axis.
inline const Eigen::Matrix3d test_rotation =
    Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
inline const Eigen::Vector3d test_shift(1, 2, 3);

/// Nodes given in a local frame, rotated and shifted so that nothing is axis-aligned.
inline NodeCoordinates placed(std::initializer_list<Eigen::Vector3d> local) {
  NodeCoordinates x(3, static_cast<Eigen::Index>(local.size()));
  int j = 0;
  for (const Eigen::Vector3d& p : local) x.col(j++) = test_rotation * p + test_shift;
  return x;
}

}  // namespace hypercontact::test
