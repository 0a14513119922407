// The element contributions of one contact evaluation, stored flat: for every active slave point
// its dof indices, element residual vector and element tangent matrix. The assembly library
// (assembly.hpp) inserts them into PETSc objects; a code with its own linear algebra reads them.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

namespace hypercontact {

/// How the dof indices of a set of elements number the unknowns.
enum class DofNumbering : std::int32_t {
  Local = 0,   ///< process-local (owned + ghost) indices, as a local array or MatSetValuesLocal
  Global = 1,  ///< global PETSc indices, as VecSetValues / MatSetValues
};

/// Row-major dense block, the storage order of ContactElements::tangent.
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Element contributions, one element per active slave point, in flat arrays:
///   element e has the rows   row_dofs[row_offsets[e] … row_offsets[e + 1]),
///             the residual   residual[row_offsets[e] … row_offsets[e + 1]) (R_e, aligned with
///                            its rows),
///             the columns    column_dofs[column_offsets[e] … column_offsets[e + 1]),
///             the tangent    K_e = ∂R_e/∂x_columns, row-major rows × columns, at
///                            tangent[tangent_offsets[e] …).
/// The global system gets b[row_dofs] += R_e and A[row_dofs, column_dofs] += K_e. A dof −1 is
/// constrained: the assembly skips its row and column, the entries stay stored. A dof that
/// appears twice among the columns (a node in two roles) receives the sum of its columns.
struct ContactElements {
  DofNumbering numbering = DofNumbering::Local;
  std::vector<std::int32_t> point;               ///< slave point (node) of each element
  std::vector<std::int32_t> row_offsets{0};      ///< size() + 1 entries
  std::vector<std::int32_t> column_offsets{0};   ///< size() + 1 entries
  std::vector<std::int64_t> tangent_offsets{0};  ///< size() + 1 entries
  std::vector<std::int32_t> row_dofs;
  std::vector<std::int32_t> column_dofs;
  std::vector<double> residual;
  std::vector<double> tangent;

  /// The number of elements.
  std::size_t size() const { return point.size(); }
  std::span<const std::int32_t> rows(std::size_t e) const;
  std::span<const std::int32_t> columns(std::size_t e) const;
  std::span<const double> element_residual(std::size_t e) const;
  /// K_e as a num_rows × num_columns row-major map.
  Eigen::Map<const RowMajorMatrix> element_tangent(std::size_t e) const;

  /// Storage of a new element, to be filled in (valid until the next append).
  struct Slot {
    std::span<std::int32_t> rows;
    std::span<std::int32_t> columns;
    Eigen::Map<Eigen::VectorXd> residual;
    Eigen::Map<RowMajorMatrix> tangent;
  };
  /// Appends element number size() for slave point `point` with zero residual and tangent.
  Slot append(std::int32_t point, int num_rows, int num_columns);
};

}  // namespace hypercontact
