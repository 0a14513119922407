// Assembly of the friction part of rigid-obstacle Coulomb contact into PETSc objects (its normal
// part is assemble_rigid's): the interface before evaluations (rigid_contact_friction.hpp) and
// assembly.hpp, kept as thin wrappers over them.
#pragma once

#include <petscmat.h>

#include <cstdint>
#include <hypercontact/rigid_contact_friction.hpp>
#include <span>
#include <vector>

namespace hypercontact {

/// Per-node and total output of one friction residual assembly (row-major n × 3 vectors).
struct RigidFrictionState {
  std::vector<double> traction;        ///< t_i, the next t_old when the step is committed
  std::vector<double> slip_increment;  ///< Δs_i of this step
  std::vector<double> dissipation;     ///< D_i = μ p_N |Δs_i| A_i of this step
  std::vector<std::int8_t> state;      ///< StickSlip as 0 open, 1 stick, 2 slip
  Eigen::Vector3d force;               ///< tangential force of the obstacle on the body, −Σ r_T
};

/// Adds r_T,i = A_i t_i (coulomb_friction) of every slave node into b[dofs(i, :)] (−1 skipped).
/// xi_old, t_old: n × 3 history of the last converged step (xi_old already moved with the
/// obstacle); multipliers (augmented Lagrangian, or empty): the friction's normal pressure is
/// then p_N = ⟨λ − ε_N g⟩, as the normal part's (evaluate_rigid_contact); other arguments as
/// assemble_rigid_residual. = add_residual(evaluate_rigid_friction(input without the normal
/// part), b).
RigidFrictionState assemble_rigid_friction_residual(
    const Obstacle& obstacle, std::span<const double> x, std::span<const double> area, double eps_n,
    double eps_t, double mu, std::span<const double> xi_old, std::span<const double> t_old,
    std::span<const std::int32_t> dofs, std::span<double> b,
    std::span<const double> multipliers = {}, double smoothing = 0.0);

/// Adds K_T,i = ∂r_T,i/∂x_i (not symmetric in slip) with MatSetValuesLocal (ADD_VALUES; rows and
/// columns of −1 dofs skipped). Arguments as assemble_rigid_friction_residual.
/// = add_tangent(evaluate_rigid_friction(input without the normal part), A).
void assemble_rigid_friction_tangent(const Obstacle& obstacle, std::span<const double> x,
                                     std::span<const double> area, double eps_n, double eps_t,
                                     double mu, std::span<const double> xi_old,
                                     std::span<const double> t_old,
                                     std::span<const std::int32_t> dofs, Mat A,
                                     std::span<const double> multipliers = {},
                                     double smoothing = 0.0);

}  // namespace hypercontact
