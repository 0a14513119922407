// Bindings of surface_contact_friction.hpp: SurfaceFrictionInput (named fields),
// SurfaceFrictionState, SurfaceFrictionEvaluation, evaluate_surface_friction(input).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hypercontact/surface_contact_friction.hpp>

#include "owned_inputs.hpp"

namespace hypercontact::python {

void declare_surface_contact_friction(py::module_& m) {
  using In = OwnedSurfaceFrictionInput;
  py::class_<In>(m, "SurfaceFrictionInput",
                 "The normal contact (a SurfaceContactInput) plus each slave point's history:\n"
                 "old_facet (np,) int32 (-1 none), xi_old (np, 2), t_old (np, 3); eps_t; mu.")
      .def(py::init([](const OwnedSurfaceContactInput& contact, IndexArray old_facet,
                       RealArray xi_old, RealArray t_old, double eps_t,
                       double mu) { return In{contact, old_facet, xi_old, t_old, eps_t, mu}; }),
           py::kw_only(), py::arg("contact"), py::arg("old_facet"), py::arg("xi_old"),
           py::arg("t_old"), py::arg("eps_t"), py::arg("mu"))
      .def_readwrite("contact", &In::contact)
      .def_readwrite("old_facet", &In::old_facet)
      .def_readwrite("xi_old", &In::xi_old)
      .def_readwrite("t_old", &In::t_old)
      .def_readwrite("eps_t", &In::eps_t)
      .def_readwrite("mu", &In::mu);

  using S = SurfaceFrictionState;
  py::class_<S>(m, "SurfaceFrictionState",
                "Pairing, normal and friction state of every slave point")
      .def_property_readonly("facet", [](const S& s) { return to_numpy_table(s.facet, 1); })
      .def_property_readonly("feature", [](const S& s) { return to_numpy_table(s.feature, 1); })
      .def_property_readonly("status", [](const S& s) { return to_numpy_table(s.status, 1); })
      .def_property_readonly("xi", [](const S& s) { return to_numpy_table(s.xi, 2); })
      .def_property_readonly("gap", [](const S& s) { return to_numpy_table(s.gap, 1); })
      .def_property_readonly("pressure", [](const S& s) { return to_numpy_table(s.pressure, 1); })
      .def_property_readonly("normal", [](const S& s) { return to_numpy_table(s.normal, 3); })
      .def_property_readonly("traction", [](const S& s) { return to_numpy_table(s.traction, 3); })
      .def_property_readonly("slip_increment",
                             [](const S& s) { return to_numpy_table(s.slip_increment, 3); })
      .def_property_readonly("dissipation",
                             [](const S& s) { return to_numpy_table(s.dissipation, 1); })
      .def_property_readonly(
          "state", [](const S& s) { return to_numpy_table(s.stick, 1); }, "0 open, 1 stick, 2 slip")
      .def_readonly("normal_force", &S::force,
                    "normal part of the force of the master on the slave body")
      .def_readonly("force", &S::total_force,
                    "force of the master on the slave body, normal + friction (3,)")
      .def_readonly("num_closed", &S::num_closed);

  py::class_<SurfaceFrictionEvaluation, S>(
      m, "SurfaceFrictionEvaluation", "SurfaceFrictionState plus the element of every closed point")
      .def_readonly(
          "elements", &SurfaceFrictionEvaluation::elements,
          "ContactElements: rows [slave, facet], columns [slave, facet, old facet], global");

  m.def(
      "evaluate_surface_friction",
      [](const In& in) { return evaluate_surface_friction(in.view()); }, py::arg("input"),
      "Narrow phase, normal element and Coulomb return map of every slave point, once: the state\n"
      "and each closed point's residual and tangent (add_residual / add_tangent insert them).");
}

}  // namespace hypercontact::python
