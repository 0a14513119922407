// Closest-point projection of a slave point onto one facet of a deformable master surface: a
// bilinear or biquadratic quadrilateral or a linear or quadratic triangle (conventions of
// facet_shape.hpp), with the number of nodes NM a template parameter or, for a run-time facet
// (3 × n), dispatched on.
#pragma once

#include <Eigen/Core>
#include <hypercontact/facet_shape.hpp>
#include <hypercontact/obstacle.hpp>  // Feature

namespace hypercontact {

/// Unit outward normal a_1 × a_2 / |a_1 × a_2| at ξ of the facet with nodes x (3 × 3, 4, 6, 9).
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

/// Closest point of the facet with nodes `master` (3 × 4 or 3 × 9 quadrilateral, 3 × 3 or 3 × 6
/// triangle) to x_s: minimises F(ξ) = ½ |x_s − x_M(ξ)|² over the reference facet.
///
/// Face: safeguarded Newton on F over ξ ∈ R², exact Hessian H_αβ = a_α·a_β − r·x_,αβ
/// (r = x_s − x_M; every x_,αβ of a curved facet, only x_,12 of a bilinear one); a step −H⁻¹∇F
/// when H is positive definite, else the gradient step −∇F / (|a_1|² + |a_2|²); Armijo
/// backtracking unless the Newton step is already small; a start is abandoned when ξ leaves
/// [−2, 2]² (quadrilaterals) or lies more than one edge beyond a side (curved triangles).
/// Starts: the centroid of a linear triangle; (0, 0) and (±½, ±½) for quadrilaterals;
/// (⅓, ⅓), (0.6, 0.2), (0.2, 0.6), (0.2, 0.2) for the 6-node triangle — so that every local
/// minimum of a warped or curved facet is found. A stationary point with H positive
/// semi-definite and ξ inside the facet (to 1e-10) is a Face candidate.
/// Boundary: the exact closest point of each edge. Straight edges: x_k + t (x_{k+1} − x_k) with
/// t = clamp((x_s − x_k)·(x_{k+1} − x_k)/|x_{k+1} − x_k|², 0, 1). Curved edges (the parabola
/// through x_k, the edge node and x_{k+1}): the closest of t = 0, 1 and the minima in (0, 1) of
/// the quartic distance², whose derivative (a cubic) is bracketed between its turning points and
/// bisected. t = 0 or 1 is Vertex k or k + 1, else Edge k with ξ* = (1 − t) ξ_k + t ξ_{k+1}, so
/// that ξ* lies exactly on the edge.
/// The closest candidate wins; a Face candidate wins ties (distance within 1e-12 L, L the
/// longest edge) over the boundary, an Edge wins exact ties over a Vertex.
///
/// Throws std::invalid_argument if master has not 3, 4, 6 or 9 columns, any input is not finite,
/// or the facet is degenerate: zero area of its corners (|½ d_1 × d_2| ≤ 1e-12 L² with d the
/// diagonals of the quadrilateral, the two edges from corner 0 of the triangle; L the longest
/// corner-to-corner chord), a zero corner (two coincident corners or two collinear adjacent
/// chords of a quadrilateral), or a_1 × a_2 = 0 at ξ* (folded).
/// The result is never NaN.
template <int NM>
requires FacetNodeCount<NM> FacetProjection project_to_facet(const FacetNodes<NM>& master,
                                                             const Eigen::Vector3d& x_s);
/// The same for a facet whose number of nodes is known at run time.
FacetProjection project_to_facet(const NodeCoordinates& master, const Eigen::Vector3d& x_s);

extern template Eigen::Vector3d facet_normal<3>(const FacetNodes<3>&, const Eigen::Vector2d&);
extern template Eigen::Vector3d facet_normal<4>(const FacetNodes<4>&, const Eigen::Vector2d&);
extern template Eigen::Vector3d facet_normal<6>(const FacetNodes<6>&, const Eigen::Vector2d&);
extern template Eigen::Vector3d facet_normal<9>(const FacetNodes<9>&, const Eigen::Vector2d&);
extern template FacetProjection project_to_facet<3>(const FacetNodes<3>&, const Eigen::Vector3d&);
extern template FacetProjection project_to_facet<4>(const FacetNodes<4>&, const Eigen::Vector3d&);
extern template FacetProjection project_to_facet<6>(const FacetNodes<6>&, const Eigen::Vector3d&);
extern template FacetProjection project_to_facet<9>(const FacetNodes<9>&, const Eigen::Vector3d&);

}  // namespace hypercontact
