// Bindings of rigid_contact_friction.hpp: RigidFrictionInput (named fields),
// RigidFrictionEvaluation, evaluate_rigid_friction.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hypercontact/rigid_contact_friction.hpp>

#include "owned_inputs.hpp"

namespace hypercontact::python {

namespace {

/// RigidFrictionInput holding its arrays: xi_old, t_old (n, 3).
struct OwnedRigidFrictionInput {
  OwnedRigidContactInput contact;
  RealArray xi_old, t_old;
  double eps_t, mu;
  bool with_normal;

  RigidFrictionInput view() const {
    RigidContactInput c = contact.view();
    check_shape(xi_old, "xi_old", {contact.x.shape(0), 3});
    check_shape(t_old, "t_old", {contact.x.shape(0), 3});
    return {c, as_span(xi_old), as_span(t_old), eps_t, mu, with_normal};
  }
};

}  // namespace

void declare_rigid_contact_friction(py::module_& m) {
  using In = OwnedRigidFrictionInput;
  py::class_<In>(
      m, "RigidFrictionInput",
      "The normal contact (a RigidContactInput) plus the history of the last converged\n"
      "step: xi_old (n, 3) positions carried with the obstacle, t_old (n, 3) tractions;\n"
      "eps_t; mu; with_normal: elements hold normal + friction (True) or the friction\n"
      "part alone (False).")
      .def(py::init([](const OwnedRigidContactInput& contact, RealArray xi_old, RealArray t_old,
                       double eps_t, double mu, bool with_normal) {
             return In{contact, xi_old, t_old, eps_t, mu, with_normal};
           }),
           py::kw_only(), py::arg("contact"), py::arg("xi_old"), py::arg("t_old"), py::arg("eps_t"),
           py::arg("mu"), py::arg("with_normal") = true)
      .def_readwrite("contact", &In::contact)
      .def_readwrite("xi_old", &In::xi_old)
      .def_readwrite("t_old", &In::t_old)
      .def_readwrite("eps_t", &In::eps_t)
      .def_readwrite("mu", &In::mu)
      .def_readwrite("with_normal", &In::with_normal);

  using E = RigidFrictionEvaluation;
  py::class_<E>(m, "RigidFrictionEvaluation",
                "Normal and friction state of every slave node, and each closed node's element")
      .def_property_readonly("gap", [](const E& e) { return to_numpy(e.gap); })
      .def_property_readonly("pressure", [](const E& e) { return to_numpy(e.pressure); })
      .def_readonly("num_closed", &E::num_closed)
      .def_property_readonly("traction", [](const E& e) { return to_numpy_table(e.traction, 3); })
      .def_property_readonly("slip_increment",
                             [](const E& e) { return to_numpy_table(e.slip_increment, 3); })
      .def_property_readonly("dissipation", [](const E& e) { return to_numpy(e.dissipation); })
      .def_property_readonly(
          "state", [](const E& e) { return to_numpy_table(e.state, 1); }, "0 open, 1 stick, 2 slip")
      .def_readonly("normal_force", &E::force, "normal force of the obstacle on the body (3,)")
      .def_readonly("friction_force", &E::friction_force,
                    "tangential force of the obstacle on the body (3,)")
      .def_readonly("force", &E::total_force, "normal_force + friction_force (3,)")
      .def_readonly("elements", &E::elements,
                    "ContactElements: rows = columns = dofs of the node, local numbering");

  m.def(
      "evaluate_rigid_friction", [](const In& in) { return evaluate_rigid_friction(in.view()); },
      py::arg("input"),
      "One projection per slave node, its normal penalty and Coulomb return map: the state and\n"
      "each closed node's residual and tangent (add_residual / add_tangent insert them).");
}

}  // namespace hypercontact::python
