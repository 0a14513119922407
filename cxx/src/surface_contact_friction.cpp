#include <algorithm>
#include <hypercontact/surface_contact_friction.hpp>
#include <hypercontact/surface_friction.hpp>
#include <stdexcept>
#include <string>

#include "smooth_points.hpp"
#include "surface_point.hpp"

namespace hypercontact {

namespace {

constexpr const char* who = "evaluate_surface_friction";

void check_history(const SurfaceFrictionInput& fin) {
  const std::size_t np = fin.contact.point_area.size();
  const auto nf = static_cast<std::int32_t>(fin.contact.facets.size());
  auto fail = [](const std::string& what) {
    throw std::invalid_argument(std::string(who) + ": " + what);
  };
  if (fin.old_facet.size() != np || fin.xi_old.size() != 2 * np || fin.t_old.size() != 3 * np)
    fail("old_facet, xi_old, t_old must hold 1, 2, 3 entries per slave point");
  for (std::int32_t f : fin.old_facet)
    if (f < -1 || f >= nf) fail("an old facet index is out of range");
  if (!(fin.eps_t > 0)) fail("eps_t must be > 0");
  if (!(fin.mu >= 0)) fail("mu must be >= 0");
}

SurfaceFrictionEvaluation empty_evaluation(std::size_t np) {
  SurfaceFrictionEvaluation s;
  detail::init_state(s, np);
  s.traction.assign(3 * np, 0.0);
  s.slip_increment.assign(3 * np, 0.0);
  s.dissipation.assign(np, 0.0);
  s.stick.assign(np, static_cast<std::int32_t>(StickSlip::Open));
  s.total_force.setZero();
  s.elements.numbering = DofNumbering::Global;
  return s;
}

/// The friction of closed point p against its current facet, with its history on facet `old`
/// (or none: the current point, t_old = 0).
template <int NM>
SurfaceFriction point_friction(const SurfaceFrictionInput& fin, std::size_t p,
                               const detail::ClosedPoint<NM>& point, std::int32_t old) {
  const SurfaceContactInput& in = fin.contact;
  const bool history = fin.old_facet[p] >= 0;
  const Eigen::Vector2d xi_old = history ? Eigen::Vector2d(fin.xi_old[2 * p], fin.xi_old[2 * p + 1])
                                         : point.pairing.projection.xi;
  const Eigen::Vector3d t_old =
      history ? Eigen::Vector3d(&fin.t_old[3 * p]) : Eigen::Vector3d::Zero();
  const FacetNodes<NM> old_master = gather_facet<NM>(old, in.facets, in.x);
  return surface_friction<NM, NM>(point.slave.x, point.slave.weights, point.master,
                                  point.pairing.projection, old_master, xi_old, t_old,
                                  in.point_area[p], in.eps_n, fin.eps_t, fin.mu,
                                  in.multipliers.empty() ? 0.0 : in.multipliers[p], in.smoothing);
}

void record_friction(const SurfaceFriction& fr, std::size_t p, SurfaceFrictionEvaluation& s) {
  for (int k = 0; k < 3; ++k) {
    s.traction[3 * p + k] = fr.traction[k];
    s.slip_increment[3 * p + k] = fr.slip_increment[k];
  }
  s.dissipation[p] = fr.dissipation;
  s.stick[p] = static_cast<std::int32_t>(fr.state);
}

/// Slave point p against facets of NM nodes (the faceted element with its friction).
template <int NM>
void friction_point(const SurfaceFrictionInput& fin, const NarrowPhase& narrow, std::size_t p,
                    SurfaceFrictionEvaluation& s, detail::ClosedPoint<NM>& point) {
  const SurfaceContactInput& in = fin.contact;
  if (!detail::closed_normal_element<NM>(in, narrow, p, s, point)) return;
  const bool history = fin.old_facet[p] >= 0;
  const std::int32_t old = history ? fin.old_facet[p] : point.pairing.facet;
  const SurfaceFriction fr = point_friction<NM>(fin, p, point, old);
  record_friction(fr, p, s);

  // Rows: slave nodes + current facet; columns: those + old facet.
  const SurfaceContact& e = point.element;
  const int ns = point.slave.num_nodes;
  const int n = 3 * (ns + NM), m = n + 3 * NM;
  ContactElements::Slot slot = s.elements.append(static_cast<std::int32_t>(p), n, m);
  detail::element_dofs(in, point.slave.nodes(), point.pairing.facet, slot.rows);
  std::copy(slot.rows.begin(), slot.rows.end(), slot.columns.begin());
  detail::element_dofs(in, {}, old, slot.columns.subspan(n));
  slot.residual = e.residual + fr.residual.head(n);
  slot.tangent.leftCols(n) = e.tangent;
  if (history) slot.tangent += fr.tangent.topRows(n);
  for (int i = 0; i < ns; ++i) {
    s.force -= e.residual.segment<3>(3 * i);
    s.total_force -= slot.residual.segment<3>(3 * i);
  }
}

/// Every slave point against facets of NM nodes.
template <int NM>
void evaluate_points(const SurfaceFrictionInput& fin, const NarrowPhase& narrow,
                     SurfaceFrictionEvaluation& s) {
  detail::ClosedPoint<NM> point;
  for (std::size_t p = 0; p < fin.contact.point_area.size(); ++p)
    friction_point<NM>(fin, narrow, p, s, point);
}

/// Every slave point against a smooth master of facets of NM nodes.
template <int NM>
void evaluate_smooth(const SurfaceFrictionInput& fin, const NarrowPhase& narrow,
                     SurfaceFrictionEvaluation& s) {
  detail::ClosedPoint<NM> point;
  detail::evaluate_smooth_points<NM>(fin.contact, narrow, s, s.elements, &fin, &s,
                                     [&](std::size_t p) { friction_point<NM>(fin, narrow, p, s, point); });
}

}  // namespace

SurfaceFrictionEvaluation evaluate_surface_friction(const SurfaceFrictionInput& fin) {
  const SurfaceContactInput& in = fin.contact;
  detail::check_surface_input(in, who);
  check_history(fin);
  const NarrowPhase narrow({in.x, in.facets, in.edge_neighbour});
  SurfaceFrictionEvaluation s = empty_evaluation(in.point_area.size());
  if (in.smooth_master) {
    switch (in.facets.nodes_per_facet) {
      case 3:
        evaluate_smooth<3>(fin, narrow, s);
        break;
      case 4:
        evaluate_smooth<4>(fin, narrow, s);
        break;
      case 6:
        evaluate_smooth<6>(fin, narrow, s);
        break;
      default:
        evaluate_smooth<9>(fin, narrow, s);
        break;
    }
    return s;
  }
  switch (in.facets.nodes_per_facet) {
    case 3: evaluate_points<3>(fin, narrow, s); break;
    case 4: evaluate_points<4>(fin, narrow, s); break;
    case 6: evaluate_points<6>(fin, narrow, s); break;
    default: evaluate_points<9>(fin, narrow, s); break;
  }
  return s;
}

}  // namespace hypercontact
