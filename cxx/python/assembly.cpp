// Bindings of assembly.hpp: add_residual / add_tangent of an evaluation (anything with an
// `elements` attribute, or a ContactElements) into a numpy array, a petsc4py Vec or Mat.
#include <caster_petsc.h>

#include <hypercontact/assembly.hpp>

#include "array.hpp"

namespace hypercontact::python {

namespace {
/// The ContactElements of an evaluation, or the object itself if it is one (no copy).
const ContactElements& elements_of(const py::object& evaluation) {
  if (py::isinstance<ContactElements>(evaluation)) return evaluation.cast<const ContactElements&>();
  return evaluation.attr("elements").cast<const ContactElements&>();
}
}  // namespace

void declare_assembly(py::module_& m) {
  m.def(
      "add_residual",
      [](const py::object& evaluation, Vec b) { add_residual(elements_of(evaluation), b); },
      py::arg("evaluation"), py::arg("b"),
      "Adds every element residual into the petsc4py Vec b (VecSetValues for global numbering,\n"
      "VecSetValuesLocal for local; ADD_VALUES, -1 skipped); call b.assemblyBegin/End after.");
  m.def(
      "add_residual",
      [](const py::object& evaluation, py::array b) {
        add_residual(elements_of(evaluation), as_writable_span(b, "b"));
      },
      py::arg("evaluation"), py::arg("b"),
      "Adds every element residual into b[row dofs] in place: b a writable contiguous float64\n"
      "1-D array of process-local entries (e.g. the array_w of vec.localForm()); local\n"
      "numbering only (rigid contacts).");
  m.def(
      "add_tangent",
      [](const py::object& evaluation, Mat A) { add_tangent(elements_of(evaluation), A); },
      py::arg("evaluation"), py::arg("A"),
      "Adds every element tangent into the petsc4py Mat A (MatSetValues for global numbering,\n"
      "MatSetValuesLocal for local, which needs A's local-to-global mapping; ADD_VALUES, -1\n"
      "skipped); call A.assemble() after.");
}

}  // namespace hypercontact::python
