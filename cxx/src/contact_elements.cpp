#include <hypercontact/contact_elements.hpp>

namespace hypercontact {

std::span<const std::int32_t> ContactElements::rows(std::size_t e) const {
  return {row_dofs.data() + row_offsets[e],
          static_cast<std::size_t>(row_offsets[e + 1] - row_offsets[e])};
}

std::span<const std::int32_t> ContactElements::columns(std::size_t e) const {
  return {column_dofs.data() + column_offsets[e],
          static_cast<std::size_t>(column_offsets[e + 1] - column_offsets[e])};
}

std::span<const double> ContactElements::element_residual(std::size_t e) const {
  return {residual.data() + row_offsets[e],
          static_cast<std::size_t>(row_offsets[e + 1] - row_offsets[e])};
}

Eigen::Map<const RowMajorMatrix> ContactElements::element_tangent(std::size_t e) const {
  return {tangent.data() + tangent_offsets[e], row_offsets[e + 1] - row_offsets[e],
          column_offsets[e + 1] - column_offsets[e]};
}

ContactElements::Slot ContactElements::append(std::int32_t p, int num_rows, int num_columns) {
  point.push_back(p);
  const std::size_t r = row_dofs.size(), c = column_dofs.size(), t = tangent.size();
  row_offsets.push_back(static_cast<std::int32_t>(r + num_rows));
  column_offsets.push_back(static_cast<std::int32_t>(c + num_columns));
  tangent_offsets.push_back(static_cast<std::int64_t>(t) + std::int64_t{num_rows} * num_columns);
  row_dofs.resize(r + num_rows);
  column_dofs.resize(c + num_columns);
  residual.resize(r + num_rows, 0.0);
  tangent.resize(t + static_cast<std::size_t>(num_rows) * num_columns, 0.0);
  return {{row_dofs.data() + r, static_cast<std::size_t>(num_rows)},
          {column_dofs.data() + c, static_cast<std::size_t>(num_columns)},
          {residual.data() + r, num_rows},
          {tangent.data() + t, num_rows, num_columns}};
}

}  // namespace hypercontact
