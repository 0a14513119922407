// Bindings of surface_contact.hpp: SurfaceContactInput (named fields), SurfaceContactState,
// SurfaceContactEvaluation, evaluate_surface_contact(input).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hypercontact/surface_contact.hpp>

#include "owned_inputs.hpp"

namespace hypercontact::python {

void declare_surface_contact(py::module_& m) {
  using In = OwnedSurfaceContactInput;
  py::class_<In>(m, "SurfaceContactInput",
                 "A slave surface against a master surface: x (nn, 3) current coordinates of the\n"
                 "contact nodes; point_nodes, point_weights (np, 4) (-1 = unused); point_area\n"
                 "(np,); facets, edge_neighbour (nf, 3) triangles or (nf, 4) quadrilaterals; offsets\n"
                 "(np + 1,), candidates: the broad phase's CSR; dofs (nn, 3) int32 global, -1 =\n"
                 "constrained; eps_n; multipliers (np,) augmented-Lagrangian pressures >= 0, or empty;\n"
                 "smoothing >= 0; smooth_master: project along averaged nodal normals (linear facets).")
      .def(py::init([](RealArray x, IndexArray point_nodes, RealArray point_weights,
                       RealArray point_area, IndexArray facets, IndexArray edge_neighbour,
                       IndexArray offsets, IndexArray candidates, IndexArray dofs, double eps_n,
                       RealArray multipliers, double smoothing, bool smooth_master) {
             return In{x,       point_nodes, point_weights, point_area, facets,      edge_neighbour,
                       offsets, candidates,  dofs,          eps_n,      multipliers, smoothing,
                       smooth_master};
           }),
           py::kw_only(), py::arg("x"), py::arg("point_nodes"), py::arg("point_weights"),
           py::arg("point_area"), py::arg("facets"), py::arg("edge_neighbour"), py::arg("offsets"),
           py::arg("candidates"), py::arg("dofs"), py::arg("eps_n"),
           py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
           py::arg("smooth_master") = false)
      .def_readwrite("x", &In::x)
      .def_readwrite("point_nodes", &In::point_nodes)
      .def_readwrite("point_weights", &In::point_weights)
      .def_readwrite("point_area", &In::point_area)
      .def_readwrite("facets", &In::facets)
      .def_readwrite("edge_neighbour", &In::edge_neighbour)
      .def_readwrite("offsets", &In::offsets)
      .def_readwrite("candidates", &In::candidates)
      .def_readwrite("dofs", &In::dofs)
      .def_readwrite("eps_n", &In::eps_n)
      .def_readwrite("multipliers", &In::multipliers)
      .def_readwrite("smoothing", &In::smoothing)
      .def_readwrite("smooth_master", &In::smooth_master);

  using S = SurfaceContactState;
  py::class_<S>(m, "SurfaceContactState", "Pairing, gap and pressure of every slave point")
      .def_property_readonly("facet", [](const S& s) { return to_numpy_table(s.facet, 1); })
      .def_property_readonly("feature", [](const S& s) { return to_numpy_table(s.feature, 1); })
      .def_property_readonly("status", [](const S& s) { return to_numpy_table(s.status, 1); })
      .def_property_readonly("xi", [](const S& s) { return to_numpy_table(s.xi, 2); })
      .def_property_readonly("gap", [](const S& s) { return to_numpy_table(s.gap, 1); })
      .def_property_readonly("pressure", [](const S& s) { return to_numpy_table(s.pressure, 1); })
      .def_property_readonly("normal", [](const S& s) { return to_numpy_table(s.normal, 3); })
      .def_readonly("force", &S::force,
                    "force of the master on the slave body, -sum of the slave residuals (3,)")
      .def_readonly("num_closed", &S::num_closed);

  py::class_<SurfaceContactEvaluation, S>(
      m, "SurfaceContactEvaluation", "SurfaceContactState plus the element of every closed point")
      .def_readonly("elements", &SurfaceContactEvaluation::elements,
                    "ContactElements: rows = columns = dofs of [slave nodes, facet], global");

  m.def(
      "evaluate_surface_contact", [](const In& in) { return evaluate_surface_contact(in.view()); },
      py::arg("input"),
      "Narrow phase and normal element of every slave point, once: the state and each closed\n"
      "point's residual and tangent (add_residual / add_tangent insert them).");
}

}  // namespace hypercontact::python
