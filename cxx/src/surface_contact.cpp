#include <algorithm>
#include <stdexcept>
#include <string>
#include <hypercontact/smooth_master.hpp>
#include <hypercontact/surface_contact.hpp>

#include "smooth_points.hpp"
#include "surface_point.hpp"

namespace hypercontact {

namespace {

/// The faceted element of point p, if closed (also the smooth master's fallback).
template <int NM>
void faceted_point(const SurfaceContactInput& in, const NarrowPhase& narrow, std::size_t p,
                   SurfaceContactEvaluation& out, detail::ClosedPoint<NM>& point) {
  if (!detail::closed_normal_element<NM>(in, narrow, p, out, point)) return;
  const SurfaceContact& e = point.element;
  const int ns = point.slave.num_nodes;
  const int n = 3 * (ns + NM);
  ContactElements::Slot slot = out.elements.append(static_cast<std::int32_t>(p), n, n);
  detail::element_dofs(in, point.slave.nodes(), point.pairing.facet, slot.rows);
  std::copy(slot.rows.begin(), slot.rows.end(), slot.columns.begin());
  slot.residual = e.residual;
  slot.tangent = e.tangent;
  for (int i = 0; i < ns; ++i) out.force -= e.residual.segment<3>(3 * i);
}

/// Every slave point against facets of NM nodes.
template <int NM>
void evaluate_points(const SurfaceContactInput& in, const NarrowPhase& narrow,
                     SurfaceContactEvaluation& out) {
  detail::ClosedPoint<NM> point;
  for (std::size_t p = 0; p < in.point_area.size(); ++p) faceted_point<NM>(in, narrow, p, out, point);
}

/// Every slave point against a smooth master of facets of NM nodes.
template <int NM>
void evaluate_smooth(const SurfaceContactInput& in, const NarrowPhase& narrow,
                     SurfaceContactEvaluation& out) {
  detail::ClosedPoint<NM> point;
  detail::evaluate_smooth_points<NM>(
      in, narrow, out, out.elements, nullptr, nullptr,
      [&](std::size_t p) { faceted_point<NM>(in, narrow, p, out, point); });
}

}  // namespace

SurfaceContactEvaluation evaluate_surface_contact(const SurfaceContactInput& in) {
  detail::check_surface_input(in, "evaluate_surface_contact");
  const NarrowPhase narrow({in.x, in.facets, in.edge_neighbour});
  SurfaceContactEvaluation out;
  detail::init_state(out, in.point_area.size());
  out.elements.numbering = DofNumbering::Global;
  if (in.smooth_master) {
    switch (in.facets.nodes_per_facet) {
      case 3:
        evaluate_smooth<3>(in, narrow, out);
        break;
      case 4:
        evaluate_smooth<4>(in, narrow, out);
        break;
      case 6:
        evaluate_smooth<6>(in, narrow, out);
        break;
      default:
        evaluate_smooth<9>(in, narrow, out);
        break;
    }
    return out;
  }
  switch (in.facets.nodes_per_facet) {
    case 3: evaluate_points<3>(in, narrow, out); break;
    case 4: evaluate_points<4>(in, narrow, out); break;
    case 6: evaluate_points<6>(in, narrow, out); break;
    default: evaluate_points<9>(in, narrow, out); break;
  }
  return out;
}

}  // namespace hypercontact
