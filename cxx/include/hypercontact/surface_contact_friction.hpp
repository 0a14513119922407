// Coulomb friction against a deformable master surface, PETSc-free part: the input (the normal
// contact's plus each slave point's history) and the per-point state of its evaluation.
#pragma once

#include <hypercontact/surface_contact.hpp>

namespace hypercontact {

/// Per slave point and total output: the pairing and normal part as SurfaceContactState, plus
/// the friction of each point (zero for a point that is not closed).
struct SurfaceFrictionState : SurfaceContactState {
  std::vector<double> traction;        ///< t (3 per point): the next t_old; the master pulls the slave by −t
  std::vector<double> slip_increment;  ///< Δs (3 per point)
  std::vector<double> dissipation;     ///< D = w t·Δs ≥ 0 (per point, not per area)
  std::vector<std::int32_t> stick;     ///< StickSlip: 0 open, 1 stick, 2 slip
  /// force of the master on the slave body, normal and tangential (`force` is the normal part)
  Eigen::Vector3d total_force;
};

/// The history of every slave point: the master material point of the last converged step,
/// (old_facet, ξ_old), and that step's traction t_old. old_facet = −1: no history.
struct SurfaceFrictionInput {
  SurfaceContactInput contact;
  std::span<const std::int32_t> old_facet;  ///< np
  std::span<const double> xi_old;           ///< 2 np
  std::span<const double> t_old;            ///< 3 np
  double eps_t;
  double mu;
};

}  // namespace hypercontact
