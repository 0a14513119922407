// Bindings of normal_penalty.hpp.
#include <pybind11/eigen.h>

#include <hypercontact/normal_penalty.hpp>

#include "array.hpp"

namespace hypercontact::python {

void declare_normal_penalty(py::module_& m) {
  py::class_<NodalContact>(m, "NodalContact", "Penalty contribution of one slave node")
      .def_readonly("residual", &NodalContact::residual, "r = A eps_n g n (3,)")
      .def_readonly("tangent", &NodalContact::tangent, "K = dr/dx (3, 3)")
      .def_readonly("pressure", &NodalContact::pressure, "eps_n <-g> >= 0")
      .def_readonly("closed", &NodalContact::closed, "g <= 0");

  m.def("normal_penalty_energy", &normal_penalty_energy, py::arg("projection"), py::arg("area"),
        py::arg("eps_n"), py::arg("smoothing") = 0.0,
        "W = area eps_n Q(g), Q = 1/2 <-g>^2 (smoothed over |g| < smoothing, penetration.hpp)");
  m.def("normal_penalty", &normal_penalty, py::arg("projection"), py::arg("area"), py::arg("eps_n"),
        py::arg("smoothing") = 0.0, "Residual dW/dx and tangent of W = area eps_n Q(g)");
}

}  // namespace hypercontact::python
