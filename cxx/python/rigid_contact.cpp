// Bindings of rigid_contact.hpp: RigidContactInput (named fields), RigidContactState,
// RigidContactEvaluation, evaluate_rigid_contact.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hypercontact/rigid_contact.hpp>

#include "owned_inputs.hpp"

namespace hypercontact::python {

void declare_rigid_contact(py::module_& m) {
  using In = OwnedRigidContactInput;
  py::class_<In>(m, "RigidContactInput",
                 "Slave nodes against one rigid obstacle: obstacle; x (n, 3) current coordinates;\n"
                 "area (n,); dofs (n, 3) int32 process-local, -1 = constrained; eps_n;\n"
                 "multipliers (n,) augmented-Lagrangian pressures >= 0, or empty (penalty);\n"
                 "smoothing: the band delta >= 0 of the smoothed law (0: the Macaulay bracket);\n"
                 "point_weights (n, k): slave points x_p = sum_a M_a x_a of k nodes each (Gauss\n"
                 "points; then dofs is (n, 3k), the nodes' dofs in order), or empty: nodes;\n"
                 "points_per_facet Q > 0: the points are the Q Gauss points of n / Q facets and\n"
                 "each facet carries the pressure of its mean gap (dofs (n / Q, 3k), multipliers\n"
                 "(n / Q,)); 0: each point its own.")
      .def(py::init([](Obstacle obstacle, RealArray x, RealArray area, IndexArray dofs,
                       double eps_n, RealArray multipliers, double smoothing,
                       RealArray point_weights, int points_per_facet) {
             return In{
                 std::move(obstacle), x, area, dofs, eps_n, multipliers, smoothing, point_weights,
                 points_per_facet};
           }),
           py::kw_only(), py::arg("obstacle"), py::arg("x"), py::arg("area"), py::arg("dofs"),
           py::arg("eps_n"), py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
           py::arg("point_weights") = RealArray(0), py::arg("points_per_facet") = 0)
      .def_readwrite("obstacle", &In::obstacle)
      .def_readwrite("x", &In::x)
      .def_readwrite("area", &In::area)
      .def_readwrite("dofs", &In::dofs)
      .def_readwrite("eps_n", &In::eps_n)
      .def_readwrite("multipliers", &In::multipliers)
      .def_readwrite("smoothing", &In::smoothing)
      .def_readwrite("point_weights", &In::point_weights)
      .def_readwrite("points_per_facet", &In::points_per_facet);

  py::class_<RigidContactState>(m, "RigidContactState", "Per-node gap and pressure, total force")
      .def_property_readonly("gap", [](const RigidContactState& s) { return to_numpy(s.gap); })
      .def_property_readonly("pressure",
                             [](const RigidContactState& s) { return to_numpy(s.pressure); })
      .def_readonly("force", &RigidContactState::force,
                    "force of the obstacle on the body, -sum of the nodal residuals (3,)")
      .def_readonly("num_closed", &RigidContactState::num_closed);

  py::class_<RigidContactEvaluation, RigidContactState>(
      m, "RigidContactEvaluation", "RigidContactState plus the element of every closed node")
      .def_readonly("elements", &RigidContactEvaluation::elements,
                    "ContactElements: rows = columns = dofs of the node, local numbering");

  m.def(
      "evaluate_rigid_contact", [](const In& in) { return evaluate_rigid_contact(in.view()); },
      py::arg("input"),
      "Projection and normal penalty of every slave node, once: the state and each closed\n"
      "node's residual and tangent (add_residual / add_tangent insert them).");
}

}  // namespace hypercontact::python
