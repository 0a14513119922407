// Coulomb friction against a deformable master surface (PETSc-free): per slave point the pairing
// and normal element of surface_contact.hpp plus the return map of surface_friction with the
// point's history, in one evaluation.
#pragma once

#include <hypercontact/surface_contact.hpp>

namespace hypercontact {

/// Per slave point and total output: the pairing and normal part as SurfaceContactState, plus
/// the friction of each point (zero for a point that is not closed).
struct SurfaceFrictionState : SurfaceContactState {
  std::vector<double>
      traction;  ///< t (3 per point): the next t_old; the master pulls the slave by −t
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

/// The state and, for every closed point, its element: rows = the dofs of [slave nodes, current
/// facet], columns = those and the old facet's (duplicates of shared nodes add up),
/// R = normal + friction residual, K = normal tangent (its columns) + friction tangent; global
/// numbering.
struct SurfaceFrictionEvaluation : SurfaceFrictionState {
  ContactElements elements;
};

/// Evaluates every slave point as evaluate_surface_contact; a closed point (Paired, g ≤ touch)
/// keeps the normal element (node_to_surface) plus the friction of surface_friction against its
/// current facet at ξ* with the history (old facet's CURRENT nodes at ξ_old, t_old). A point
/// without history (old_facet = −1) uses old facet = current facet, ξ_old = ξ*, t_old = 0: its
/// trial traction ε_T P_T (x_s − x_M(ξ*)) vanishes, so it keeps its (zero) friction residual but
/// no friction tangent (the consistent derivative of a residual that is zero for every x).
/// Throws as evaluate_surface_contact, and std::invalid_argument if the history is inconsistent.
SurfaceFrictionEvaluation evaluate_surface_friction(const SurfaceFrictionInput& in);

}  // namespace hypercontact
