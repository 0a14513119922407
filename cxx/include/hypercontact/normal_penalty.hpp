// Frictionless normal penalty at one slave node ("nodal integration").
#pragma once

#include <hypercontact/obstacle.hpp>
#include <hypercontact/penetration.hpp>

namespace hypercontact {

/// Contribution of one slave node to the residual and the tangent.
struct NodalContact {
  Eigen::Vector3d residual;  ///< r = ∂W/∂x, added to the internal-force residual
  Eigen::Matrix3d tangent;   ///< K = ∂r/∂x
  double pressure;           ///< p_N = ε_N ⟨−g⟩ ≥ 0
  bool closed;               ///< g ≤ 0 (g < δ when smoothed)
};

/// Penalty energy of a slave node with tributary area A and penalty ε_N:
///   W = ½ A ε_N ⟨−g⟩²,   ⟨·⟩ the Macaulay bracket.
/// Throws std::invalid_argument if A < 0 or ε_N ≤ 0.
double normal_penalty_energy(const ObstacleProjection& p, double area, double eps_n,
                             double smoothing = 0.0);

/// Residual and tangent of W. The contact is closed when g ≤ 0 (g = 0 counts as closed, so
/// the tangent is present at first touch); then
///   r = ∂W/∂x = A ε_N g n,
///   K = ∂r/∂x = A ε_N (n ⊗ n + g ∂n/∂x),
///   p_N = −ε_N g,
/// and r = 0, K = 0, p_N = 0 when open (g > 0).
/// Throws std::invalid_argument if A < 0 or ε_N ≤ 0.
/// With smoothing δ > 0 the bracket is the C¹ penetration P(g) of penetration.hpp:
///   r = −A ε_N P(g) n,   K = −A ε_N (P'(g) n ⊗ n + P(g) ∂n/∂x),   p_N = ε_N P(g),
/// active (closed) where g < δ; δ = 0 gives the formulas above.
NodalContact normal_penalty(const ObstacleProjection& p, double area, double eps_n,
                            double smoothing = 0.0);

}  // namespace hypercontact
