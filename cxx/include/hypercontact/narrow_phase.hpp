// Narrow phase of deformable–deformable contact: the master surface (its facets with their
// number of nodes, their edge neighbours), the closest of a slave point's candidate facets, and
// how the point is paired with it (the gap and its sign, the master surface's rim).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <hypercontact/facet_projection.hpp>
#include <span>
#include <vector>

namespace hypercontact {

/// Master facets: facet f has the nodes nodes[k f], …, nodes[k f + k − 1], k = nodes_per_facet
/// (3: linear triangles, 4: bilinear quadrilaterals, 6: quadratic triangles, 9: biquadratic
/// quadrilaterals), corners counter-clockwise seen from outside the master body, then the edge
/// nodes and the centre (conventions of facet_shape.hpp).
struct FacetConnectivity {
  std::span<const std::int32_t> nodes;
  int nodes_per_facet = 4;

  std::size_t size() const { return nodes.size() / static_cast<std::size_t>(nodes_per_facet); }
  /// Corners (= edges) of a facet: 3 for triangles, 4 for quadrilaterals.
  int corners() const { return nodes_per_facet == 3 || nodes_per_facet == 6 ? 3 : 4; }
  std::int32_t node(std::size_t facet, int a) const {
    return nodes[static_cast<std::size_t>(nodes_per_facet) * facet + static_cast<std::size_t>(a)];
  }
};

/// The nodes of `facet` as a 3 × NM matrix (coords: num_nodes × 3, row-major). Throws
/// std::out_of_range on a facet or node index out of range, std::invalid_argument unless
/// facets.nodes_per_facet = NM.
template <int NM>
requires FacetNodeCount<NM> FacetNodes<NM> gather_facet(std::int32_t facet,
                                                        const FacetConnectivity& facets,
                                                        std::span<const double> coords);
/// The same as a 3 × nodes_per_facet matrix.
NodeCoordinates gather_facet(std::int32_t facet, const FacetConnectivity& facets,
                             std::span<const double> coords);

/// The closest of several candidate facets to a slave point.
struct ClosestFacet {
  std::int32_t facet;          ///< the winning candidate: a facet of `facets`
  FacetProjection projection;  ///< project_to_facet onto that facet
};

/// Projects x_s onto every candidate facet (any order) and returns the closest. Ties (distances
/// within 1e-12 (L + d), L the longest edge of the facets compared, d the distance) go to Face
/// over Edge over Vertex, then to the lower facet index.
/// Throws std::invalid_argument if candidates is empty, nodes_per_facet is not 3, 4, 6 or 9, sizes are
/// inconsistent, x_s is not finite or a candidate facet is degenerate (the message names it);
/// std::out_of_range on a candidate or node index out of range.
ClosestFacet closest_facet(const Eigen::Vector3d& x_s, std::span<const std::int32_t> candidates,
                           const FacetConnectivity& facets, std::span<const double> coords);

/// How one slave point was paired.
enum class PairingStatus : std::int32_t {
  NoCandidate = 0,  ///< the broad phase found no master facet near the point
  OffSurface = 1,   ///< closest point on the master surface's rim, the point outside its extent
  Paired = 2,       ///< projected onto a face, an inner edge or an inner vertex
};

/// A master surface: the current coordinates of its nodes (and possibly others', num_nodes × 3,
/// row-major), its facets, and edge_neighbour (one entry per facet edge, facets.corners() per
/// facet): the facet across edge k (corner k → k + 1) of facet f, −1 on the surface's boundary
/// (its rim).
struct MasterSurface {
  std::span<const double> x;
  FacetConnectivity facets;
  std::span<const std::int32_t> edge_neighbour;
};

/// The pairing of one slave point.
struct PointPairing {
  PairingStatus status = PairingStatus::NoCandidate;
  std::int32_t facet = -1;     ///< the closest facet (−1: no candidate)
  FacetProjection projection;  ///< onto that facet (continued over the rim: a face point)
  double gap = 0.0;            ///< signed gap (Paired), distance to the rim (OffSurface)
  double touch = 0.0;          ///< Paired: closed if gap ≤ touch (meshes built in touch)
};

/// The narrow phase against one master surface (its rim nodes found once).
///
/// pair(x_s, candidates): closest_facet over the candidates, then, with r = x_s − x_M(ξ*) and n
/// the winning facet's unit normal at ξ* (at the clamped ξ* on an edge or at a vertex):
///  - the gap is g = r·n: its sign is the side of the winning facet's plane at the closest point,
///    on a face, an inner edge (the lower-index facet of the two at equal distance) or an inner
///    vertex alike;
///  - a closest point on the rim (an edge without neighbour, or a vertex of one) is first
///    retried on the facet continued beyond its edges (Newton with ξ free): a point that
///    overhangs the rim by at most 2.5 % of the facet (quadrilateral: |ξ|∞ ≤ 1.05; triangle:
///    max(−ξ1, −ξ2, ξ1 + ξ2 − 1) ≤ 0.025) is paired as a face point there (smooth, no spurious
///    tangential force); otherwise, unless r is along n (|r − (r·n) n| ≤ 1e-8 |r|: within the
///    facet's extent), the point is OffSurface, with gap = |r| (open);
///  - touch = 1e-10 |x_2 − x_0| (a diagonal of a quadrilateral, an edge of a triangle): gaps of
///    rounding size count as closed, so that surfaces meshed in touch are closed at once.
/// No candidates: NoCandidate. Throws as closest_facet.
class NarrowPhase {
 public:
  /// Throws std::invalid_argument unless nodes_per_facet is 3, 4, 6 or 9, the sizes agree and every
  /// node and neighbour index is in range.
  explicit NarrowPhase(const MasterSurface& master);

  PointPairing pair(const Eigen::Vector3d& x_s, std::span<const std::int32_t> candidates) const;

  const MasterSurface& master() const { return master_; }
  /// Per node of x: true if it is a node of an edge of the master surface without a neighbour.
  bool on_rim(std::int32_t node) const { return rim_[static_cast<std::size_t>(node)] != 0; }

 private:
  template <int NM>
  PointPairing pair_on(const Eigen::Vector3d& x_s, std::span<const std::int32_t> candidates) const;

  MasterSurface master_;
  std::vector<char> rim_;
};

}  // namespace hypercontact
