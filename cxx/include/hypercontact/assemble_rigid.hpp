// Assembly of rigid-obstacle normal penalty contact into PETSc objects, one call for the residual
// and one for the tangent (each evaluates every node): the interface before evaluations
// (rigid_contact.hpp) and assembly.hpp, kept as thin wrappers over them.
#pragma once

#include <petscmat.h>

#include <cstdint>
#include <hypercontact/rigid_contact.hpp>
#include <span>
#include <vector>

namespace hypercontact {

/// Adds the contact residual r_i = A_i ε_N g_i n_i of every closed node into b:
///   b[dofs(i, k)] += r_i[k]   for dofs(i, k) ≥ 0.
/// x: n × 3 current coordinates; area: n; dofs: n × 3 process-local unblocked dof indices,
/// −1 marking a constrained dof that is skipped; b: local array (owned + ghost) of the residual.
/// multipliers: augmented-Lagrangian pressures per node, or empty (see rigid_contact_node).
/// = add_residual(evaluate_rigid_contact(input), b). Throws std::out_of_range if a dof is
/// ≥ b.size(), otherwise as evaluate_rigid_contact.
RigidContactState assemble_rigid_residual(const Obstacle& obstacle, std::span<const double> x,
                                          std::span<const double> area, double eps_n,
                                          std::span<const std::int32_t> dofs, std::span<double> b,
                                          std::span<const double> multipliers = {},
                                          double smoothing = 0.0);

/// Adds the contact tangent K_i = A_i ε_N (n_i ⊗ n_i + g_i ∂n_i/∂x) of every closed node:
///   MatSetValuesLocal(A, 3, dofs(i, :), 3, dofs(i, :), K_i, ADD_VALUES);
/// PETSc skips the rows and columns of negative (constrained) dofs. A needs a local-to-global
/// mapping; MatAssemblyBegin/End is left to the caller. Arguments as assemble_rigid_residual.
/// = add_tangent(evaluate_rigid_contact(input), A). Throws std::runtime_error if PETSc reports
/// an error.
void assemble_rigid_tangent(const Obstacle& obstacle, std::span<const double> x,
                            std::span<const double> area, double eps_n,
                            std::span<const std::int32_t> dofs, Mat A,
                            std::span<const double> multipliers = {}, double smoothing = 0.0);

}  // namespace hypercontact
