// Bindings of assemble_surface_friction.hpp (the positional interface before SurfaceFrictionInput
// and evaluate_surface_friction(input)); b and A are petsc4py objects.
#include <caster_petsc.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hypercontact/assemble_surface_friction.hpp>

#include "owned_inputs.hpp"

namespace hypercontact::python {

void declare_assemble_surface_friction(py::module_& m) {
  auto input = [](const RealArray& x, const IndexArray& point_nodes, const RealArray& point_weights,
                  const RealArray& point_area, const IndexArray& facets,
                  const IndexArray& edge_neighbour, const IndexArray& offsets,
                  const IndexArray& candidates, double eps_n, const IndexArray& dofs,
                  const IndexArray& old_facet, const RealArray& xi_old, const RealArray& t_old,
                  double eps_t, double mu, const RealArray& multipliers, double smoothing) {
    return OwnedSurfaceFrictionInput{
        OwnedSurfaceContactInput{x, point_nodes, point_weights, point_area, facets, edge_neighbour,
                                 offsets, candidates, dofs, eps_n, multipliers, smoothing},
        old_facet,
        xi_old,
        t_old,
        eps_t,
        mu};
  };
  const char* doc =
      "x (nn, 3); point_nodes, point_weights (np, 4); point_area (np,); facets, edge_neighbour "
      "(nf, 3 or 4);\n"
      "offsets (np + 1,), candidates: the broad phase's CSR; eps_n; dofs (nn, 3) int32 global, -1 "
      "=\n"
      "constrained; history: old_facet (np,) int32 (-1 none), xi_old (np, 2), t_old (np, 3); "
      "eps_t; mu;\n"
      "multipliers (np,) or empty: augmented Lagrangian pressures lambda_N >= 0 (empty: penalty);\n"
      "smoothing: the band delta >= 0 of the smoothed normal law (0: the Macaulay bracket).";
#define HC_ARGS                                                                                \
  py::arg("x"), py::arg("point_nodes"), py::arg("point_weights"), py::arg("point_area"),       \
      py::arg("facets"), py::arg("edge_neighbour"), py::arg("offsets"), py::arg("candidates"), \
      py::arg("eps_n"), py::arg("dofs"), py::arg("old_facet"), py::arg("xi_old"),              \
      py::arg("t_old"), py::arg("eps_t"), py::arg("mu")
  m.def(
      "evaluate_surface_friction",
      [input](const RealArray& x, const IndexArray& pn, const RealArray& pw, const RealArray& pa,
              const IndexArray& f, const IndexArray& en, const IndexArray& o, const IndexArray& c,
              double eps_n, const IndexArray& dofs, const IndexArray& of, const RealArray& xo,
              const RealArray& to, double eps_t, double mu, const RealArray& lam,
              double smoothing) {
        return assemble_surface_friction(
            input(x, pn, pw, pa, f, en, o, c, eps_n, dofs, of, xo, to, eps_t, mu, lam, smoothing)
                .view(),
            nullptr, nullptr);
      },
      HC_ARGS, py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
      (std::string("Pairing, normal and friction state of every slave point, no assembly.\n") + doc)
          .c_str());
  m.def(
      "assemble_surface_friction_residual",
      [input](const RealArray& x, const IndexArray& pn, const RealArray& pw, const RealArray& pa,
              const IndexArray& f, const IndexArray& en, const IndexArray& o, const IndexArray& c,
              double eps_n, const IndexArray& dofs, const IndexArray& of, const RealArray& xo,
              const RealArray& to, double eps_t, double mu, Vec b, const RealArray& lam,
              double smoothing) {
        return assemble_surface_friction(
            input(x, pn, pw, pa, f, en, o, c, eps_n, dofs, of, xo, to, eps_t, mu, lam, smoothing)
                .view(),
            b, nullptr);
      },
      HC_ARGS, py::arg("b"), py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
      (std::string("Adds normal + friction residual into the petsc4py Vec b (global, ADD).\n") +
       doc)
          .c_str());
  m.def(
      "assemble_surface_friction_tangent",
      [input](const RealArray& x, const IndexArray& pn, const RealArray& pw, const RealArray& pa,
              const IndexArray& f, const IndexArray& en, const IndexArray& o, const IndexArray& c,
              double eps_n, const IndexArray& dofs, const IndexArray& of, const RealArray& xo,
              const RealArray& to, double eps_t, double mu, Mat A, const RealArray& lam,
              double smoothing) {
        return assemble_surface_friction(
            input(x, pn, pw, pa, f, en, o, c, eps_n, dofs, of, xo, to, eps_t, mu, lam, smoothing)
                .view(),
            nullptr, A);
      },
      HC_ARGS, py::arg("A"), py::arg("multipliers") = RealArray(0), py::arg("smoothing") = 0.0,
      (std::string("Adds the non-symmetric tangent (old-facet columns included) into the petsc4py "
                   "Mat A.\n") +
       doc)
          .c_str());
#undef HC_ARGS
}

}  // namespace hypercontact::python
