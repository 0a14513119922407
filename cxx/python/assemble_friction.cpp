// Bindings of assemble_friction.hpp (the positional interface before RigidFrictionInput and
// evaluate_rigid_friction); A is a petsc4py Mat (dolfinx's pybind11 PETSc casters).
#include <caster_petsc.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hypercontact/assemble_friction.hpp>

#include "array.hpp"

namespace hypercontact::python {

namespace {
/// Checks x, xi_old, t_old (n, 3), area (n,), dofs (n, 3).
void check_friction_nodes(const RealArray& x, const RealArray& area, const RealArray& xi_old,
                          const RealArray& t_old, const IndexArray& dofs) {
  check_shape(x, "x", {any, 3});
  check_shape(area, "area", {x.shape(0)});
  check_shape(xi_old, "xi_old", {x.shape(0), 3});
  check_shape(t_old, "t_old", {x.shape(0), 3});
  check_shape(dofs, "dofs", {x.shape(0), 3});
}

py::array_t<double> as_n3(const std::vector<double>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size() / 3), py::ssize_t(3)});
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}
}  // namespace

void declare_assemble_friction(py::module_& m) {
  py::class_<RigidFrictionState>(m, "RigidFrictionState",
                                 "Output of assemble_rigid_friction_residual")
      .def_property_readonly("traction",
                             [](const RigidFrictionState& s) { return as_n3(s.traction); })
      .def_property_readonly("slip_increment",
                             [](const RigidFrictionState& s) { return as_n3(s.slip_increment); })
      .def_property_readonly("dissipation",
                             [](const RigidFrictionState& s) { return to_numpy(s.dissipation); })
      .def_property_readonly("state",
                             [](const RigidFrictionState& s) {
                               py::array_t<std::int8_t> a(static_cast<py::ssize_t>(s.state.size()));
                               std::copy(s.state.begin(), s.state.end(), a.mutable_data());
                               return a;
                             })
      .def_readonly("force", &RigidFrictionState::force);

  m.def(
      "assemble_rigid_friction_residual",
      [](const Obstacle& obstacle, const RealArray& x, const RealArray& area, double eps_n,
         double eps_t, double mu, const RealArray& xi_old, const RealArray& t_old,
         const IndexArray& dofs, py::array b, const RealArray& multipliers, double smoothing) {
        check_friction_nodes(x, area, xi_old, t_old, dofs);
        const std::span<double> b_span = as_writable_span(b, "b");
        return assemble_rigid_friction_residual(obstacle, as_span(x), as_span(area), eps_n, eps_t,
                                                mu, as_span(xi_old), as_span(t_old), as_span(dofs),
                                                b_span, as_span(multipliers), smoothing);
      },
      py::arg("obstacle"), py::arg("x"), py::arg("area"), py::arg("eps_n"), py::arg("eps_t"),
      py::arg("mu"), py::arg("xi_old"), py::arg("t_old"), py::arg("dofs"), py::arg("b"),
      py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
      "Adds the Coulomb friction residuals into b[dofs] in place; returns a RigidFrictionState.");
  m.def(
      "assemble_rigid_friction_tangent",
      [](const Obstacle& obstacle, const RealArray& x, const RealArray& area, double eps_n,
         double eps_t, double mu, const RealArray& xi_old, const RealArray& t_old,
         const IndexArray& dofs, Mat A, const RealArray& multipliers, double smoothing) {
        check_friction_nodes(x, area, xi_old, t_old, dofs);
        assemble_rigid_friction_tangent(obstacle, as_span(x), as_span(area), eps_n, eps_t, mu,
                                        as_span(xi_old), as_span(t_old), as_span(dofs), A,
                                        as_span(multipliers), smoothing);
      },
      py::arg("obstacle"), py::arg("x"), py::arg("area"), py::arg("eps_n"), py::arg("eps_t"),
      py::arg("mu"), py::arg("xi_old"), py::arg("t_old"), py::arg("dofs"), py::arg("A"),
      py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
      "Adds the (non-symmetric) friction tangents into the petsc4py Mat A (ADD_VALUES).");
}

}  // namespace hypercontact::python
