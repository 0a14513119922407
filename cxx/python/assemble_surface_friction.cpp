// Bindings of assemble_surface_friction.hpp; b and A are petsc4py objects or None.
#include <caster_petsc.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hypercontact/assemble_surface_friction.hpp>

#include "array.hpp"

namespace hypercontact::python {

void declare_assemble_surface_friction(py::module_& m) {
  using S = SurfaceFrictionState;
  py::class_<S>(m, "SurfaceFrictionState", "Output of assemble_surface_friction")
      .def_property_readonly("facet", [](const S& s) { return to_numpy_table(s.facet, 1); })
      .def_property_readonly("feature", [](const S& s) { return to_numpy_table(s.feature, 1); })
      .def_property_readonly("status", [](const S& s) { return to_numpy_table(s.status, 1); })
      .def_property_readonly("xi", [](const S& s) { return to_numpy_table(s.xi, 2); })
      .def_property_readonly("gap", [](const S& s) { return to_numpy_table(s.gap, 1); })
      .def_property_readonly("pressure", [](const S& s) { return to_numpy_table(s.pressure, 1); })
      .def_property_readonly("normal", [](const S& s) { return to_numpy_table(s.normal, 3); })
      .def_property_readonly("traction", [](const S& s) { return to_numpy_table(s.traction, 3); })
      .def_property_readonly("slip_increment", [](const S& s) { return to_numpy_table(s.slip_increment, 3); })
      .def_property_readonly("dissipation", [](const S& s) { return to_numpy_table(s.dissipation, 1); })
      .def_property_readonly("state", [](const S& s) { return to_numpy_table(s.stick, 1); },
                             "0 open, 1 stick, 2 slip")
      .def_readonly("normal_force", &S::force, "normal part of the force of the master on the slave body")
      .def_readonly("force", &S::total_force, "force of the master on the slave body, normal + friction (3,)")
      .def_readonly("num_closed", &S::num_closed);

  auto input = [](const RealArray& x, const IndexArray& point_nodes, const RealArray& point_weights,
                  const RealArray& point_area, const IndexArray& facets, const IndexArray& edge_neighbour,
                  const IndexArray& offsets, const IndexArray& candidates, double eps_n,
                  const IndexArray& dofs, const IndexArray& old_facet, const RealArray& xi_old,
                  const RealArray& t_old, double eps_t, double mu, const RealArray& multipliers,
                  double smoothing) {
    check_shape(multipliers, "multipliers", {any});
    check_shape(x, "x", {any, 3});
    check_shape(point_area, "point_area", {any});
    const py::ssize_t np = point_area.shape(0);
    check_shape(point_nodes, "point_nodes", {np, 4});
    check_shape(point_weights, "point_weights", {np, 4});
    check_shape(facets, "facets", {any, 4});
    check_shape(edge_neighbour, "edge_neighbour", {facets.shape(0), 4});
    check_shape(offsets, "offsets", {np + 1});
    check_shape(candidates, "candidates", {any});
    check_shape(dofs, "dofs", {x.shape(0), 3});
    check_shape(old_facet, "old_facet", {np});
    check_shape(xi_old, "xi_old", {np, 2});
    check_shape(t_old, "t_old", {np, 3});
    return SurfaceFrictionInput{
        SurfaceContactInput{as_span(x), as_span(point_nodes), as_span(point_weights), as_span(point_area),
                            as_span(facets), as_span(edge_neighbour), as_span(offsets), as_span(candidates),
                            as_span(dofs), eps_n, as_span(multipliers), smoothing},
        as_span(old_facet), as_span(xi_old), as_span(t_old), eps_t, mu};
  };
  const char* doc =
      "x (nn, 3); point_nodes, point_weights (np, 4); point_area (np,); facets, edge_neighbour (nf, 4);\n"
      "offsets (np + 1,), candidates: the broad phase's CSR; eps_n; dofs (nn, 3) int32 global, -1 =\n"
      "constrained; history: old_facet (np,) int32 (-1 none), xi_old (np, 2), t_old (np, 3); eps_t; mu;\n"
      "multipliers (np,) or empty: augmented Lagrangian pressures lambda_N >= 0 (empty: penalty);\n"
      "smoothing: the band delta >= 0 of the smoothed normal law (0: the Macaulay bracket).";
#define HC_ARGS                                                                                         \
  py::arg("x"), py::arg("point_nodes"), py::arg("point_weights"), py::arg("point_area"), py::arg("facets"), \
      py::arg("edge_neighbour"), py::arg("offsets"), py::arg("candidates"), py::arg("eps_n"),               \
      py::arg("dofs"), py::arg("old_facet"), py::arg("xi_old"), py::arg("t_old"), py::arg("eps_t"),        \
      py::arg("mu")
  m.def(
      "evaluate_surface_friction",
      [input](const RealArray& x, const IndexArray& pn, const RealArray& pw, const RealArray& pa,
              const IndexArray& f, const IndexArray& en, const IndexArray& o, const IndexArray& c, double eps_n,
              const IndexArray& dofs, const IndexArray& of, const RealArray& xo, const RealArray& to,
              double eps_t, double mu, const RealArray& lam, double smoothing) {
        return assemble_surface_friction(input(x, pn, pw, pa, f, en, o, c, eps_n, dofs, of, xo, to, eps_t, mu, lam, smoothing),
                                         nullptr, nullptr);
      },
      HC_ARGS, py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0, (std::string("Pairing, normal and friction state of every slave point, no assembly.\n") + doc).c_str());
  m.def(
      "assemble_surface_friction_residual",
      [input](const RealArray& x, const IndexArray& pn, const RealArray& pw, const RealArray& pa,
              const IndexArray& f, const IndexArray& en, const IndexArray& o, const IndexArray& c, double eps_n,
              const IndexArray& dofs, const IndexArray& of, const RealArray& xo, const RealArray& to,
              double eps_t, double mu, Vec b, const RealArray& lam, double smoothing) {
        return assemble_surface_friction(input(x, pn, pw, pa, f, en, o, c, eps_n, dofs, of, xo, to, eps_t, mu, lam, smoothing), b,
                                         nullptr);
      },
      HC_ARGS, py::arg("b"), py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
      (std::string("Adds normal + friction residual into the petsc4py Vec b (global, ADD).\n") + doc).c_str());
  m.def(
      "assemble_surface_friction_tangent",
      [input](const RealArray& x, const IndexArray& pn, const RealArray& pw, const RealArray& pa,
              const IndexArray& f, const IndexArray& en, const IndexArray& o, const IndexArray& c, double eps_n,
              const IndexArray& dofs, const IndexArray& of, const RealArray& xo, const RealArray& to,
              double eps_t, double mu, Mat A, const RealArray& lam, double smoothing) {
        return assemble_surface_friction(input(x, pn, pw, pa, f, en, o, c, eps_n, dofs, of, xo, to, eps_t, mu, lam, smoothing),
                                         nullptr, A);
      },
      HC_ARGS, py::arg("A"), py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
      (std::string("Adds the non-symmetric tangent (old-facet columns included) into the petsc4py Mat A.\n") +
       doc).c_str());
#undef HC_ARGS
}

}  // namespace hypercontact::python
