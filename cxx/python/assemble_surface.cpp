// Bindings of assemble_surface.hpp (the positional interface before SurfaceContactInput and
// evaluate_surface_contact(input)); b and A are petsc4py objects.
#include <caster_petsc.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hypercontact/assemble_surface.hpp>

#include "owned_inputs.hpp"

namespace hypercontact::python {

void declare_assemble_surface(py::module_& m) {
  auto input = [](const RealArray& x, const IndexArray& point_nodes, const RealArray& point_weights,
                  const RealArray& point_area, const IndexArray& facets,
                  const IndexArray& edge_neighbour, const IndexArray& offsets,
                  const IndexArray& candidates, double eps_n, const IndexArray& dofs,
                  const RealArray& multipliers, double smoothing) {
    return OwnedSurfaceContactInput{x,      point_nodes,    point_weights, point_area,
                                    facets, edge_neighbour, offsets,       candidates,
                                    dofs,   eps_n,          multipliers,   smoothing};
  };
  const char* doc_args =
      "x (nn, 3) current coordinates of the contact nodes; point_nodes, point_weights (np, 4);\n"
      "point_area (np,); facets, edge_neighbour (nf, 3 or 4); offsets (np + 1,), candidates: the broad\n"
      "phase's CSR; eps_n; dofs (nn, 3) int32 global indices, -1 = constrained (skipped);\n"
      "multipliers (np,) or empty: augmented Lagrangian pressures lambda_N >= 0 (empty: penalty);\n"
      "smoothing: the band delta >= 0 of the smoothed normal law (0: the Macaulay bracket).";
  m.def(
      "evaluate_surface_contact",
      [input](const RealArray& x, const IndexArray& pn, const RealArray& pw, const RealArray& pa,
              const IndexArray& f, const IndexArray& en, const IndexArray& o, const IndexArray& c,
              double eps_n, const IndexArray& dofs, const RealArray& lam, double smoothing) {
        return assemble_surface_contact(
            input(x, pn, pw, pa, f, en, o, c, eps_n, dofs, lam, smoothing).view(), nullptr,
            nullptr);
      },
      py::arg("x"), py::arg("point_nodes"), py::arg("point_weights"), py::arg("point_area"),
      py::arg("facets"), py::arg("edge_neighbour"), py::arg("offsets"), py::arg("candidates"),
      py::arg("eps_n"), py::arg("dofs"), py::arg("multipliers") = RealArray(0),
      py::arg("smoothing") = 0.0,
      (std::string("Pairing, gaps and pressures of every slave point, no assembly.\n") + doc_args)
          .c_str());
  m.def(
      "assemble_surface_residual",
      [input](const RealArray& x, const IndexArray& pn, const RealArray& pw, const RealArray& pa,
              const IndexArray& f, const IndexArray& en, const IndexArray& o, const IndexArray& c,
              double eps_n, const IndexArray& dofs, Vec b, const RealArray& lam, double smoothing) {
        return assemble_surface_contact(
            input(x, pn, pw, pa, f, en, o, c, eps_n, dofs, lam, smoothing).view(), b, nullptr);
      },
      py::arg("x"), py::arg("point_nodes"), py::arg("point_weights"), py::arg("point_area"),
      py::arg("facets"), py::arg("edge_neighbour"), py::arg("offsets"), py::arg("candidates"),
      py::arg("eps_n"), py::arg("dofs"), py::arg("b"), py::arg("multipliers") = RealArray(0),
      py::arg("smoothing") = 0.0,
      (std::string("Adds the residual into the petsc4py Vec b (VecSetValues, global, ADD);\n"
                   "call b.assemblyBegin/End afterwards.\n") +
       doc_args)
          .c_str());
  m.def(
      "assemble_surface_tangent",
      [input](const RealArray& x, const IndexArray& pn, const RealArray& pw, const RealArray& pa,
              const IndexArray& f, const IndexArray& en, const IndexArray& o, const IndexArray& c,
              double eps_n, const IndexArray& dofs, Mat A, const RealArray& lam, double smoothing) {
        return assemble_surface_contact(
            input(x, pn, pw, pa, f, en, o, c, eps_n, dofs, lam, smoothing).view(), nullptr, A);
      },
      py::arg("x"), py::arg("point_nodes"), py::arg("point_weights"), py::arg("point_area"),
      py::arg("facets"), py::arg("edge_neighbour"), py::arg("offsets"), py::arg("candidates"),
      py::arg("eps_n"), py::arg("dofs"), py::arg("A"), py::arg("multipliers") = RealArray(0),
      py::arg("smoothing") = 0.0,
      (std::string("Adds the tangent into the petsc4py Mat A (MatSetValues, global, ADD); call\n"
                   "A.assemble() afterwards.\n") +
       doc_args)
          .c_str());
}

}  // namespace hypercontact::python
