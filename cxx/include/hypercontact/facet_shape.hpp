// The master facets of a deformable surface — bilinear and biquadratic quadrilaterals, linear and
// quadratic triangles — their reference conventions and shape functions, with the number of
// nodes a template parameter (fixed-size Eigen types) or, for callers that know it only at run
// time, an argument.
#pragma once

#include <Eigen/Core>
#include <array>

namespace hypercontact {

/// Master facet conventions (NM = num_nodes = 3, 4, 6 or 9; corners counter-clockwise seen from
/// outside, then the edge nodes, then the centre):
///   Quadrilateral (4, 9 nodes): ξ ∈ [−1, 1]², corners ξ_a = (−1,−1), (1,−1), (1,1), (−1,1);
///     4 nodes: N_a = ¼ (1 + s1_a ξ1)(1 + s2_a ξ2) with (s1_a, s2_a) = ξ_a;
///     9 nodes: node 4 + k at the middle of edge k, node 8 at the centre,
///     N_a = L_{i_a}(ξ1) L_{j_a}(ξ2) with L_{−1}(s) = s(s − 1)/2, L_0 = 1 − s², L_1 = s(s + 1)/2
///     and (i_a, j_a) the node's ξ.
///   Triangle (3, 6 nodes): ξ1 ≥ 0, ξ2 ≥ 0, ξ1 + ξ2 ≤ 1, corners ξ_a = (0,0), (1,0), (0,1),
///     barycentric λ = (1 − ξ1 − ξ2, ξ1, ξ2);
///     3 nodes: N = λ; 6 nodes: N_k = λ_k (2 λ_k − 1) at corner k, N_{3+k} = 4 λ_k λ_{k+1} at the
///     middle of edge k.
///   Edge k runs from corner k to corner (k + 1) mod c (c = 3 or 4 corners). It is the straight
///   segment between the corners for 3 and 4 nodes and the parabola through the corners and the
///   edge node for 6 and 9 nodes; in ξ it is always the straight segment ξ_k → ξ_{k+1}.
///   x_M(ξ) = Σ_a N_a(ξ) x_a,  a_α = ∂x_M/∂ξ_α,  unit outward normal n = a_1 × a_2 / |a_1 × a_2|.
/// Functions taking num_nodes throw std::invalid_argument unless it is 3, 4, 6 or 9.

/// The node counts of a master facet: 3, 6 (triangles) and 4, 9 (quadrilaterals).
template <int NM>
concept FacetNodeCount = NM == 3 || NM == 4 || NM == 6 || NM == 9;

/// Corners (= edges) of a facet of NM nodes: 3 for triangles, 4 for quadrilaterals.
template <int NM>
constexpr int facet_corners = (NM == 3 || NM == 6) ? 3 : 4;
/// Whether the facet of NM nodes is curved (quadratic shape functions).
template <int NM>
constexpr bool facet_is_quadratic = NM == 6 || NM == 9;

/// Node coordinates of a facet of NM nodes, one column per node.
template <int NM>
using FacetNodes = Eigen::Matrix<double, 3, NM>;
/// Node coordinates, one column per node, the number of nodes known at run time (3 × n).
using NodeCoordinates = Eigen::Matrix<double, 3, Eigen::Dynamic>;

namespace detail {
constexpr std::array<std::array<double, 2>, 4> quad_vertices{
    {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}};
constexpr std::array<std::array<double, 2>, 3> tri_vertices{{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}};
/// ξ of the nine nodes of the biquadratic quadrilateral (each coordinate −1, 0 or 1).
constexpr std::array<std::array<int, 2>, 9> quad9_nodes{
    {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}, {0, 0}}};

/// The 1D quadratic Lagrange polynomial of node i ∈ {−1, 0, 1} on [−1, 1] and its derivatives.
inline double lagrange2(int i, double s) {
  return i == 0 ? 1 - s * s : 0.5 * s * (s + i);
}
inline double lagrange2_d(int i, double s) { return i == 0 ? -2 * s : s + 0.5 * i; }
inline double lagrange2_dd(int i) { return i == 0 ? -2.0 : 1.0; }

/// ∂λ_k/∂ξ_α of the triangle's barycentric coordinates.
constexpr std::array<std::array<double, 2>, 3> barycentric_d{{{-1.0, -1.0}, {1.0, 0.0}, {0.0, 1.0}}};
inline std::array<double, 3> barycentric(const Eigen::Vector2d& xi) {
  return {1 - xi[0] - xi[1], xi[0], xi[1]};
}
}  // namespace detail

