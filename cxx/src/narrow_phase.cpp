#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <hypercontact/narrow_phase.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {

/// Order of preference at equal distance.
int rank(Feature f) { return f == Feature::Face ? 0 : f == Feature::Edge ? 1 : 2; }

void check_nodes_per_facet(int nodes_per_facet, const char* who) {
  if (nodes_per_facet != 3 && nodes_per_facet != 4 && nodes_per_facet != 6 && nodes_per_facet != 9)
    throw std::invalid_argument(std::string(who) + ": nodes_per_facet must be 3, 4, 6 or 9, got " +
                                std::to_string(nodes_per_facet));
}

template <int NM>
FacetNodes<NM> gather(std::int32_t facet, const FacetConnectivity& facets,
                      std::span<const double> coords) {
  const std::size_t num_nodes = coords.size() / 3;
  if (facet < 0 || static_cast<std::size_t>(facet) >= facets.size())
    throw std::out_of_range("gather_facet: facet " + std::to_string(facet) + " out of range [0, " +
                            std::to_string(facets.size()) + ")");
  FacetNodes<NM> x;
  for (int a = 0; a < NM; ++a) {
    const std::int32_t node = facets.node(static_cast<std::size_t>(facet), a);
    if (node < 0 || static_cast<std::size_t>(node) >= num_nodes)
      throw std::out_of_range("gather_facet: facet " + std::to_string(facet) + " has node " +
                              std::to_string(node) + " out of range [0, " +
                              std::to_string(num_nodes) + ")");
    for (int i = 0; i < 3; ++i) x(i, a) = coords[3 * static_cast<std::size_t>(node) + i];
  }
  return x;
}

/// closest_facet for facets of NM nodes, the arguments checked.
template <int NM>
ClosestFacet closest_of(const Eigen::Vector3d& x_s, std::span<const std::int32_t> candidates,
                        const FacetConnectivity& facets, std::span<const double> coords) {
  bool have = false;
  ClosestFacet best{};
  double best_length = 0;
  for (const std::int32_t facet : candidates) {
    const FacetNodes<NM> x = gather<NM>(facet, facets, coords);
    FacetProjection p;
    try {
      p = project_to_facet<NM>(x, x_s);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("closest_facet: candidate facet " + std::to_string(facet) + ": " +
                                  e.what());
    }
    constexpr int nc = facet_corners<NM>;
    double length = 0;
    for (int a = 0; a < nc; ++a) length = std::max(length, (x.col((a + 1) % nc) - x.col(a)).norm());
    bool better = !have;
    if (have) {
      const double tol =
          1e-12 * (std::max(length, best_length) + std::max(p.distance, best.projection.distance));
      if (p.distance < best.projection.distance - tol) {
        better = true;
      } else if (p.distance <= best.projection.distance + tol) {
        const int r = rank(p.feature), r_best = rank(best.projection.feature);
        better = r < r_best || (r == r_best && facet < best.facet);
      }
    }
    if (better) {
      best = {facet, p};
      best_length = length;
      have = true;
    }
  }
  return best;
}

/// How far ξ lies outside the reference facet, as the fraction of a facet edge: quadrilateral
/// (|ξ|∞ − 1)/2 (ξ spans 2), triangle max(−ξ1, −ξ2, ξ1 + ξ2 − 1).
constexpr double max_overhang = 0.025;
template <int NM>
bool within_overhang(const Eigen::Vector2d& xi) {
  if constexpr (facet_corners<NM> == 4) return xi.cwiseAbs().maxCoeff() <= 1.0 + 2 * max_overhang;
  return std::max({-xi[0], -xi[1], xi[0] + xi[1] - 1}) <= max_overhang;
}

