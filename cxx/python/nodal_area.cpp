// Bindings of nodal_area.hpp.
#include <array>
#include <hypercontact/nodal_area.hpp>

#include "array.hpp"

namespace hypercontact::python {

void declare_nodal_area(py::module_& m) {
  m.def(
      "nodal_areas",
      [](const RealArray& coords, const IndexArray& quads_tp, std::size_t num_nodes) {
        check_shape(coords, "coords", {static_cast<py::ssize_t>(num_nodes), 3});
        check_shape(quads_tp, "quads_tp", {any, 4});
        // Tensor-product order (v0, v1, v2, v3) has the cycle v0-v1-v3-v2.
        constexpr std::array<std::size_t, 4> cycle{0, 1, 3, 2};
        const std::span<const std::int32_t> tp = as_span(quads_tp);
        std::vector<std::int32_t> cyclic(tp.size());
        for (std::size_t q = 0; q < tp.size() / 4; ++q)
          for (std::size_t a = 0; a < 4; ++a) cyclic[4 * q + a] = tp[4 * q + cycle[a]];
        return to_numpy(nodal_areas(as_span(coords), cyclic, num_nodes));
      },
      py::arg("coords"), py::arg("quads_tp"), py::arg("num_nodes"),
      "Nodal areas A_i = sum over quads of the integral of N_i dA (2x2 Gauss).\n\n"
      "coords: (num_nodes, 3) float64. quads_tp: (m, 4) int32 node indices in dolfinx's\n"
      "TENSOR-PRODUCT order (v0, v1, v2, v3), i.e. the cycle around the facet is v0-v1-v3-v2.\n"
      "Returns (num_nodes,) float64.");

  m.def(
      "nodal_areas_tri",
      [](const RealArray& coords, const IndexArray& triangles, std::size_t num_nodes) {
        check_shape(coords, "coords", {static_cast<py::ssize_t>(num_nodes), 3});
        check_shape(triangles, "triangles", {any, 3});
        return to_numpy(nodal_areas_tri(as_span(coords), as_span(triangles), num_nodes));
      },
      py::arg("coords"), py::arg("triangles"), py::arg("num_nodes"),
      "Nodal areas of linear triangles: a third of each triangle's area per vertex.\n\n"
      "coords: (num_nodes, 3) float64; triangles: (m, 3) int32. Returns (num_nodes,) float64.");
}

}  // namespace hypercontact::python
