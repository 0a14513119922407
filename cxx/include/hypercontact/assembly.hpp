// Insertion of a contact evaluation's element contributions (contact_elements.hpp) into a
// residual and a tangent: a process-local array, a PETSc Vec, a PETSc Mat.
#pragma once

#include <petscmat.h>
#include <petscvec.h>

#include <concepts>
#include <hypercontact/contact_elements.hpp>
#include <span>

namespace hypercontact {

/// b_local[row dof] += R_e for every element (ContactElements' conventions; rows −1 skipped).
/// b_local: a process-local array (owned + ghost entries, e.g. of VecGetArray on a ghosted
/// vector). Throws std::invalid_argument unless the numbering is Local, std::out_of_range (before
/// adding anything) if a dof is ≥ b_local.size().
void add_residual(const ContactElements& elements, std::span<double> b_local);

/// VecSetValues (Global numbering) or VecSetValuesLocal (Local; b needs a local-to-global
/// mapping) of every element's R_e with ADD_VALUES; rows −1 skipped (this sets
/// VEC_IGNORE_NEGATIVE_INDICES on b). VecAssemblyBegin/End is the caller's. Throws
/// std::runtime_error naming the slave point if PETSc reports an error.
void add_residual(const ContactElements& elements, Vec b);

/// MatSetValues (Global) or MatSetValuesLocal (Local; A needs a local-to-global mapping) of
/// every element's K_e with ADD_VALUES; rows and columns −1 skipped. The coupling must be in A's
/// pattern unless A allows new nonzeros. MatAssemblyBegin/End is the caller's. Throws
/// std::runtime_error naming the slave point if PETSc reports an error.
void add_tangent(const ContactElements& elements, Mat A);

/// An evaluation with element contributions (RigidContactEvaluation, RigidFrictionEvaluation,
/// SurfaceContactEvaluation, SurfaceFrictionEvaluation).
template <typename E>
concept ContactEvaluation = requires(const E& e) {
  { e.elements } -> std::convertible_to<const ContactElements&>;
};

template <ContactEvaluation E>
void add_residual(const E& evaluation, std::span<double> b_local) {
  add_residual(evaluation.elements, b_local);
}
template <ContactEvaluation E>
void add_residual(const E& evaluation, Vec b) {
  add_residual(evaluation.elements, b);
}
template <ContactEvaluation E>
void add_tangent(const E& evaluation, Mat A) {
  add_tangent(evaluation.elements, A);
}

}  // namespace hypercontact
