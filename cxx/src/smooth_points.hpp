// Internal: every slave point of a surface evaluation against a smooth master (smooth_master.hpp),
// shared by the frictionless and the frictional family (surface_contact.cpp,
// surface_contact_friction.cpp): the closest facet from the narrow phase, the walk across edges
// to the facet where the projection along the normal field lands, the smooth element (with the
// point's friction history if any), and the faceted element where the smooth one is not defined.
#pragma once

#include <algorithm>
#include <hypercontact/smooth_master.hpp>
#include <hypercontact/surface_contact.hpp>
#include <hypercontact/surface_contact_friction.hpp>
#include <vector>

#include "surface_point.hpp"

namespace hypercontact::detail {

/// Evaluates every slave point of `in` against the smooth master: records the pairing in s and
/// appends each closed point's element to `elements`. With `fin` (and `fs`, the same object as s)
/// the friction of fin's history is added and recorded. A point whose normal-field projection
/// does not converge, runs more than twice the closest distance, crosses the rim by more than
/// 2.5 % of a facet or meets a facet with a crease node (is_crease) is handed to `faceted(p)` (the
/// faceted element of the point, as without smoothing); one whose foot lies on a facet that is
/// not among its candidates is open (OffSurface, feature 3).
template <int NM, typename Faceted>
void evaluate_smooth_points(const SurfaceContactInput& in, const NarrowPhase& narrow,
                            SurfaceContactState& s, ContactElements& elements,
                            const SurfaceFrictionInput* fin, SurfaceFrictionState* fs,
                            Faceted faceted) {
  const std::size_t nn = in.x.size() / 3;
  const NodeFacets at(in.facets, nn);
  std::vector<Eigen::Vector3d> m(nn, Eigen::Vector3d::Zero());
  std::vector<char> crease(nn, 0);
  for (std::size_t a = 0; a < nn; ++a)
    if (at.offsets[a + 1] > at.offsets[a]) {
      m[a] = nodal_normal_value(static_cast<std::int32_t>(a), at, in.facets, in.x);
      crease[a] = is_crease(static_cast<std::int32_t>(a), m[a], at, in.facets, in.x);
    }
  const int corners = in.facets.corners();
  const double rim = facet_corners<NM> == 4 ? 0.05 : 0.025;
  const Eigen::Vector2d centre =
      facet_corners<NM> == 4 ? Eigen::Vector2d(0, 0) : Eigen::Vector2d(1.0 / 3, 1.0 / 3);
  std::vector<std::int32_t> visited;
  std::array<std::int32_t, NM> old_nodes{};
  for (std::size_t p = 0; p < in.point_area.size(); ++p) {
    const auto begin = in.offsets[p], end = in.offsets[p + 1];
    if (begin == end) continue;  // NoCandidate
    const auto candidates = in.candidates.subspan(begin, end - begin);
    const SlavePoint slave = slave_point(in, p);
    const Eigen::Vector3d x_s = slave.position();
    const PointPairing pr = narrow.pair(x_s, candidates);
    if (pr.status != PairingStatus::Paired) {
      record_pairing(pr, p, s);
      continue;
    }
    std::int32_t f = pr.facet;
    Eigen::Vector2d xi0 = pr.projection.xi;
    NormalFieldProjection proj;
    bool found = false;
    visited.clear();
    for (int walk = 0; walk < 8; ++walk) {
      visited.push_back(f);
      const FacetNodes<NM> X = gather_facet<NM>(f, in.facets, in.x);
      FacetNodes<NM> M;
      for (int a = 0; a < NM; ++a)
        M.col(a) = m[static_cast<std::size_t>(in.facets.node(static_cast<std::size_t>(f), a))];
      bool sharp = false;
      for (int a = 0; a < NM; ++a)
        sharp = sharp || crease[static_cast<std::size_t>(in.facets.node(static_cast<std::size_t>(f), a))];
      if (sharp) break;  // a facet at a crease keeps the faceted element
      proj = project_along_normals<NM>(x_s, X, M, xi0);
      if (!proj.converged) break;
      // a projection far longer than the closest distance has run along a normal field that
      // turns fast (the walls of a tight fold): not this facet's point
      // (touch is 1e-10 of the facet's diagonal: the allowance is 1e-8 of it)
      if (std::abs(proj.gap) > 2.0 * pr.projection.distance + 1e2 * pr.touch) break;
      const Overhang oh = overhang<NM>(proj.xi);
      if (oh.amount <= 1e-10) {
        found = true;
        break;
      }
      const std::int32_t next = in.edge_neighbour[static_cast<std::size_t>(corners * f + oh.edge)];
      if (next < 0) {
        found = oh.amount <= rim;
        break;
      }
      if (std::find(visited.begin(), visited.end(), next) != visited.end()) break;
      if (std::find(candidates.begin(), candidates.end(), next) == candidates.end()) {
        // the point's foot along the normals lies beyond its candidates: on a facet farther than
        // the capture distance, or (self-contact) on its own neighbourhood
        break;
      }
      f = next;
      xi0 = centre;
    }
    // The faceted element where the smooth one is not defined, except beside an edge or vertex
    // (the closest point off the face with r more than 60° from the facet's normal, |g| < |r|/2):
    // that point is not over or under the master, and the faceted element would press it by
    // its whole distance |r| with the sign of the facet's plane, which flips as it moves (the
    // apex of a tube folded flat, beside the other wall's end facets).
    if (!found && pr.projection.feature != Feature::Face &&
        std::abs(pr.gap) < 0.5 * pr.projection.distance) {
      s.facet[p] = pr.facet;
      s.feature[p] = 3;
      s.status[p] = static_cast<std::int32_t>(PairingStatus::OffSurface);
      s.gap[p] = pr.projection.distance;
      continue;
    }
    if (!found) {
      faceted(p);
      continue;
    }
    s.facet[p] = f;
    s.feature[p] = 3;
    s.status[p] = static_cast<std::int32_t>(PairingStatus::Paired);
    s.xi[2 * p] = proj.xi[0];
    s.xi[2 * p + 1] = proj.xi[1];
    for (int k = 0; k < 3; ++k) s.normal[3 * p + k] = proj.normal[k];
    s.gap[p] = proj.gap;
    const double lambda = in.multipliers.empty() ? 0.0 : in.multipliers[p];
    SmoothFrictionHistory history;
    if (fin != nullptr) {
      history.eps_t = fin->eps_t;
      history.mu = fin->mu;
      const std::int32_t old = fin->old_facet[p];
      if (old >= 0) {
        for (int b = 0; b < NM; ++b)
          old_nodes[static_cast<std::size_t>(b)] = in.facets.node(static_cast<std::size_t>(old), b);
        history.old_nodes = old_nodes;
        history.xi_old = {fin->xi_old[2 * p], fin->xi_old[2 * p + 1]};
        history.t_old = Eigen::Vector3d(&fin->t_old[3 * p]);
      }
    }
    const SmoothContact e = smooth_node_to_surface<NM>(
        slave.nodes(), slave.x, slave.weights, f, at, in.facets, in.x, proj, in.point_area[p],
        in.eps_n, pr.touch, lambda, in.smoothing, fin != nullptr ? &history : nullptr);
    if (!e.closed) continue;
    ++s.num_closed;
    s.pressure[p] = e.pressure;
    const int ns = slave.num_nodes;
    const int rows = static_cast<int>(e.residual.size());
    const int cols = 3 * static_cast<int>(e.columns.size());
    ContactElements::Slot slot = elements.append(static_cast<std::int32_t>(p), rows, cols);
    element_dofs(in, slave.nodes(), f, slot.rows);
    for (std::size_t j = 0; j < e.columns.size(); ++j)
      for (std::size_t k = 0; k < 3; ++k)
        slot.columns[3 * j + k] = in.dofs[3 * static_cast<std::size_t>(e.columns[j]) + k];
    slot.residual = e.residual;
    slot.tangent = e.tangent;
    // the normal force: −w p_N n on the slave point (the residual holds friction too)
    s.force += in.point_area[p] * e.pressure * e.normal;
    if (fs != nullptr) {
      for (int k = 0; k < 3; ++k) {
        fs->traction[3 * p + static_cast<std::size_t>(k)] = e.traction[k];
        fs->slip_increment[3 * p + static_cast<std::size_t>(k)] = e.slip_increment[k];
      }
      fs->dissipation[p] = e.dissipation;
      fs->stick[p] = static_cast<std::int32_t>(e.state);
      for (int i = 0; i < ns; ++i) fs->total_force -= e.residual.template segment<3>(3 * i);
    }
  }
}

}  // namespace hypercontact::detail
