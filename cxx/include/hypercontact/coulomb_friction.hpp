// Penalty-regularised Coulomb friction of one slave node against a rigid obstacle: the return
// mapping of the trial traction onto the Coulomb cone in Cartesian components.
#pragma once

#include <hypercontact/obstacle.hpp>
#include <hypercontact/penetration.hpp>

namespace hypercontact {

/// Open: g > 0, no friction. Stick: Φ ≤ 0. Slip: Φ > 0 (Φ = |t_trial| − μ p_N).
enum class StickSlip { Open, Stick, Slip };

/// Traction after the return map and the branch taken (Stick or Slip, never Open).
struct ReturnMapResult {
  Eigen::Vector3d traction;
  StickSlip state;
};

/// Return map of a trial tangential traction onto the Coulomb cone of radius μ p_N:
///   Φ = |t_trial| − μ p_N;  Φ ≤ 0: t = t_trial (Stick);  Φ > 0: t = μ p_N m, m = t_trial/|t_trial|
///   (Slip). So |t| ≤ μ p_N always. μ = 0 is frictionless: Slip with t = 0, whatever t_trial.
/// Throws std::invalid_argument if t_trial is not finite, or p_N or μ is negative or not finite.
ReturnMapResult return_map(const Eigen::Vector3d& t_trial, double p_n, double mu);

/// Friction contribution of one slave node, and what the caller stores as history.
struct FrictionResult {
  Eigen::Vector3d residual;        ///< r_T = A t, added to the internal-force residual
  Eigen::Matrix3d tangent;         ///< K_T = ∂r_T/∂x (not symmetric in slip)
  Eigen::Vector3d traction;        ///< t, tangential traction per unit area: the next t_old
  Eigen::Vector3d slip_increment;  ///< Δs = (|t_trial| − μ p_N)/ε_T m in slip, 0 otherwise
  double dissipation;              ///< D = μ p_N |Δs| A = A t·Δs ≥ 0
  StickSlip state;
};

/// Coulomb friction of a slave node at x, tributary area A, against a rigid obstacle with
/// projection p (gap g, normal n, N = ∂n/∂x), with P = I − n ⊗ n:
///   p_N     = ε_N ⟨−g⟩  (closed for g ≤ 0, as normal_penalty),
///   w       = t_old + ε_T (x − ξ_old),
///   t_trial = P w = P t_old + ε_T P (x − ξ_old),
///   (t, state) = return_map(t_trial, p_N, μ),   r_T = A t.
/// History (never modified): ξ_old is the node's position at the end of the last converged step,
/// already carried with the obstacle's rigid motion by the caller; t_old is that step's traction.
/// t_old is projected onto the current tangent plane (P t_old), so a normal component (e.g. from
/// a normal that turned on a curved obstacle) is dropped rather than rotated.
/// Sign: −r_T is the force on the body; it opposes the motion relative to the obstacle.
/// Tangent, with T = ∂t_trial/∂x = ε_T P − (n·w) N − n ⊗ (Nᵀ w) (T = ε_T P on a flat face)
/// and ∂p_N/∂x = −ε_N n:
///   Stick: K_T = A T,
///   Slip:  K_T = A [μ m ⊗ ∂p_N/∂x + μ p_N/|t_trial| (I − m ⊗ m) T].
/// Open (g > 0): everything zero; the caller then stores t_old = 0.
/// μ = 0: r_T = 0 and K_T = 0; state Open if g > 0, else Slip with t = 0 and Δs = t_trial/ε_T.
/// With smoothing δ > 0, p_N = ε_N P(g) (the C¹ penetration of penetration.hpp), active where
/// g < δ, and ∂p_N/∂x = ε_N P'(g) n.
/// Throws std::invalid_argument if A < 0, ε_N ≤ 0, ε_T ≤ 0, μ < 0, δ < 0, or any input is not
/// finite.
FrictionResult coulomb_friction(const ObstacleProjection& p, const Eigen::Vector3d& x,
                                const Eigen::Vector3d& xi_old, const Eigen::Vector3d& t_old,
                                double area, double eps_n, double eps_t, double mu,
                                double smoothing = 0.0);

}  // namespace hypercontact
