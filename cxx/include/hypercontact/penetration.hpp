// The penetration function of the normal penalty: the Macaulay bracket ⟨−g⟩, optionally
// smoothed over a band |g| < δ so that the contact law (and Newton's tangent) has no kink.
#pragma once

#include <algorithm>

namespace hypercontact {

/// P(g) and its slope P'(g) = dP/dg.
struct Penetration {
  double value;  ///< P(g) ≥ 0: the pressure is ε_N P(g)
  double slope;  ///< P'(g) ∈ [−1, 0]
};

/// The penetration P(g) of a gap g, smoothed over the band |g| < δ (δ = smoothing ≥ 0):
///   g ≤ −δ:      P = −g,                P' = −1,
///   |g| < δ:     P = (δ − g)² / (4δ),    P' = −(δ − g) / (2δ),
///   g ≥ δ:       P = 0,                  P' = 0.
/// P and P' are continuous (P is C¹); P = ⟨−g⟩ outside the band, and inside it
/// 0 ≤ P − ⟨−g⟩ ≤ δ/4 (largest at g = 0). δ = 0 is the paper's Macaulay bracket: P = ⟨−g⟩,
/// P' = −1 for g ≤ 0 (closed at g = 0), 0 for g > 0.
/// The contact is active (exerts a pressure) where g < δ, or g ≤ 0 when δ = 0.
Penetration penetration(double gap, double smoothing);

/// Q(g) = ∫_g^∞ P(s) ds, the penalty energy per unit ε_N and area (Q' = −P):
///   g ≤ −δ: g²/2 + δ²/6;  |g| < δ: (δ − g)³/(12δ);  g ≥ δ: 0.
double penetration_energy(double gap, double smoothing);

/// Whether the gap is in the active part of the law (P > 0, or g ≤ 0 when δ = 0).
inline bool penetration_active(double gap, double smoothing) {
  return smoothing > 0 ? gap < smoothing : gap <= 0;
}

}  // namespace hypercontact

namespace hypercontact {

/// Normal pressure of a slave point at gap g, penalty ε_N > 0, augmented-Lagrangian multiplier
/// λ ≥ 0 (0: pure penalty) and smoothing δ ≥ 0, and its slope dp_N/dg:
///   δ > 0:  p_N = ε_N P(g − λ/ε_N),   dp_N/dg = ε_N P'(g − λ/ε_N),   active where g < λ/ε_N + δ;
///   δ = 0:  p_N = ⟨λ − ε_N g⟩ (computed as λ − ε_N g, or ε_N ⟨−g⟩ when λ = 0), dp_N/dg = −ε_N,
///           active where λ − ε_N g > 0 (λ > 0), g ≤ 0 (λ = 0).
/// Inactive: p_N = 0 and slope 0.
struct NormalPressure {
  double value;
  double slope;
  bool active;
};

inline NormalPressure normal_pressure(double gap, double eps_n, double lambda, double smoothing) {
  if (smoothing > 0) {
    const double shifted = gap - lambda / eps_n;
    if (!penetration_active(shifted, smoothing)) return {0.0, 0.0, false};
    const Penetration pen = penetration(shifted, smoothing);
    return {eps_n * pen.value, eps_n * pen.slope, true};
  }
  if (lambda > 0) {
    const double p = lambda - eps_n * gap;
    return p > 0 ? NormalPressure{p, -eps_n, true} : NormalPressure{0.0, 0.0, false};
  }
  return gap <= 0 ? NormalPressure{eps_n * std::max(0.0, -gap), -eps_n, true}
                  : NormalPressure{0.0, 0.0, false};
}

}  // namespace hypercontact
