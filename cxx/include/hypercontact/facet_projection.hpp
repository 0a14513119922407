// Closest-point projection of a slave point onto one facet of a deformable master surface:
// a bilinear quadrilateral or a linear triangle (SPEC §1).
#pragma once

#include <Eigen/Core>
#include <hypercontact/obstacle.hpp>  // Feature

namespace hypercontact {

/// Node coordinates, one column per node (3 × n).
using NodeCoordinates = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// Master facet conventions (num_nodes = 4 or 3; nodes counter-clockwise seen from outside):
///   Quadrilateral: ξ ∈ [−1, 1]², vertices ξ_a = (−1,−1), (1,−1), (1,1), (−1,1),
///     N_a = ¼ (1 + s1_a ξ1)(1 + s2_a ξ2) with (s1_a, s2_a) = ξ_a.
///   Triangle: ξ1 ≥ 0, ξ2 ≥ 0, ξ1 + ξ2 ≤ 1, vertices ξ_a = (0,0), (1,0), (0,1),
///     N = (1 − ξ1 − ξ2, ξ1, ξ2).
///   Edge k runs from vertex k to vertex (k + 1) mod n; it is a straight segment in space for
///   both facets (a bilinear map is linear along an edge).
///   x_M(ξ) = Σ_a N_a(ξ) x_a,  a_α = ∂x_M/∂ξ_α,  unit outward normal n = a_1 × a_2 / |a_1 × a_2|.
/// Functions taking num_nodes throw std::invalid_argument unless it is 3 or 4.

/// N_a(ξ), a = 0 … num_nodes − 1 (also valid for ξ outside the reference facet).
Eigen::VectorXd facet_shape_functions(int num_nodes, const Eigen::Vector2d& xi);

/// ∂N_a/∂ξ_α: num_nodes × 2.
Eigen::Matrix<double, Eigen::Dynamic, 2> facet_shape_derivatives(int num_nodes,
                                                                 const Eigen::Vector2d& xi);

/// ∂²N_a/∂ξ1∂ξ2 (constant: ¼ s1_a s2_a for the quadrilateral, 0 for the triangle). The pure
/// second derivatives ∂²N_a/∂ξ1², ∂²N_a/∂ξ2² vanish for both facets.
Eigen::VectorXd facet_shape_mixed_derivatives(int num_nodes);

/// Reference coordinates ξ_k of vertex k (k taken mod num_nodes).
Eigen::Vector2d facet_vertex_xi(int num_nodes, int k);

/// Unit outward normal a_1 × a_2 / |a_1 × a_2| at ξ of the facet with nodes x (3 × 3 or 3 × 4).
/// Throws std::invalid_argument if the facet is degenerate (see project_to_facet) or if
/// a_1 × a_2 vanishes at ξ (a folded quadrilateral).
Eigen::Vector3d facet_normal(const NodeCoordinates& x, const Eigen::Vector2d& xi);

/// Result of project_to_facet.
struct FacetProjection {
  Eigen::Vector2d xi;      ///< ξ* of the closest point (on the edge / at the vertex if not Face)
  Feature feature;         ///< Face: ξ* inside; Edge: ξ* on edge local_index; Vertex: ξ* = ξ_k
  int local_index;         ///< edge k (vertex k → k + 1) or vertex k; −1 for Face
  Eigen::Vector3d point;   ///< x_M(ξ*)
  double distance;         ///< |x_s − x_M(ξ*)|
  Eigen::Vector3d normal;  ///< unit outward facet normal at ξ* (at the clamped ξ* off the face)
  int iterations;          ///< Newton iterations, summed over the starts
  bool converged;          ///< every Newton start ended at a stationary point or left the facet
};

/// Closest point of the facet with nodes `master` (3 × 4 quadrilateral or 3 × 3 triangle) to
/// x_s: minimises F(ξ) = ½ |x_s − x_M(ξ)|² over the reference facet.
///
/// Face: safeguarded Newton on F over ξ ∈ R², exact Hessian H_αβ = a_α·a_β − r·x_,αβ
/// (r = x_s − x_M); a step −H⁻¹∇F when H is positive definite, else the gradient step
/// −∇F / (|a_1|² + |a_2|²); Armijo backtracking unless the Newton step is already small; a
/// quadrilateral's start is abandoned when ξ leaves [−2, 2]². Starts: the centroid, and for the
/// quadrilateral also (±½, ±½), so that every local minimum of a warped facet is found. A
/// stationary point with H positive semi-definite and ξ inside the facet (to 1e-10) is a Face
/// candidate.
/// Boundary: the exact closest point of each straight edge, x_k + t (x_{k+1} − x_k) with
/// t = clamp((x_s − x_k)·(x_{k+1} − x_k)/|x_{k+1} − x_k|², 0, 1); t = 0 or 1 is Vertex k or
/// k + 1, else Edge k with ξ* = (1 − t) ξ_k + t ξ_{k+1}, so that ξ* lies exactly on the edge.
/// The closest candidate wins; a Face candidate wins ties (distance within 1e-12 L, L the
/// longest edge) over the boundary, an Edge wins exact ties over a Vertex.
///
/// Throws std::invalid_argument if master has neither 3 nor 4 columns, any input is not finite,
/// or the facet is degenerate: zero area (|½ d_1 × d_2| ≤ 1e-12 L² with d the diagonals of the
/// quadrilateral, the two edges from node 0 of the triangle), a zero corner (two coincident
/// nodes or two collinear adjacent edges of a quadrilateral), or a_1 × a_2 = 0 at ξ* (folded).
/// The result is never NaN.
FacetProjection project_to_facet(const NodeCoordinates& master, const Eigen::Vector3d& x_s);

}  // namespace hypercontact
