// Normal penalty and Coulomb friction of a set of slave nodes against one rigid obstacle
// (PETSc-free): one projection per node, its normal part (rigid_contact.hpp) and its return
// map (coulomb_friction.hpp), with the element contributions.
#pragma once

#include <cstdint>
#include <hypercontact/coulomb_friction.hpp>
#include <hypercontact/rigid_contact.hpp>
#include <span>
#include <vector>

namespace hypercontact {

/// The normal contact's input plus each node's history and the friction law.
struct RigidFrictionInput {
  RigidContactInput contact;
  /// n × 3: ξ_old,i, node i's position at the last converged step, already carried with the
  /// obstacle's rigid motion by the caller.
  std::span<const double> xi_old;
  std::span<const double> t_old;  ///< n × 3: that step's traction t_old,i
  double eps_t;                   ///< tangential penalty ε_T > 0
  double mu;                      ///< friction coefficient μ ≥ 0
  /// true: each element holds the normal part and the friction of its node; false: the friction
  /// part alone (the normal part's state is still reported).
  bool with_normal = true;
};

/// The normal state of RigidContactState (`force` is the normal part) plus the friction of
/// every node (zero for an open node).
struct RigidFrictionEvaluation : RigidContactState {
  std::vector<double> traction;        ///< t_i (n × 3): the next t_old when the step is committed
  std::vector<double> slip_increment;  ///< Δs_i (n × 3) of this step
  std::vector<double> dissipation;     ///< D_i = μ p_N |Δs_i| A_i of this step
  std::vector<std::int8_t> state;      ///< StickSlip: 0 open, 1 stick, 2 slip
  Eigen::Vector3d friction_force;  ///< tangential force of the obstacle on the body, −Σ r_T,i
  Eigen::Vector3d total_force;     ///< force + friction_force
  /// Per active node: rows = columns = dofs(i, :), R = r_N,i + r_T,i and K = K_N,i + K_T,i
  /// (with_normal; else r_T,i and K_T,i), process-local numbering.
  ContactElements elements;
};

/// For every slave node i: one projection onto the obstacle, the normal part of
/// rigid_contact_node and, with the same shifted projection (p_N = ⟨λ_i − ε_N g_i⟩, smoothed
/// with δ), coulomb_friction(x_i, ξ_old,i, t_old,i, A_i, ε_N, ε_T, μ, δ). An active node (the
/// normal part closed, the friction Stick or Slip) adds its element. Throws as
/// evaluate_rigid_contact and coulomb_friction, and std::invalid_argument unless xi_old and t_old
/// hold 3 entries per node.
RigidFrictionEvaluation evaluate_rigid_friction(const RigidFrictionInput& in);

}  // namespace hypercontact
