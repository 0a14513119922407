// Penalty-regularised Coulomb friction of a slave point against a deformable master facet: the
// return mapping of the trial traction onto the Coulomb cone in Cartesian components, with the
// history carried as a material point of the master surface. The node counts of the current and
// the old facet are template parameters (fixed-size types, nothing on the heap); the overloads
// on NodeCoordinates dispatch on them at run time.
#pragma once

#include <Eigen/Core>
#include <hypercontact/coulomb_friction.hpp>  // StickSlip, return_map
#include <hypercontact/facet_projection.hpp>
#include <hypercontact/surface_element_types.hpp>

namespace hypercontact {

/// Friction contribution of one slave point against a master facet, and what the caller stores
/// as history.
struct SurfaceFriction {
  /// R, 3 (ns + nm + no) entries: the ns slave nodes, the nm nodes of the current facet, the no
  /// nodes of the old facet (always zero: no force acts there), each as (x, y, z).
  FrictionVector residual;
  /// K = ∂R/∂x, square, same ordering (columns of the old facet included); not symmetric.
  FrictionMatrix tangent;
  Eigen::Vector3d traction;        ///< t, tangential traction per unit area: the next t_old
  Eigen::Vector3d slip_increment;  ///< Δs = (t_trial − t)/ε_T: (|t_trial| − μ p_N)/ε_T m in slip
  double dissipation;              ///< D = μ p_N |Δs| w = w t·Δs ≥ 0
  StickSlip state;
  double gap;              ///< g = (x_s − x_M(ξ*))·n
  double pressure;         ///< p_N = ε_N ⟨−g⟩ (augmented: ⟨λ_N − ε_N g⟩)
  Eigen::Vector3d normal;  ///< n at ξ*
  Eigen::Vector2d xi;      ///< ξ*: with the facet, the next ξ_old
  Feature feature;
  int local_index;
};

/// Coulomb friction of the slave point x_s = Σ_i M_i x_i (as node_to_surface: one slave node, or
/// a Gauss point of a slave facet) against the current master facet `master` at its projection
/// ξ* (conventions of facet_projection.hpp), weight w ≥ 0, penalties ε_N, ε_T > 0, μ ≥ 0:
///   n       = unit outward normal of the current facet at ξ*,  P_T = I − n ⊗ n,
///   g       = (x_s − x_M(ξ*))·n,  p_N = ε_N ⟨−g⟩ (closed for g ≤ 0, as node_to_surface),
///   x_old   = Σ_b N_b(ξ_old) x_b^old  (the old facet's CURRENT node coordinates),
///   t_trial = P_T t_old + ε_T P_T (x_s − x_old),
///   (t, state) = return_map(t_trial, p_N, μ)  (coulomb_friction.hpp),
///   R       = w [M_1 t, …, M_ns t, −N_1(ξ*) t, …, −N_nm(ξ*) t, 0, …, 0] = w [P(ξ*)ᵀ t; 0].
/// Virtual work: δW = w t·(δx_s − δx_M|_ξ*) = w t·P(ξ*) δx, the work of the traction on the
/// slave point and of its reaction −t on the master material point under the slave point (ξ*
/// held fixed: eq. (14) takes the master's material velocity, with no convective term
/// t·a_α δξ^α). Σ M_i = 1 makes the forces balance. Sign as coulomb_friction: −R is the force on
/// the bodies; on the slave it opposes the motion relative to the master.
///
/// History (never modified): the master material point of the last converged step, i.e. the
/// facet it was on (`old_master`, its nodes at their CURRENT coordinates, 3 × 3 or 3 × 4) and
/// ξ_old there, and that step's traction t_old. x_old moves with the master, so a master that
/// only moves rigidly or deforms under a sticking slave point produces no trial traction, and a
/// slave point now over another facet keeps its history. The caller stores (facet, ξ*, t) of a
/// converged step; a first contact passes old facet = current facet, ξ_old = ξ*, t_old = 0. When
/// the old facet shares nodes with the current one (e.g. is the same facet), the caller adds the
/// old-facet columns of K to those of the shared nodes.
///
/// Tangent (exact, w.r.t. slave, current-facet and old-facet nodes): with dξ*/dx = −T (TᵀHT)⁻¹
/// Tᵀ Bᵀ from node_to_surface (zero at a vertex), dr = P dx − a_α dξ*^α,
/// da_α = Σ_a N_a,α dx_a + x_,αβ dξ*^β, dn = (I − n ⊗ n)/|a_1 × a_2| d(a_1 × a_2),
/// dg = n·dr + r·dn, dp_N = −ε_N dg, v = t_old + ε_T (x_s − x_old),
/// dt_trial = P_T dv − n (v·dn) − (n·v) dn:
///   Stick: dt = dt_trial;  Slip: dt = μ m dp_N + μ p_N/|t_trial| (I − m ⊗ m) dt_trial,
///   dR = w ([Pᵀ; 0] dt + [P_,αᵀ t; 0] dξ*^α).
/// Open (g > 0): everything zero, state Open; the caller then stores t_old = 0.
/// μ = 0: R = 0, K = 0; state Open if g > 0, else Slip with t = 0 and Δs = t_trial/ε_T.
/// Augmented Lagrangian: `lambda` = λ_N ≥ 0, the slave point's multiplier (held fixed). λ_N = 0
/// is the penalty above, operation for operation; λ_N > 0: the Coulomb cone uses the augmented
/// pressure p_N = λ_N − ε_N g, the point is open unless p_N > 0 (so a small positive gap can
/// stick or slip), dp_N = −ε_N dg as above (node_to_surface, given λ_N, is active wherever this
/// is: off the face its ĝ is ≥ g when g > 0).
/// Smoothing δ > 0: p_N = ε_N P(g − λ_N/ε_N) and dp_N = ε_N P' dg (penetration.hpp), active where
/// g < λ_N/ε_N + δ, as node_to_surface.
/// Throws std::invalid_argument if w < 0, ε_N ≤ 0, ε_T ≤ 0, μ < 0, λ_N < 0, sizes are
/// inconsistent, any input is not finite, the projection is inconsistent or a facet is
/// degenerate; std::runtime_error as node_to_surface at a centre of curvature. Never returns NaN.
template <int NM, int NO>
requires FacetNodeCount<NM> && FacetNodeCount<NO> SurfaceFriction surface_friction(
    const SlaveNodes& slave, const SlaveWeights& weights, const FacetNodes<NM>& master,
    const FacetProjection& projection, const FacetNodes<NO>& old_master,
    const Eigen::Vector2d& xi_old, const Eigen::Vector3d& t_old, double w, double eps_n,
    double eps_t, double mu, double lambda = 0.0, double smoothing = 0.0);
/// The same for a slave point and facets of run-time sizes (ns ≤ 9; 3 or 4 facet nodes, the old
/// facet 3 or 4 too; or 6 or 9 facet nodes, the old facet alike).
SurfaceFriction surface_friction(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                                 const NodeCoordinates& master, const FacetProjection& projection,
                                 const NodeCoordinates& old_master, const Eigen::Vector2d& xi_old,
                                 const Eigen::Vector3d& t_old, double w, double eps_n, double eps_t,
                                 double mu, double lambda = 0.0, double smoothing = 0.0);

/// The same, projecting x_s onto the current facet first (project_to_facet).
SurfaceFriction surface_friction(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                                 const NodeCoordinates& master, const NodeCoordinates& old_master,
                                 const Eigen::Vector2d& xi_old, const Eigen::Vector3d& t_old,
                                 double w, double eps_n, double eps_t, double mu,
                                 double lambda = 0.0, double smoothing = 0.0);

#define HYPERCONTACT_SURFACE_FRICTION(NM, NO)                                                \
  extern template SurfaceFriction surface_friction<NM, NO>(                                  \
      const SlaveNodes&, const SlaveWeights&, const FacetNodes<NM>&, const FacetProjection&, \
      const FacetNodes<NO>&, const Eigen::Vector2d&, const Eigen::Vector3d&, double, double, \
      double, double, double, double);
HYPERCONTACT_SURFACE_FRICTION(3, 3)
HYPERCONTACT_SURFACE_FRICTION(3, 4)
HYPERCONTACT_SURFACE_FRICTION(4, 3)
HYPERCONTACT_SURFACE_FRICTION(4, 4)
HYPERCONTACT_SURFACE_FRICTION(6, 6)
HYPERCONTACT_SURFACE_FRICTION(9, 9)
#undef HYPERCONTACT_SURFACE_FRICTION

}  // namespace hypercontact
