// Closest-point projection of a slave point onto one facet of a deformable master surface: a
// bilinear quadrilateral or a linear triangle (conventions of facet_shape.hpp), with the number
// of nodes NM a template parameter or, for a run-time facet (3 × n), dispatched on.
#pragma once

#include <Eigen/Core>
#include <hypercontact/facet_shape.hpp>
#include <hypercontact/obstacle.hpp>  // Feature

namespace hypercontact {

/// Unit outward normal a_1 × a_2 / |a_1 × a_2| at ξ of the facet with nodes x (3 × 3 or 3 × 4).
/// Throws std::invalid_argument if the facet is degenerate (see project_to_facet) or if
/// a_1 × a_2 vanishes at ξ (a folded quadrilateral).
template <int NM>
requires FacetNodeCount<NM> Eigen::Vector3d facet_normal(const FacetNodes<NM>& x,
                                                         const Eigen::Vector2d& xi);
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
template <int NM>
requires FacetNodeCount<NM> FacetProjection project_to_facet(const FacetNodes<NM>& master,
                                                             const Eigen::Vector3d& x_s);
/// The same for a facet whose number of nodes is known at run time.
FacetProjection project_to_facet(const NodeCoordinates& master, const Eigen::Vector3d& x_s);

extern template Eigen::Vector3d facet_normal<3>(const FacetNodes<3>&, const Eigen::Vector2d&);
extern template Eigen::Vector3d facet_normal<4>(const FacetNodes<4>&, const Eigen::Vector2d&);
extern template FacetProjection project_to_facet<3>(const FacetNodes<3>&, const Eigen::Vector3d&);
extern template FacetProjection project_to_facet<4>(const FacetNodes<4>&, const Eigen::Vector3d&);

}  // namespace hypercontact
