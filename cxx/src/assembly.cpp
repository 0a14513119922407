#include <hypercontact/assembly.hpp>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace hypercontact {

namespace {

/// The dofs as PetscInt: the int32 storage itself when PetscInt is 32-bit, else a copy.
const PetscInt* petsc_indices(std::span<const std::int32_t> dofs, std::vector<PetscInt>& buffer) {
  if constexpr (std::is_same_v<PetscInt, std::int32_t>) {
    return dofs.data();
  } else {
    buffer.assign(dofs.begin(), dofs.end());
    return buffer.data();
  }
}

[[noreturn]] void petsc_failed(const char* who, const char* call, PetscErrorCode err,
                               std::int32_t point, const char* hint = "") {
  throw std::runtime_error(std::string(who) + ": " + call + " failed (PETSc error " +
                           std::to_string(err) + ") for slave point " + std::to_string(point) +
                           hint);
}

}  // namespace

void add_residual(const ContactElements& elements, std::span<double> b_local) {
  if (elements.numbering != DofNumbering::Local)
    throw std::invalid_argument(
        "add_residual: global dof numbers cannot index a process-local array (pass a Vec)");
  for (const std::int32_t dof : elements.row_dofs)
    if (dof >= static_cast<std::int64_t>(b_local.size()))
      throw std::out_of_range("add_residual: dof " + std::to_string(dof) +
                              " outside the local residual array of size " +
                              std::to_string(b_local.size()));
  for (std::size_t k = 0; k < elements.row_dofs.size(); ++k)
    if (const std::int32_t dof = elements.row_dofs[k]; dof >= 0)
      b_local[dof] += elements.residual[k];
}

void add_residual(const ContactElements& elements, Vec b) {
  if (const PetscErrorCode err = VecSetOption(b, VEC_IGNORE_NEGATIVE_INDICES, PETSC_TRUE))
    throw std::runtime_error("add_residual: VecSetOption failed (PETSc error " +
                             std::to_string(err) + ")");
  const bool local = elements.numbering == DofNumbering::Local;
  std::vector<PetscInt> buffer;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const std::span<const std::int32_t> rows = elements.rows(e);
    const PetscInt n = static_cast<PetscInt>(rows.size());
    const PetscInt* idx = petsc_indices(rows, buffer);
    const PetscScalar* values = elements.element_residual(e).data();
    const PetscErrorCode err = local ? VecSetValuesLocal(b, n, idx, values, ADD_VALUES)
                                     : VecSetValues(b, n, idx, values, ADD_VALUES);
    if (err)
      petsc_failed("add_residual", local ? "VecSetValuesLocal" : "VecSetValues", err,
                   elements.point[e]);
  }
}

void add_tangent(const ContactElements& elements, Mat A) {
  const bool local = elements.numbering == DofNumbering::Local;
  std::vector<PetscInt> row_buffer, column_buffer;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const std::span<const std::int32_t> rows = elements.rows(e), columns = elements.columns(e);
    const PetscInt m = static_cast<PetscInt>(rows.size()),
                   n = static_cast<PetscInt>(columns.size());
    const PetscInt* r = petsc_indices(rows, row_buffer);
    const PetscInt* c = petsc_indices(columns, column_buffer);
    const PetscScalar* values = elements.element_tangent(e).data();
    const PetscErrorCode err = local ? MatSetValuesLocal(A, m, r, n, c, values, ADD_VALUES)
                                     : MatSetValues(A, m, r, n, c, values, ADD_VALUES);
    if (err)
      petsc_failed("add_tangent", local ? "MatSetValuesLocal" : "MatSetValues", err,
                   elements.point[e], " (is the coupling in the matrix pattern?)");
  }
}

}  // namespace hypercontact