/// N_a(ξ), a = 0 … NM − 1 (also valid for ξ outside the reference facet).
template <int NM>
Eigen::Matrix<double, NM, 1> facet_shape_functions(const Eigen::Vector2d& xi) {
  static_assert(FacetNodeCount<NM>, "a master facet has 3, 4, 6 or 9 nodes");
  Eigen::Matrix<double, NM, 1> N;
  if constexpr (NM == 4) {
    for (int a = 0; a < 4; ++a)
      N[a] = 0.25 * (1 + detail::quad_vertices[a][0] * xi[0]) *
             (1 + detail::quad_vertices[a][1] * xi[1]);
  } else if constexpr (NM == 3) {
    N << 1 - xi[0] - xi[1], xi[0], xi[1];
  } else if constexpr (NM == 9) {
    for (int a = 0; a < 9; ++a)
      N[a] = detail::lagrange2(detail::quad9_nodes[a][0], xi[0]) *
             detail::lagrange2(detail::quad9_nodes[a][1], xi[1]);
  } else {
    const std::array<double, 3> l = detail::barycentric(xi);
    for (int k = 0; k < 3; ++k) {
      N[k] = l[k] * (2 * l[k] - 1);
      N[3 + k] = 4 * l[k] * l[(k + 1) % 3];
    }
  }
  return N;
}

/// ∂N_a/∂ξ_α: NM × 2.
template <int NM>
Eigen::Matrix<double, NM, 2> facet_shape_derivatives(const Eigen::Vector2d& xi) {
  static_assert(FacetNodeCount<NM>, "a master facet has 3, 4, 6 or 9 nodes");
  Eigen::Matrix<double, NM, 2> dN;
  if constexpr (NM == 4) {
    for (int a = 0; a < 4; ++a) {
      const double s1 = detail::quad_vertices[a][0], s2 = detail::quad_vertices[a][1];
      dN(a, 0) = 0.25 * s1 * (1 + s2 * xi[1]);
      dN(a, 1) = 0.25 * s2 * (1 + s1 * xi[0]);
    }
  } else if constexpr (NM == 3) {
    dN << -1, -1, 1, 0, 0, 1;
  } else if constexpr (NM == 9) {
    for (int a = 0; a < 9; ++a) {
      const int i = detail::quad9_nodes[a][0], j = detail::quad9_nodes[a][1];
      dN(a, 0) = detail::lagrange2_d(i, xi[0]) * detail::lagrange2(j, xi[1]);
      dN(a, 1) = detail::lagrange2(i, xi[0]) * detail::lagrange2_d(j, xi[1]);
    }
  } else {
    const std::array<double, 3> l = detail::barycentric(xi);
    const auto& d = detail::barycentric_d;
    for (int k = 0; k < 3; ++k) {
      const int m = (k + 1) % 3;
      for (int alpha = 0; alpha < 2; ++alpha) {
        dN(k, alpha) = (4 * l[k] - 1) * d[k][alpha];
        dN(3 + k, alpha) = 4 * (l[m] * d[k][alpha] + l[k] * d[m][alpha]);
      }
    }
  }
  return dN;
}

