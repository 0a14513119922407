// The master facets of a deformable surface — bilinear quadrilaterals and linear triangles —
// their reference conventions and shape functions, with the number of nodes a template
// parameter (fixed-size Eigen types) or, for callers that know it only at run time, an argument.
#pragma once

#include <Eigen/Core>
#include <array>

namespace hypercontact {

/// Master facet conventions (NM = num_nodes = 4 or 3; nodes counter-clockwise seen from outside):
///   Quadrilateral: ξ ∈ [−1, 1]², vertices ξ_a = (−1,−1), (1,−1), (1,1), (−1,1),
///     N_a = ¼ (1 + s1_a ξ1)(1 + s2_a ξ2) with (s1_a, s2_a) = ξ_a.
///   Triangle: ξ1 ≥ 0, ξ2 ≥ 0, ξ1 + ξ2 ≤ 1, vertices ξ_a = (0,0), (1,0), (0,1),
///     N = (1 − ξ1 − ξ2, ξ1, ξ2).
///   Edge k runs from vertex k to vertex (k + 1) mod n; it is a straight segment in space for
///   both facets (a bilinear map is linear along an edge).
///   x_M(ξ) = Σ_a N_a(ξ) x_a,  a_α = ∂x_M/∂ξ_α,  unit outward normal n = a_1 × a_2 / |a_1 × a_2|.
/// Functions taking num_nodes throw std::invalid_argument unless it is 3 or 4.

/// The node counts of a master facet: 3 (triangle) and 4 (quadrilateral).
template <int NM>
concept FacetNodeCount = NM == 3 || NM == 4;

/// Node coordinates of a facet of NM nodes, one column per node.
template <int NM>
using FacetNodes = Eigen::Matrix<double, 3, NM>;
/// Node coordinates, one column per node, the number of nodes known at run time (3 × n).
using NodeCoordinates = Eigen::Matrix<double, 3, Eigen::Dynamic>;

namespace detail {
constexpr std::array<std::array<double, 2>, 4> quad_vertices{
    {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}};
constexpr std::array<std::array<double, 2>, 3> tri_vertices{{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}};
}  // namespace detail

/// N_a(ξ), a = 0 … NM − 1 (also valid for ξ outside the reference facet).
template <int NM>
Eigen::Matrix<double, NM, 1> facet_shape_functions(const Eigen::Vector2d& xi) {
  static_assert(NM == 3 || NM == 4, "a master facet has 3 or 4 nodes");
  Eigen::Matrix<double, NM, 1> N;
  if constexpr (NM == 4) {
    for (int a = 0; a < 4; ++a)
      N[a] = 0.25 * (1 + detail::quad_vertices[a][0] * xi[0]) *
             (1 + detail::quad_vertices[a][1] * xi[1]);
  } else {
    N << 1 - xi[0] - xi[1], xi[0], xi[1];
  }
  return N;
}

/// ∂N_a/∂ξ_α: NM × 2.
template <int NM>
Eigen::Matrix<double, NM, 2> facet_shape_derivatives(const Eigen::Vector2d& xi) {
  static_assert(NM == 3 || NM == 4, "a master facet has 3 or 4 nodes");
  Eigen::Matrix<double, NM, 2> dN;
  if constexpr (NM == 4) {
    for (int a = 0; a < 4; ++a) {
      const double s1 = detail::quad_vertices[a][0], s2 = detail::quad_vertices[a][1];
      dN(a, 0) = 0.25 * s1 * (1 + s2 * xi[1]);
      dN(a, 1) = 0.25 * s2 * (1 + s1 * xi[0]);
    }
  } else {
    dN << -1, -1, 1, 0, 0, 1;
  }
  return dN;
}

/// ∂²N_a/∂ξ1∂ξ2 (constant: ¼ s1_a s2_a for the quadrilateral, 0 for the triangle). The pure
/// second derivatives ∂²N_a/∂ξ1², ∂²N_a/∂ξ2² vanish for both facets.
template <int NM>
Eigen::Matrix<double, NM, 1> facet_shape_mixed_derivatives() {
  static_assert(NM == 3 || NM == 4, "a master facet has 3 or 4 nodes");
  Eigen::Matrix<double, NM, 1> d2N = Eigen::Matrix<double, NM, 1>::Zero();
  if constexpr (NM == 4)
    for (int a = 0; a < 4; ++a)
      d2N[a] = 0.25 * detail::quad_vertices[a][0] * detail::quad_vertices[a][1];
  return d2N;
}

/// Reference coordinates ξ_k of vertex k (k taken mod NM).
template <int NM>
Eigen::Vector2d facet_vertex_xi(int k) {
  static_assert(NM == 3 || NM == 4, "a master facet has 3 or 4 nodes");
  const int j = ((k % NM) + NM) % NM;
  if constexpr (NM == 4) return {detail::quad_vertices[j][0], detail::quad_vertices[j][1]};
  return {detail::tri_vertices[j][0], detail::tri_vertices[j][1]};
}

/// The same with the number of nodes at run time.
Eigen::VectorXd facet_shape_functions(int num_nodes, const Eigen::Vector2d& xi);
Eigen::Matrix<double, Eigen::Dynamic, 2> facet_shape_derivatives(int num_nodes,
                                                                 const Eigen::Vector2d& xi);
Eigen::VectorXd facet_shape_mixed_derivatives(int num_nodes);
Eigen::Vector2d facet_vertex_xi(int num_nodes, int k);

}  // namespace hypercontact
