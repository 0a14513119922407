// Bindings of assemble_rigid.hpp (the positional interface before RigidContactInput and
// evaluate_rigid_contact); A is a petsc4py Mat (dolfinx's pybind11 PETSc casters).
#include <caster_petsc.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hypercontact/assemble_rigid.hpp>

#include "array.hpp"

namespace hypercontact::python {

namespace {
/// Checks x (n, 3), area (n,), dofs (n, 3).
void check_nodes(const RealArray& x, const RealArray& area, const IndexArray& dofs) {
  check_shape(x, "x", {any, 3});
  check_shape(area, "area", {x.shape(0)});
  check_shape(dofs, "dofs", {x.shape(0), 3});
}
}  // namespace

void declare_assemble_rigid(py::module_& m) {
  m.def(
      "assemble_rigid_residual",
      [](const Obstacle& obstacle, const RealArray& x, const RealArray& area, double eps_n,
         const IndexArray& dofs, py::array b, const RealArray& multipliers, double smoothing) {
        check_nodes(x, area, dofs);
        const std::span<double> b_span = as_writable_span(b, "b");
        return assemble_rigid_residual(obstacle, as_span(x), as_span(area), eps_n, as_span(dofs),
                                       b_span, as_span(multipliers), smoothing);
      },
      py::arg("obstacle"), py::arg("x"), py::arg("area"), py::arg("eps_n"), py::arg("dofs"),
      py::arg("b"), py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
      "Adds the nodal penalty residuals into b[dofs] in place and returns a RigidContactState.\n\n"
      "x: (n, 3) current coordinates; area: (n,); dofs: (n, 3) int32 process-local unblocked\n"
      "dof indices, -1 = constrained (skipped); b: writable contiguous float64 1-D array, e.g.\n"
      "the array_w of vec.localForm().");

  m.def(
      "assemble_rigid_tangent",
      [](const Obstacle& obstacle, const RealArray& x, const RealArray& area, double eps_n,
         const IndexArray& dofs, Mat A, const RealArray& multipliers, double smoothing) {
        check_nodes(x, area, dofs);
        assemble_rigid_tangent(obstacle, as_span(x), as_span(area), eps_n, as_span(dofs), A,
                               as_span(multipliers), smoothing);
      },
      py::arg("obstacle"), py::arg("x"), py::arg("area"), py::arg("eps_n"), py::arg("dofs"),
      py::arg("A"), py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
      "Adds the nodal penalty tangents into the petsc4py Mat A with MatSetValuesLocal\n"
      "(ADD_VALUES; rows/columns of -1 dofs skipped). A needs a local-to-global mapping;\n"
      "call A.assemble() afterwards. Arguments as assemble_rigid_residual.");
}

}  // namespace hypercontact::python
