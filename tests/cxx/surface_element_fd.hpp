// Test helpers for the deformable-master contact elements: stacking of the element's node
// coordinates and central finite differences over all of them.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <hypercontact/facet_projection.hpp>
#include <initializer_list>
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

/// The facets the element tests share (placed: rotated and shifted off the axes).
inline const NodeCoordinates flat_quad =
    placed({{0, 0, 0}, {1.1, 0.1, 0}, {1.2, 0.9, 0}, {-0.1, 1, 0}});
/// Non-planar: n · x_,12 ≈ 0.2, so the curvature term r·x_,12 of H matters when g ≠ 0.
inline const NodeCoordinates warped_quad =
    placed({{0, 0, 0.2}, {1.2, 0.1, -0.1}, {1.1, 0.9, 0.3}, {-0.1, 1, -0.2}});
inline const NodeCoordinates triangle = placed({{0, 0, 0}, {1.2, 0.1, 0.1}, {0.2, 1, -0.1}});
/// The weights of a slave point that is one node.
inline const Eigen::VectorXd one_node = Eigen::VectorXd::Ones(1);

/// ξ of node a of a facet of n nodes: corners, then edge midpoints, then the centre.
inline Eigen::Vector2d node_xi(int n, int a) {
  const int nc = (n == 3 || n == 6) ? 3 : 4;
  if (a < nc) return facet_vertex_xi(n, a);
  if (a < 2 * nc) return 0.5 * (facet_vertex_xi(n, a - nc) + facet_vertex_xi(n, a - nc + 1));
  return {0.0, 0.0};
}

/// x_M(ξ) on facet m.
inline Eigen::Vector3d surface_point(const NodeCoordinates& m, const Eigen::Vector2d& xi) {
  return m * facet_shape_functions(static_cast<int>(m.cols()), xi);
}

/// x_M(ξ) + g n(ξ): for small |g| its closest point is x_M(ξ), its gap g.
inline Eigen::Vector3d point_at(const NodeCoordinates& m, const Eigen::Vector2d& xi, double gap) {
  return surface_point(m, xi) + gap * facet_normal(m, xi);
}

/// One slave node as a 3 × 1 node set.
inline NodeCoordinates single(const Eigen::Vector3d& x) { return x; }

/// Outward unit normal, in the facet's tangent plane at ξ, of edge k.
inline Eigen::Vector3d edge_outward(const NodeCoordinates& m, int k, const Eigen::Vector2d& xi) {
  const int n = static_cast<int>(m.cols());
  return (m.col((k + 1) % n) - m.col(k)).cross(facet_normal(m, xi)).normalized();
}

}  // namespace hypercontact::test
