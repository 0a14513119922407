#include "surface_point.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace hypercontact::detail {

void check_surface_input(const SurfaceContactInput& in, const char* who) {
  auto fail = [who](const std::string& what) {
    throw std::invalid_argument(std::string(who) + ": " + what);
  };
  const int k = in.facets.nodes_per_facet;
  if (k != 3 && k != 4 && k != 6 && k != 9)
    fail("facets must have 3, 4, 6 or 9 nodes per facet, got " + std::to_string(k));
  if (in.x.size() % 3) fail("x must hold 3 coordinates per contact node");
  const std::size_t nn = in.x.size() / 3;
  if (in.dofs.size() != 3 * nn) fail("dofs must hold 3 entries per contact node (like x)");
  const std::size_t np = in.point_area.size();
  const std::size_t stride = nodes_per_point(in);
  if (stride < 1 || stride > static_cast<std::size_t>(max_slave_nodes) ||
      in.point_nodes.size() != stride * np || in.point_weights.size() != stride * np)
    fail("point_nodes and point_weights must hold the same number of entries, 1 to " +
         std::to_string(max_slave_nodes) + ", per slave point (like point_area)");
  if (in.offsets.size() != np + 1) fail("offsets must have one entry per slave point plus one");
  if (in.offsets.front() != 0 ||
      in.offsets.back() != static_cast<std::int32_t>(in.candidates.size()))
    fail("offsets must start at 0 and end at the number of candidates");
  if (!(in.eps_n > 0)) fail("eps_n must be > 0");
  if (!in.multipliers.empty() && in.multipliers.size() != np)
    fail("multipliers has " + std::to_string(in.multipliers.size()) + " entries, expected " +
         std::to_string(np) + " (one per slave point) or none");
  for (double m : in.multipliers)
    if (!(std::isfinite(m) && m >= 0)) fail("multipliers must be finite and >= 0");
  for (std::int32_t n : in.point_nodes)
    if (n >= static_cast<std::int32_t>(nn)) fail("a slave point node index is out of range");
  const auto nf = static_cast<std::int32_t>(in.facets.size());
  for (std::int32_t f : in.candidates)
    if (f < 0 || f >= nf) fail("a candidate facet index is out of range");
}

std::size_t nodes_per_point(const SurfaceContactInput& in) {
  const std::size_t np = in.point_area.size();
  return np == 0 ? 1 : in.point_nodes.size() / np;
}

void init_state(SurfaceContactState& s, std::size_t np) {
  s.facet.assign(np, -1);
  s.feature.assign(np, -1);
  s.status.assign(np, static_cast<std::int32_t>(PairingStatus::NoCandidate));
  s.xi.assign(2 * np, 0.0);
  s.gap.assign(np, 0.0);
  s.pressure.assign(np, 0.0);
  s.normal.assign(3 * np, 0.0);
  s.force.setZero();
  s.num_closed = 0;
}

SlavePoint slave_point(const SurfaceContactInput& in, std::size_t p) {
  SlavePoint out;
  const std::size_t stride = nodes_per_point(in);
  for (std::size_t i = 0; i < stride; ++i) out.num_nodes += in.point_nodes[stride * p + i] >= 0;
  out.x.resize(3, out.num_nodes);
  out.weights.resize(out.num_nodes);
  for (std::size_t i = 0, j = 0; i < stride; ++i) {
    const std::int32_t n = in.point_nodes[stride * p + i];
    if (n < 0) continue;
    out.x.col(j) = Eigen::Map<const Eigen::Vector3d>(&in.x[3 * static_cast<std::size_t>(n)]);
    out.weights[j] = in.point_weights[stride * p + i];
    out.node_storage[j++] = n;
  }
  return out;
}

void record_pairing(const PointPairing& pr, std::size_t p, SurfaceContactState& s) {
  s.facet[p] = pr.facet;
  const Feature feature = pr.projection.feature;
  s.feature[p] = feature == Feature::Face ? 0 : feature == Feature::Edge ? 1 : 2;
  s.xi[2 * p] = pr.projection.xi[0];
  s.xi[2 * p + 1] = pr.projection.xi[1];
  for (int k = 0; k < 3; ++k) s.normal[3 * p + k] = pr.projection.normal[k];
  s.gap[p] = pr.gap;
  s.status[p] = static_cast<std::int32_t>(pr.status);
}

template <int NM>
bool closed_normal_element(const SurfaceContactInput& in, const NarrowPhase& narrow, std::size_t p,
                           SurfaceContactState& s, ClosedPoint<NM>& out) {
  const auto begin = in.offsets[p], end = in.offsets[p + 1];
  if (begin == end) return false;  // NoCandidate
  out.slave = slave_point(in, p);
  const PointPairing& pr = out.pairing =
      narrow.pair(out.slave.position(), in.candidates.subspan(begin, end - begin));
  record_pairing(pr, p, s);
  const double lambda = in.multipliers.empty() ? 0.0 : in.multipliers[p];
  // Augmented or smoothed: active where ĝ < λ_N/ε_N + δ, and ĝ ≥ g when g > 0, so a larger g is
  // open.
  const bool general = lambda > 0 || in.smoothing > 0;
  if (pr.status != PairingStatus::Paired ||
      (pr.gap > pr.touch && !(general && pr.gap < lambda / in.eps_n + in.smoothing)))
    return false;
  out.master = gather_facet<NM>(pr.facet, in.facets, in.x);
  out.element = node_to_surface<NM>(out.slave.x, out.slave.weights, out.master, pr.projection,
                                    in.point_area[p], in.eps_n, pr.touch, lambda, in.smoothing);
  if (!out.element.closed) return false;
  ++s.num_closed;
  s.pressure[p] = out.element.pressure;
  return true;
}

template bool closed_normal_element<3>(const SurfaceContactInput&, const NarrowPhase&, std::size_t,
                                       SurfaceContactState&, ClosedPoint<3>&);
template bool closed_normal_element<4>(const SurfaceContactInput&, const NarrowPhase&, std::size_t,
                                       SurfaceContactState&, ClosedPoint<4>&);
template bool closed_normal_element<6>(const SurfaceContactInput&, const NarrowPhase&, std::size_t,
                                       SurfaceContactState&, ClosedPoint<6>&);
template bool closed_normal_element<9>(const SurfaceContactInput&, const NarrowPhase&, std::size_t,
                                       SurfaceContactState&, ClosedPoint<9>&);

void element_dofs(const SurfaceContactInput& in, std::span<const std::int32_t> nodes,
                  std::int32_t facet, std::span<std::int32_t> out) {
  std::size_t j = 0;
  const auto add = [&](std::int32_t node) {
    for (int k = 0; k < 3; ++k) out[j++] = in.dofs[3 * static_cast<std::size_t>(node) + k];
  };
  for (const std::int32_t node : nodes) add(node);
  for (int a = 0; a < in.facets.nodes_per_facet; ++a)
    add(in.facets.node(static_cast<std::size_t>(facet), a));
}

}  // namespace hypercontact::detail
