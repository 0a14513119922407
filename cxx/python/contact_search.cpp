// Bindings of contact_search.hpp.
#include <hypercontact/contact_search.hpp>
#include <utility>

#include "array.hpp"

namespace hypercontact::python {

namespace {

/// The vector as a 1-D numpy array that owns it (no copy).
py::array_t<std::int32_t> to_numpy(std::vector<std::int32_t>&& v) {
  auto* owned = new std::vector<std::int32_t>(std::move(v));
  py::capsule free_when_done(owned,
                             [](void* p) { delete static_cast<std::vector<std::int32_t>*>(p); });
  return py::array_t<std::int32_t>(static_cast<py::ssize_t>(owned->size()), owned->data(),
                                   free_when_done);
}

/// find_candidates or find_candidates_brute_force, behind the same checks of the numpy shapes.
template <ContactCandidates (*search)(std::span<const double>, std::span<const double>,
                                      std::span<const std::int32_t>, int, double)>
std::pair<py::array_t<std::int32_t>, py::array_t<std::int32_t>> search_numpy(
    const RealArray& slave_x, const RealArray& master_x, const IndexArray& facets, double capture) {
  check_shape(slave_x, "slave_x", {any, 3});
  check_shape(master_x, "master_x", {any, 3});
  check_shape(facets, "facets", {any, any});
  const auto k = static_cast<int>(facets.shape(1));
  if (k != 3 && k != 4 && k != 6 && k != 9)
    throw py::value_error("facets: expected shape (*, 3), (*, 4), (*, 6) or (*, 9), got " +
                          shape_string({facets.shape(0), facets.shape(1)}));
  ContactCandidates found;
  {
    py::gil_scoped_release release;  // the arrays stay referenced by the caller
    found = search(as_span(slave_x), as_span(master_x), as_span(facets), k, capture);
  }
  return {to_numpy(std::move(found.offsets)), to_numpy(std::move(found.indices))};
}

}  // namespace

void declare_contact_search(py::module_& m) {
  m.def("find_candidates", &search_numpy<&find_candidates>, py::arg("slave_x"), py::arg("master_x"),
        py::arg("facets"), py::arg("capture"),
        "Broad-phase contact search: the candidate master facets of every slave point.\n\n"
        "Facet f is a candidate of point x iff x lies in the closed axis-aligned bounding box of\n"
        "f's nodes inflated by `capture` on every side (a superset of the facets within distance\n"
        "`capture`). k-d tree over the slave points, O((n + f) log n + candidates).\n\n"
        "slave_x: (n, 3) float64. master_x: (m, 3) float64. facets: (f, 3) or (f, 4) int32\n"
        "indices into master_x (triangles or quadrilaterals, any node order). capture: >= 0.\n"
        "Returns (offsets, indices), int32 arrays in CSR form: the candidates of point i are\n"
        "indices[offsets[i]:offsets[i + 1]], ascending; offsets has n + 1 entries.\n"
        "Raises ValueError on a bad shape, a non-finite coordinate or capture, IndexError on a\n"
        "facet index outside [0, m).");

  m.def("find_candidates_brute_force", &search_numpy<&find_candidates_brute_force>,
        py::arg("slave_x"), py::arg("master_x"), py::arg("facets"), py::arg("capture"),
        "Reference for tests and benchmarks: find_candidates by testing every (point, facet)\n"
        "pair, O(n f); the same arguments and the identical result.");
}

}  // namespace hypercontact::python
