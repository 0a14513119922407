#include <hypercontact/node_to_surface.hpp>
#include <hypercontact/surface_contact.hpp>

#include "surface_pairing.hpp"

namespace hypercontact {

SurfaceContactEvaluation evaluate_surface_contact(const SurfaceContactInput& in) {
  detail::check_surface_input(in, "evaluate_surface_contact");
  const std::size_t np = in.point_area.size();
  const std::vector<char> boundary_node = detail::master_boundary_nodes(in);
  SurfaceContactEvaluation out;
  detail::init_state(out, np);
  out.elements.numbering = DofNumbering::Global;
  for (std::size_t p = 0; p < np; ++p) {
    detail::SlavePointPairing pr;
    NodeCoordinates master;
    SurfaceContact e;
    if (!detail::closed_normal_element(in, boundary_node, p, out, pr, master, e)) continue;
    const int ns = static_cast<int>(pr.nodes.size());
    const int n = 3 * (ns + 4);
    ContactElements::Slot slot = out.elements.append(static_cast<std::int32_t>(p), n, n);
    detail::element_dofs(in, pr.nodes, pr.facet, slot.rows);
    std::copy(slot.rows.begin(), slot.rows.end(), slot.columns.begin());
    slot.residual = e.residual;
    slot.tangent = e.tangent;
    for (int i = 0; i < ns; ++i) out.force -= e.residual.segment<3>(3 * i);
  }
  return out;
}

}  // namespace hypercontact
