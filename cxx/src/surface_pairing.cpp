#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <hypercontact/node_to_surface.hpp>
#include <stdexcept>
#include <string>

#include "surface_pairing.hpp"

namespace hypercontact {

namespace {

/// Projection onto the facet's bilinear surface continued beyond its edges: Newton on
/// F(ξ) = ½ |x_s − x_M(ξ)|² with ξ free, from ξ0. Returns false unless it converges to a
/// stationary point with H positive definite.
bool project_extended(const NodeCoordinates& master, const Eigen::Vector3d& x_s, Eigen::Vector2d& xi) {
  for (int it = 0; it < 30; ++it) {
    const Eigen::VectorXd N = facet_shape_functions(4, xi);
    const Eigen::Matrix<double, Eigen::Dynamic, 2> dN = facet_shape_derivatives(4, xi);
    const Eigen::Vector3d r = x_s - master * N;
    const Eigen::Matrix<double, 3, 2> a = master * dN;
    const Eigen::Vector3d x12 = master * facet_shape_mixed_derivatives(4);
    Eigen::Matrix2d H = a.transpose() * a;
    H(0, 1) -= r.dot(x12);
    H(1, 0) = H(0, 1);
    const Eigen::Vector2d grad = -a.transpose() * r;
    if (!(H.determinant() > 1e-12 * H.trace() * H.trace()) || !(H.trace() > 0)) return false;
    const Eigen::Vector2d step = H.ldlt().solve(grad);
    xi -= step;
    if (!xi.allFinite() || xi.cwiseAbs().maxCoeff() > 2.0) return false;
    if (step.norm() < 1e-13) return true;
  }
  return false;
}

}  // namespace

namespace detail {

void check_surface_input(const SurfaceContactInput& in, const char* who) {
  auto fail = [who](const std::string& what) { throw std::invalid_argument(std::string(who) + ": " + what); };
  if (in.x.size() % 3) fail("x must hold 3 coordinates per contact node");
  const std::size_t nn = in.x.size() / 3;
  if (in.dofs.size() != 3 * nn) fail("dofs must hold 3 entries per contact node (like x)");
  const std::size_t np = in.point_area.size();
  if (in.point_nodes.size() != 4 * np || in.point_weights.size() != 4 * np)
    fail("point_nodes and point_weights must hold 4 entries per slave point (like point_area)");
  if (in.facets.size() % 4) fail("facets must hold 4 nodes per master facet");
  if (in.edge_neighbour.size() != in.facets.size())
    fail("edge_neighbour must hold 4 entries per master facet (like facets)");
  if (in.offsets.size() != np + 1) fail("offsets must have one entry per slave point plus one");
  if (in.offsets.front() != 0 || in.offsets.back() != static_cast<std::int32_t>(in.candidates.size()))
    fail("offsets must start at 0 and end at the number of candidates");
  if (!(in.eps_n > 0)) fail("eps_n must be > 0");
  if (!in.multipliers.empty() && in.multipliers.size() != np)
    fail("multipliers has " + std::to_string(in.multipliers.size()) + " entries, expected " +
         std::to_string(np) + " (one per slave point) or none");
  for (double m : in.multipliers)
    if (!(std::isfinite(m) && m >= 0)) fail("multipliers must be finite and >= 0");
  for (std::int32_t n : in.point_nodes)
    if (n >= static_cast<std::int32_t>(nn)) fail("a slave point node index is out of range");
  for (std::int32_t n : in.facets)
    if (n < 0 || n >= static_cast<std::int32_t>(nn)) fail("a master facet node index is out of range");
  const std::int32_t nf = static_cast<std::int32_t>(in.facets.size() / 4);
  for (std::int32_t f : in.candidates)
    if (f < 0 || f >= nf) fail("a candidate facet index is out of range");
  for (std::int32_t f : in.edge_neighbour)
    if (f >= nf) fail("an edge neighbour index is out of range");
}

std::vector<char> master_boundary_nodes(const SurfaceContactInput& in) {
  const std::size_t nn = in.x.size() / 3;
  const std::size_t nf = in.facets.size() / 4;
  // Nodes on the master surface's boundary: the ends of edges without a neighbour.
  std::vector<char> boundary_node(nn, 0);
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 4; ++k)
      if (in.edge_neighbour[4 * f + k] < 0) {
        boundary_node[in.facets[4 * f + k]] = 1;
        boundary_node[in.facets[4 * f + (k + 1) % 4]] = 1;
      }
  return boundary_node;
}

bool closed_normal_element(const SurfaceContactInput& in, const std::vector<char>& boundary_node,
                           std::size_t p, SurfaceContactState& s, SlavePointPairing& pr,
                           NodeCoordinates& master, SurfaceContact& e) {
  pr = pair_slave_point(in, boundary_node, p, s);
  const double lambda = in.multipliers.empty() ? 0.0 : in.multipliers[p];
  // Augmented or smoothed: active where ĝ < λ_N/ε_N + δ, and ĝ ≥ g when g > 0, so a larger g is open.
  const bool general = lambda > 0 || in.smoothing > 0;
  if (pr.status != PairingStatus::Paired ||
      (pr.gap > pr.touch && !(general && pr.gap < lambda / in.eps_n + in.smoothing)))
    return false;
  master = gather_facet(pr.facet, in.facets, 4, in.x);
  e = node_to_surface(pr.slave, pr.weights, master, pr.projection, in.point_area[p], in.eps_n, pr.touch,
                      lambda, in.smoothing);
  if (!e.closed) return false;
  ++s.num_closed;
  s.pressure[p] = e.pressure;
  return true;
}

void element_dofs(const SurfaceContactInput& in, std::span<const std::int32_t> nodes,
                  std::int32_t facet, std::span<std::int32_t> out) {
  std::size_t j = 0;
  const auto add = [&](std::int32_t node) {
    for (int k = 0; k < 3; ++k) out[j++] = in.dofs[3 * node + k];
  };
  for (const std::int32_t node : nodes) add(node);
  for (int i = 0; i < 4; ++i) add(in.facets[4 * facet + i]);
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

SlavePointPairing pair_slave_point(const SurfaceContactInput& in, const std::vector<char>& boundary_node,
                                   std::size_t p, SurfaceContactState& s) {
  SlavePointPairing out;
  const auto begin = in.offsets[p], end = in.offsets[p + 1];
  if (begin == end) return out;
  // The slave point.
  int ns = 0;
  for (int i = 0; i < 4; ++i) ns += in.point_nodes[4 * p + i] >= 0;
  out.slave.resize(3, ns);
  out.weights.resize(ns);
  for (int i = 0, j = 0; i < 4; ++i) {
    const std::int32_t n = in.point_nodes[4 * p + i];
    if (n < 0) continue;
    out.slave.col(j) = Eigen::Map<const Eigen::Vector3d>(&in.x[3 * n]);
    out.weights[j++] = in.point_weights[4 * p + i];
    out.nodes.push_back(n);
  }
  const Eigen::Vector3d x_s = out.slave * out.weights;
  const ClosestFacet closest =
      closest_facet(x_s, in.candidates.subspan(begin, end - begin), in.facets, 4, in.x);
  FacetProjection proj = closest.projection;
  const std::int32_t f = closest.facet;
  bool on_boundary = false;
  if (proj.feature == Feature::Edge)
    on_boundary = in.edge_neighbour[4 * f + proj.local_index] < 0;
  else if (proj.feature == Feature::Vertex)
    on_boundary = boundary_node[in.facets[4 * f + proj.local_index]];
  const NodeCoordinates master = gather_facet(f, in.facets, 4, in.x);
  if (on_boundary) {
    // On the rim of the master surface: a point that overhangs it by at most kOverhang (in ξ,
    // i.e. kOverhang/2 of the facet's size) is projected onto the facet continued beyond its
    // edge, as a face point (smooth, no spurious tangential force); farther out it is off.
    constexpr double kOverhang = 0.05;
    Eigen::Vector2d xi = proj.xi;
    if (project_extended(master, x_s, xi) && xi.cwiseAbs().maxCoeff() <= 1.0 + kOverhang) {
      proj.xi = xi;
      proj.feature = Feature::Face;
      proj.local_index = -1;
      proj.point = master * facet_shape_functions(4, xi);
      proj.distance = (x_s - proj.point).norm();
      proj.normal = facet_normal(master, xi);
      on_boundary = false;
    }
  }
  out.facet = f;
  out.projection = proj;
  s.facet[p] = f;
  s.feature[p] = static_cast<std::int32_t>(proj.feature == Feature::Face   ? 0
                                           : proj.feature == Feature::Edge ? 1
                                                                           : 2);
  s.xi[2 * p] = proj.xi[0];
  s.xi[2 * p + 1] = proj.xi[1];
  for (int k = 0; k < 3; ++k) s.normal[3 * p + k] = proj.normal[k];
  const Eigen::Vector3d r = x_s - proj.point;
  const double gap = r.dot(proj.normal);
  s.gap[p] = out.gap = gap;
  if (on_boundary && (r - gap * proj.normal).norm() > 1e-8 * r.norm()) {
    out.status = PairingStatus::OffSurface;
    s.status[p] = static_cast<std::int32_t>(out.status);
    s.gap[p] = out.gap = r.norm();  // open, at this distance from the master surface's rim
    return out;
  }
  out.status = PairingStatus::Paired;
  s.status[p] = static_cast<std::int32_t>(out.status);
  // Meshes built in touch have g = ±rounding: count them closed (see node_to_surface).
  out.touch = 1e-10 * (master.col(2) - master.col(0)).norm();
  return out;
}

}  // namespace detail

}  // namespace hypercontact
