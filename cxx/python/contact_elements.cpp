// Bindings of contact_elements.hpp (DofNumbering, ContactElements with its arrays as numpy).
#include <pybind11/eigen.h>

#include <hypercontact/contact_elements.hpp>

#include "array.hpp"

namespace hypercontact::python {

void declare_contact_elements(py::module_& m) {
  py::enum_<DofNumbering>(m, "DofNumbering",
                          "How the dof indices of contact elements number the unknowns")
      .value("Local", DofNumbering::Local, "process-local (owned + ghost) indices")
      .value("Global", DofNumbering::Global, "global PETSc indices");

  using E = ContactElements;
  py::class_<E>(m, "ContactElements",
                "Element contributions of one evaluation, flat: element e has rows\n"
                "row_dofs[row_offsets[e]:row_offsets[e+1]] with residual[same], columns\n"
                "column_dofs[column_offsets[e]:column_offsets[e+1]] and the row-major tangent\n"
                "tangent[tangent_offsets[e]:tangent_offsets[e+1]]; dof -1 = constrained.")
      .def_readonly("numbering", &E::numbering)
      .def("__len__", &E::size)
      .def_property_readonly(
          "point", [](const E& e) { return to_numpy_table(e.point, 1); },
          "slave point (node) of each element")
      .def_property_readonly("row_offsets",
                             [](const E& e) { return to_numpy_table(e.row_offsets, 1); })
      .def_property_readonly("column_offsets",
                             [](const E& e) { return to_numpy_table(e.column_offsets, 1); })
      .def_property_readonly("tangent_offsets",
                             [](const E& e) { return to_numpy_table(e.tangent_offsets, 1); })
      .def_property_readonly("row_dofs", [](const E& e) { return to_numpy_table(e.row_dofs, 1); })
      .def_property_readonly("column_dofs",
                             [](const E& e) { return to_numpy_table(e.column_dofs, 1); })
      .def_property_readonly("residual", [](const E& e) { return to_numpy_table(e.residual, 1); })
      .def_property_readonly("tangent", [](const E& e) { return to_numpy_table(e.tangent, 1); })
      .def(
          "element_tangent",
          [](const E& e, std::size_t k) {
            if (k >= e.size())
              throw py::index_error("element " + std::to_string(k) + " out of range");
            return RowMajorMatrix(e.element_tangent(k));
          },
          py::arg("e"), "K_e as a (rows, columns) array");
}

}  // namespace hypercontact::python
