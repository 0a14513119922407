// Frictionless normal penalty contact of a slave point against one facet of a deformable master
// surface: the paper's 5-node element (one slave node against a bilinear facet) and, with the
// same code, Gauss-point-to-surface integration (x_s = Σ M_i x_i over a slave facet). The facet's
// number of nodes is a template parameter (fixed-size types, nothing on the heap); the overloads
// on NodeCoordinates dispatch on it at run time.
#pragma once

#include <Eigen/Core>
#include <hypercontact/facet_projection.hpp>
#include <hypercontact/penetration.hpp>
#include <hypercontact/surface_element_types.hpp>

namespace hypercontact {

/// Residual and tangent of one contact element, with its kinematics.
struct SurfaceContact {
  /// R = ∂W/∂x, 3 (ns + nm) entries: the ns slave nodes first, then the nm master nodes, each as
  /// (x, y, z). Added to the internal-force residual.
  ElementVector residual;
  ElementMatrix tangent;   ///< K = ∂R/∂x, same ordering, symmetric
  double gap;              ///< g = (x_s − x_M(ξ*)) · n
  double pressure;         ///< p_N = ε_N ⟨−g⟩ (augmented: ⟨λ_N − ε_N ĝ⟩)
  Eigen::Vector3d normal;  ///< n: unit outward facet normal at ξ*
  Eigen::Vector2d xi;      ///< ξ*
  Feature feature;         ///< as the projection
  int local_index;         ///< as the projection
  bool closed;             ///< g ≤ 0 (augmented: p_N > 0): the element is active
};

/// Contact element of a slave point x_s = Σ_i M_i x_i (i over the ns columns of `slave`; one
/// slave node: ns = 1, M = 1; a Gauss point of a slave facet: the facet's shape functions at the
/// point) against the master facet with nodes `master` (3 × 3, 4, 6 or 9, conventions of
/// facet_shape.hpp), weight w ≥ 0 (the slave point's reference area) and penalty ε_N > 0.
///
/// With x the stacked 3 (ns + nm) coordinates and P(ξ) = [M_1 I … M_ns I, −N_1 I … −N_nm I],
/// r = x_s − x_M(ξ*) = P(ξ*) x and g = r·n (n the outward facet normal at ξ*):
///   energy   W = w ε_N φ*(x) if g ≤ 0 (closed; g = 0 counts as closed), else W = 0, with
///            φ*(x) = min_ξ ½ |P(ξ) x|² over the feature found by the projection: the face
///            (ξ ∈ R² free), the line of edge k (ξ = ξ_k + t (ξ_{k+1} − ξ_k), t ∈ R free) or the
///            vertex (ξ fixed). On the face r = g n, so W = ½ w ε_N g².
///   residual R = ∂W/∂x = w ε_N Pᵀ r   (envelope theorem: ∂φ/∂ξ = 0 at ξ*),
///   tangent  K = ∂R/∂x = w ε_N [Pᵀ P − B T (Tᵀ H T)⁻¹ Tᵀ Bᵀ],
///            H = ∂²φ/∂ξ∂ξ: H_αβ = a_α·a_β − r·x_,αβ,  B = ∂²φ/∂x∂ξ: B_α = P_,αᵀ r − Pᵀ a_α,
///            T = I (face), T = ξ_{k+1} − ξ_k (edge k, a straight line in ξ; on a straight edge
///            Tᵀ H T = |x_{k+1} − x_k|², on a curved one it holds the edge's curvature), no
///            correction at a vertex (K = w ε_N Pᵀ P).
///   p_N = ε_N ⟨−g⟩; open (g > 0): R = 0, K = 0, p_N = 0.
/// K is exact and symmetric, with every curvature term (warped and curved facets, g ≠ 0).
/// Off the face (Edge, Vertex) r is not along n: the force w ε_N |r| acts along r, and W jumps
/// from ½ w ε_N |r|² to 0 where g changes sign with r ≠ 0.
///
/// `projection` must be project_to_facet(master, x_s) at the current coordinates.
/// Throws std::invalid_argument if w < 0, ε_N ≤ 0, sizes are inconsistent (weights.size() ≠
/// slave.cols() ≥ 1, master not 3 × 3, 4, 6 or 9), any input is not finite, the projection is
/// inconsistent (local index out of range) or the facet is degenerate; std::runtime_error if
/// the contact is closed at a face point where H is not positive definite (the slave point at a
/// centre of curvature of the facet: the tangent does not exist). Never returns NaN.
///
/// `touch` ≥ 0 widens "closed" to g ≤ touch: a caller passes a rounding-level length (e.g.
/// 1e-10 × the facet size) so that surfaces meshed exactly in touch (g = ±1e-17) are closed and
/// the tangent holds the contact stiffness from the first iteration.
///
/// Augmented Lagrangian: `lambda` = λ_N ≥ 0, the slave point's multiplier (a pressure, held
/// fixed). λ_N = 0 is the penalty element above, operation for operation. λ_N > 0: with the
/// signed distance ĝ (= g on the face; off it ĝ = s |r|, s = −1 if g ≤ 0 else +1, so that the
/// penalty energy is ½ w ε_N ĝ²) and p_N = λ_N − ε_N ĝ,
///   energy   W = w ⟨p_N⟩² / (2 ε_N)  (= ½ w ε_N ĝ² at λ_N = 0, ĝ ≤ 0),
///   active   p_N > 0, which includes gaps 0 < ĝ < λ_N/ε_N (touch is not used),
///   residual R = −w p_N ∇ĝ,  ∇ĝ = Pᵀ n (face), s Pᵀ r/|r| (edge, vertex),
///   tangent  K = w ε_N ∇ĝ ∇ĝᵀ − w p_N ∇²ĝ: the material part keeps ε_N, the geometric
///            (curvature) part −∇²ĝ is scaled by p_N where the penalty has ε_N ⟨−g⟩;
///            ∇²ĝ in closed form on the face (no division by g: exact at g = 0) and
///            s (∇²φ* − Pᵀ r̂ r̂ᵀ P)/|r| off it (∇²φ* = PᵀP + B dξ*/dx as above),
///   pressure p_N (reported as such; open: 0).
/// Off the face with r = 0 (the point exactly on an edge or vertex of the facet) ∇ĝ = Pᵀ n and
/// ∇²ĝ = 0 (ĝ is not differentiable there). Throws std::invalid_argument if λ_N < 0 or not finite.
///
/// Smoothing δ > 0 (penetration.hpp): the pressure is p_N = ε_N P(ĝ − λ_N/ε_N) with the C¹
/// penetration P, active where ĝ < λ_N/ε_N + δ, energy W = w ε_N Q(ĝ − λ_N/ε_N),
///   residual R = −w p_N ∇ĝ,   tangent K = −w (dp_N/dĝ) ∇ĝ ∇ĝᵀ − w p_N ∇²ĝ
/// (dp_N/dĝ = ε_N P' ∈ [−ε_N, 0]; the augmented formulas above with ε_N → −dp_N/dĝ).
template <int NM>
requires FacetNodeCount<NM> SurfaceContact
node_to_surface(const SlaveNodes& slave, const SlaveWeights& weights, const FacetNodes<NM>& master,
                const FacetProjection& projection, double w, double eps_n, double touch = 0.0,
                double lambda = 0.0, double smoothing = 0.0);
/// The same for a slave point and a facet of run-time sizes (ns ≤ 9; 3, 4, 6 or 9 facet nodes).
SurfaceContact node_to_surface(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                               const NodeCoordinates& master, const FacetProjection& projection,
                               double w, double eps_n, double touch = 0.0, double lambda = 0.0,
                               double smoothing = 0.0);

/// The same, projecting x_s onto the facet first (project_to_facet).
SurfaceContact node_to_surface(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                               const NodeCoordinates& master, double w, double eps_n,
                               double lambda = 0.0, double smoothing = 0.0);

/// The element energy W defined above (projecting x_s onto the facet first); closed for
/// g ≤ touch as node_to_surface; with λ_N > 0 the augmented W = w ⟨λ_N − ε_N ĝ⟩² / (2 ε_N).
double node_to_surface_energy(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                              const NodeCoordinates& master, double w, double eps_n,
                              double touch = 0.0, double lambda = 0.0, double smoothing = 0.0);

extern template SurfaceContact node_to_surface<3>(const SlaveNodes&, const SlaveWeights&,
                                                  const FacetNodes<3>&, const FacetProjection&,
                                                  double, double, double, double, double);
extern template SurfaceContact node_to_surface<4>(const SlaveNodes&, const SlaveWeights&,
                                                  const FacetNodes<4>&, const FacetProjection&,
                                                  double, double, double, double, double);
extern template SurfaceContact node_to_surface<6>(const SlaveNodes&, const SlaveWeights&,
                                                  const FacetNodes<6>&, const FacetProjection&,
                                                  double, double, double, double, double);
extern template SurfaceContact node_to_surface<9>(const SlaveNodes&, const SlaveWeights&,
                                                  const FacetNodes<9>&, const FacetProjection&,
                                                  double, double, double, double, double);

}  // namespace hypercontact