/// Projection onto the facet's surface continued beyond its edges: Newton on
/// F(ξ) = ½ |x_s − x_M(ξ)|² with ξ free, from ξ. Returns false unless it converges to a
/// stationary point with H positive definite.
template <int NM>
bool project_extended(const FacetNodes<NM>& master, const Eigen::Vector3d& x_s,
                      Eigen::Vector2d& xi) {
  for (int it = 0; it < 30; ++it) {
    const Eigen::Vector3d r = x_s - master * facet_shape_functions<NM>(xi);
    const Eigen::Matrix<double, 3, 2> a = master * facet_shape_derivatives<NM>(xi);
    const Eigen::Matrix2d H =
        distance_hessian(a, r, master * facet_shape_second_derivatives<NM>(xi));
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

template <int NM>
requires FacetNodeCount<NM> FacetNodes<NM> gather_facet(std::int32_t facet,
                                                        const FacetConnectivity& facets,
                                                        std::span<const double> coords) {
  if (facets.nodes_per_facet != NM)
    throw std::invalid_argument("gather_facet: the facets have " +
                                std::to_string(facets.nodes_per_facet) + " nodes, not " +
                                std::to_string(NM));
  return gather<NM>(facet, facets, coords);
}
template FacetNodes<3> gather_facet<3>(std::int32_t, const FacetConnectivity&,
                                       std::span<const double>);
template FacetNodes<4> gather_facet<4>(std::int32_t, const FacetConnectivity&,
                                       std::span<const double>);
template FacetNodes<6> gather_facet<6>(std::int32_t, const FacetConnectivity&,
                                       std::span<const double>);
template FacetNodes<9> gather_facet<9>(std::int32_t, const FacetConnectivity&,
                                       std::span<const double>);

NodeCoordinates gather_facet(std::int32_t facet, const FacetConnectivity& facets,
                             std::span<const double> coords) {
  check_nodes_per_facet(facets.nodes_per_facet, "gather_facet");
  switch (facets.nodes_per_facet) {
    case 3: return gather<3>(facet, facets, coords);
    case 4: return gather<4>(facet, facets, coords);
    case 6: return gather<6>(facet, facets, coords);
    default: return gather<9>(facet, facets, coords);
  }
}

ClosestFacet closest_facet(const Eigen::Vector3d& x_s, std::span<const std::int32_t> candidates,
                           const FacetConnectivity& facets, std::span<const double> coords) {
  if (candidates.empty()) throw std::invalid_argument("closest_facet: no candidate facets");
  check_nodes_per_facet(facets.nodes_per_facet, "closest_facet");
  if (facets.nodes.size() % static_cast<std::size_t>(facets.nodes_per_facet) != 0 ||
      coords.size() % 3 != 0)
    throw std::invalid_argument("closest_facet: facets must be num_facets x " +
                                std::to_string(facets.nodes_per_facet) +
                                " and coords num_nodes x 3 (row-major)");
  if (!x_s.allFinite()) throw std::invalid_argument("closest_facet: x_s must be finite");
  switch (facets.nodes_per_facet) {
    case 3: return closest_of<3>(x_s, candidates, facets, coords);
    case 4: return closest_of<4>(x_s, candidates, facets, coords);
    case 6: return closest_of<6>(x_s, candidates, facets, coords);
    default: return closest_of<9>(x_s, candidates, facets, coords);
  }
}

NarrowPhase::NarrowPhase(const MasterSurface& master) : master_(master) {
  constexpr const char* who = "NarrowPhase";
  const auto fail = [who](const std::string& what) {
    throw std::invalid_argument(std::string(who) + ": " + what);
  };
  const FacetConnectivity& f = master.facets;
  check_nodes_per_facet(f.nodes_per_facet, who);
  const int k = f.nodes_per_facet, nc = f.corners();
  if (master.x.size() % 3) fail("x must hold 3 coordinates per node");
  if (f.nodes.size() % static_cast<std::size_t>(k))
    fail("facets must hold " + std::to_string(k) + " nodes per master facet");
  if (master.edge_neighbour.size() != f.size() * static_cast<std::size_t>(nc))
    fail("edge_neighbour must hold " + std::to_string(nc) +
         " entries per master facet (one per edge)");
  const auto nn = static_cast<std::int32_t>(master.x.size() / 3);
  const auto nf = static_cast<std::int32_t>(f.size());
  for (std::int32_t n : f.nodes)
    if (n < 0 || n >= nn) fail("a master facet node index is out of range");
  for (std::int32_t g : master.edge_neighbour)
    if (g >= nf) fail("an edge neighbour index is out of range");
  // The rim: the nodes of edges without a neighbour (their ends, and the edge node of a curved
  // facet).
  rim_.assign(static_cast<std::size_t>(nn), 0);
  for (std::size_t facet = 0; facet < f.size(); ++facet)
    for (int e = 0; e < nc; ++e)
      if (master.edge_neighbour[static_cast<std::size_t>(nc) * facet + e] < 0) {
        rim_[f.node(facet, e)] = 1;
        rim_[f.node(facet, (e + 1) % nc)] = 1;
        if (k > nc) rim_[f.node(facet, nc + e)] = 1;
      }
}

PointPairing NarrowPhase::pair(const Eigen::Vector3d& x_s,
                               std::span<const std::int32_t> candidates) const {
  if (candidates.empty()) return {};
  if (!x_s.allFinite()) throw std::invalid_argument("NarrowPhase: the slave point is not finite");
  switch (master_.facets.nodes_per_facet) {
    case 3: return pair_on<3>(x_s, candidates);
    case 4: return pair_on<4>(x_s, candidates);
    case 6: return pair_on<6>(x_s, candidates);
    default: return pair_on<9>(x_s, candidates);
  }
}

template <int NM>
PointPairing NarrowPhase::pair_on(const Eigen::Vector3d& x_s,
                                  std::span<const std::int32_t> candidates) const {
  const ClosestFacet closest = closest_of<NM>(x_s, candidates, master_.facets, master_.x);
  PointPairing out;
  out.facet = closest.facet;
  out.projection = closest.projection;
  FacetProjection& proj = out.projection;
  const auto f = static_cast<std::size_t>(closest.facet);
  bool on_boundary = false;
  if (proj.feature == Feature::Edge)
    on_boundary = master_.edge_neighbour[facet_corners<NM> * f +
                                         static_cast<std::size_t>(proj.local_index)] < 0;
  else if (proj.feature == Feature::Vertex)
    on_boundary = on_rim(master_.facets.node(f, proj.local_index));
  const FacetNodes<NM> master = gather<NM>(closest.facet, master_.facets, master_.x);
  if (on_boundary) {
    Eigen::Vector2d xi = proj.xi;
    if (project_extended<NM>(master, x_s, xi) && within_overhang<NM>(xi)) {
      proj.xi = xi;
      proj.feature = Feature::Face;
      proj.local_index = -1;
      proj.point = master * facet_shape_functions<NM>(xi);
      proj.distance = (x_s - proj.point).norm();
      proj.normal = facet_normal<NM>(master, xi);
      on_boundary = false;
    }
  }
  const Eigen::Vector3d r = x_s - proj.point;
  out.gap = r.dot(proj.normal);
  if (on_boundary && (r - out.gap * proj.normal).norm() > 1e-8 * r.norm()) {
    out.status = PairingStatus::OffSurface;
    out.gap = r.norm();  // open, at this distance from the master surface's rim
    return out;
  }
  out.status = PairingStatus::Paired;
  // Meshes built in touch have g = ±rounding: count them closed (see node_to_surface).
  out.touch = 1e-10 * (master.col(2) - master.col(0)).norm();
  return out;
}

}  // namespace hypercontact