/// Second derivatives ∂²N_a/∂ξ1², ∂²N_a/∂ξ2², ∂²N_a/∂ξ1∂ξ2 as the columns of an NM × 3 matrix.
/// Linear triangle: 0; bilinear quadrilateral: only the mixed one, ¼ s1_a s2_a.
template <int NM>
Eigen::Matrix<double, NM, 3> facet_shape_second_derivatives(const Eigen::Vector2d& xi) {
  static_assert(FacetNodeCount<NM>, "a master facet has 3, 4, 6 or 9 nodes");
  Eigen::Matrix<double, NM, 3> d2N = Eigen::Matrix<double, NM, 3>::Zero();
  if constexpr (NM == 4) {
    for (int a = 0; a < 4; ++a)
      d2N(a, 2) = 0.25 * detail::quad_vertices[a][0] * detail::quad_vertices[a][1];
  } else if constexpr (NM == 9) {
    for (int a = 0; a < 9; ++a) {
      const int i = detail::quad9_nodes[a][0], j = detail::quad9_nodes[a][1];
      d2N(a, 0) = detail::lagrange2_dd(i) * detail::lagrange2(j, xi[1]);
      d2N(a, 1) = detail::lagrange2(i, xi[0]) * detail::lagrange2_dd(j);
      d2N(a, 2) = detail::lagrange2_d(i, xi[0]) * detail::lagrange2_d(j, xi[1]);
    }
  } else if constexpr (NM == 6) {
    const auto& d = detail::barycentric_d;
    constexpr int pairs[3][2] = {{0, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 3; ++k) {
      const int m = (k + 1) % 3;
      for (int c = 0; c < 3; ++c) {
        const int alpha = pairs[c][0], beta = pairs[c][1];
        d2N(k, c) = 4 * d[k][alpha] * d[k][beta];
        d2N(3 + k, c) = 4 * (d[m][alpha] * d[k][beta] + d[k][alpha] * d[m][beta]);
      }
    }
  }
  static_cast<void>(xi);
  return d2N;
}

/// Reference coordinates ξ_k of corner k (k taken mod the number of corners).
template <int NM>
Eigen::Vector2d facet_vertex_xi(int k) {
  static_assert(FacetNodeCount<NM>, "a master facet has 3, 4, 6 or 9 nodes");
  constexpr int c = facet_corners<NM>;
  const int j = ((k % c) + c) % c;
  if constexpr (c == 4) return {detail::quad_vertices[j][0], detail::quad_vertices[j][1]};
  return {detail::tri_vertices[j][0], detail::tri_vertices[j][1]};
}

/// The Hessian in ξ of F(ξ) = ½ |x_s − x_M(ξ)|² at r = x_s − x_M(ξ), a = [a_1 a_2] and the second
/// derivatives xdd = [x_,11 x_,22 x_,12]: H_αβ = a_α·a_β − r·x_,αβ.
inline Eigen::Matrix2d distance_hessian(const Eigen::Matrix<double, 3, 2>& a,
                                        const Eigen::Vector3d& r, const Eigen::Matrix3d& xdd) {
  Eigen::Matrix2d H = a.transpose() * a;
  H(0, 0) -= r.dot(xdd.col(0));
  H(1, 1) -= r.dot(xdd.col(1));
  H(0, 1) -= r.dot(xdd.col(2));
  H(1, 0) = H(0, 1);
  return H;
}

/// The same with the number of nodes at run time.
Eigen::VectorXd facet_shape_functions(int num_nodes, const Eigen::Vector2d& xi);
Eigen::Matrix<double, Eigen::Dynamic, 2> facet_shape_derivatives(int num_nodes,
                                                                 const Eigen::Vector2d& xi);
Eigen::Matrix<double, Eigen::Dynamic, 3> facet_shape_second_derivatives(int num_nodes,
                                                                        const Eigen::Vector2d& xi);
Eigen::Vector2d facet_vertex_xi(int num_nodes, int k);

}  // namespace hypercontact
