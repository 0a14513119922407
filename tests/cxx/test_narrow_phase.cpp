// Narrow phase: the closest of the candidate facets (ties face < edge < vertex, then the lower
// facet index; quadrilaterals and triangles; bad input), and the pairing of a slave point: the
// gap's sign from the winning facet's normal on a face, an inner edge and an inner vertex, the
// rim continued by 2.5 % of a facet (quadrilateral and triangle) and OffSurface beyond it, the
// touch tolerance, no candidates, and an inconsistent master.
#include <gtest/gtest.h>

#include <cmath>
#include <hypercontact/narrow_phase.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "surface_scene.hpp"

namespace hypercontact {
namespace {

/// A 2 × 2 patch of unit quadrilaterals in z = 0 (nodes j * 3 + i at (i, j, 0)).
struct Patch {
  std::vector<double> coords;
  std::vector<std::int32_t> quads{0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7};
  Patch() {
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) coords.insert(coords.end(), {double(i), double(j), 0.0});
  }
  ClosestFacet closest(const Eigen::Vector3d& x, std::vector<std::int32_t> candidates) const {
    return closest_facet(x, candidates, {quads, 4}, coords);
  }
};

TEST(ClosestFacet, PicksTheClosestWithTieRules) {
  const Patch patch;
  const std::vector<std::int32_t> all{0, 1, 2, 3}, reversed{3, 2, 1, 0};
  for (const auto& candidates : {all, reversed}) {
    const ClosestFacet inside = patch.closest({1.5, 0.5, -0.1}, candidates);
    EXPECT_EQ(inside.facet, 1);
    EXPECT_EQ(inside.projection.feature, Feature::Face);
    EXPECT_NEAR(inside.projection.distance, 0.1, 1e-15);
    // Above the edge shared by facets 0 and 1 (and the node shared by all): Face on both, the
    // lower index wins.
    EXPECT_EQ(patch.closest({1.0, 0.5, -0.1}, candidates).facet, 0);
    EXPECT_EQ(patch.closest({1.0, 1.0, 0.2}, candidates).facet, 0);
    EXPECT_EQ(patch.closest({1.5, 1.0, 0.2}, candidates).facet, 1);
    // Beyond the boundary: an edge of facet 1; at node 5, a vertex of facets 1 and 3.
    const ClosestFacet edge = patch.closest({2.5, 0.5, 0.0}, candidates);
    EXPECT_EQ(edge.facet, 1);
    EXPECT_EQ(edge.projection.feature, Feature::Edge);
    const ClosestFacet vertex = patch.closest({2.5, 1.0, 0.0}, candidates);
    EXPECT_EQ(vertex.facet, 1);
    EXPECT_EQ(vertex.projection.feature, Feature::Vertex);
  }
  // Only the candidates are tried.
  EXPECT_EQ(patch.closest({1.5, 0.5, -0.1}, {2, 3}).facet, 3);
}

TEST(ClosestFacet, FaceWinsATieAgainstAnEdgeOfAHigherRankedFacet) {
  // Facet 0 hinges down from the edge x = 1 of facet 1 (flat): above that edge, facet 1 gives a
  // Face point on its boundary, facet 0 an Edge point, at the same distance.
  const std::vector<double> coords{1, 0, 0, 2, 0, -1, 2, 1, -1, 1, 1, 0, 0, 0, 0, 0, 1, 0};
  const std::vector<std::int32_t> quads{0, 1, 2, 3, 4, 0, 3, 5};
  const ClosestFacet c =
      closest_facet({1.0, 0.5, 0.3}, std::vector<std::int32_t>{0, 1}, {quads, 4}, coords);
  EXPECT_EQ(c.facet, 1);
  EXPECT_EQ(c.projection.feature, Feature::Face);
  const FacetProjection other =
      project_to_facet(gather_facet(0, {quads, 4}, coords), {1.0, 0.5, 0.3});
  EXPECT_EQ(other.feature, Feature::Edge);
  EXPECT_NEAR(other.distance, c.projection.distance, 1e-15);
}

TEST(ClosestFacet, TrianglesAndBadInput) {
  const std::vector<double> coords{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const std::vector<std::int32_t> tris{0, 1, 2, 1, 3, 2};
  EXPECT_EQ(
      closest_facet({0.8, 0.7, 0.1}, std::vector<std::int32_t>{0, 1}, {tris, 3}, coords).facet, 1);
  const auto call = [&](std::vector<std::int32_t> candidates, std::vector<std::int32_t> facets,
                        int npf) {
    return closest_facet({0.2, 0.2, 0.1}, candidates, {facets, npf}, coords);
  };
  EXPECT_THROW(call({}, tris, 3), std::invalid_argument);
  EXPECT_THROW(call({0, 2}, tris, 3), std::out_of_range);
  EXPECT_THROW(call({-1}, tris, 3), std::out_of_range);
  EXPECT_THROW(call({0}, {0, 1, 9}, 3), std::out_of_range);
  EXPECT_THROW(call({0}, tris, 5), std::invalid_argument);
  EXPECT_THROW(call({0}, {0, 1, 2, 1}, 3), std::invalid_argument);
  try {
    call({0, 1}, {0, 1, 2, 0, 1, 1}, 3);
    ADD_FAILURE() << "a degenerate candidate must throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("candidate facet 1"), std::string::npos) << e.what();
  }
}

/// The narrow phase of a scene's master surface.
NarrowPhase narrow_phase(const test::SurfaceScene& s) {
  return NarrowPhase({s.x, {s.facets, s.nodes_per_facet}, s.edge_neighbour});
}

std::vector<std::int32_t> all_facets(const test::SurfaceScene& s) {
  std::vector<std::int32_t> all(s.facets.size() / s.nodes_per_facet);
  for (std::size_t f = 0; f < all.size(); ++f) all[f] = static_cast<std::int32_t>(f);
  return all;
}

TEST(NarrowPhase, TheGapHasTheSignOfTheWinningFacetsSideOnFacesEdgesAndVertices) {
  // Valley z = 0.5 |x|: below its line both facets are closest on their common edge (facet 0
  // wins); above it both on their faces (facet 0 wins the tie).
  const test::SurfaceScene valley = test::valley_scene();
  const NarrowPhase narrow = narrow_phase(valley);
  const Eigen::Vector3d below(0.01, 0.55, -0.2), above(0.0, 0.5, 0.1);
  const PointPairing edge = narrow.pair(below, all_facets(valley));
  EXPECT_EQ(edge.status, PairingStatus::Paired);
  EXPECT_EQ(edge.facet, 0);
  EXPECT_EQ(edge.projection.feature, Feature::Edge);
  const Eigen::Vector3d n0 = Eigen::Vector3d(0.5, 0, 1).normalized();  // facet 0: z = −0.5 x
  EXPECT_NEAR(edge.gap, (below - Eigen::Vector3d(0, 0.55, 0)).dot(n0), 1e-15);
  EXPECT_LT(edge.gap, 0);
  const PointPairing face = narrow.pair(above, all_facets(valley));
  EXPECT_EQ(face.facet, 0);
  EXPECT_EQ(face.projection.feature, Feature::Face);
  EXPECT_NEAR(face.gap, 0.1 / std::sqrt(1.25), 1e-15);
  // Bowl z = 0.5 (|x| + |y|): below the node at the origin every facet's closest point is it.
  const test::SurfaceScene bowl = test::bowl_scene();
  const PointPairing vertex = narrow_phase(bowl).pair({0.01, 0.02, -0.2}, all_facets(bowl));
  EXPECT_EQ(vertex.projection.feature, Feature::Vertex);
  EXPECT_EQ(vertex.status, PairingStatus::Paired);
  EXPECT_LT(vertex.gap, 0);
  EXPECT_NEAR(vertex.gap, Eigen::Vector3d(0.01, 0.02, -0.2).dot(vertex.projection.normal), 1e-15);
}

TEST(NarrowPhase, TheRimIsContinuedByTwoAndAHalfPercentThenOffSurface) {
  for (const bool triangles : {false, true}) {
    test::SurfaceScene s;
    s.add_master_grid(
        1, 1, 0.0, 0.0, 1.0, [](double, double) { return 0.0; }, triangles);
    const NarrowPhase narrow = narrow_phase(s);
    // Beyond x = 1 by 2 % of the facet (a quadrilateral's ξ1 = 1.04; for the triangles, beyond
    // the edge x = 1 of triangle 0): continued, a face point with the plane's gap.
    const PointPairing near = narrow.pair({1.02, 0.4, -0.01}, all_facets(s));
    EXPECT_EQ(near.status, PairingStatus::Paired) << "triangles " << triangles;
    EXPECT_EQ(near.projection.feature, Feature::Face);
    EXPECT_NEAR(near.gap, -0.01, 1e-15);
    EXPECT_NEAR(near.projection.point.x(), 1.02, 1e-14);
    // By 3 %: off the surface, at its distance from the rim.
    const PointPairing far = narrow.pair({1.03, 0.4, -0.01}, all_facets(s));
    EXPECT_EQ(far.status, PairingStatus::OffSurface) << "triangles " << triangles;
    EXPECT_NEAR(far.gap, std::hypot(0.03, 0.01), 1e-15);
    // Paired points are closed up to a rounding of the facet's size: 1e-10 |x_2 − x_0|, the
    // diagonal of the square, of which both triangles have it as their edge 0 → 2.
    EXPECT_NEAR(near.touch, 1e-10 * std::sqrt(2.0), 1e-25);
  }
}

TEST(NarrowPhase, NoCandidateAndAnInconsistentMaster) {
  const test::SurfaceScene s = test::face_scene();
  const NarrowPhase narrow = narrow_phase(s);
  const PointPairing none = narrow.pair({0.5, 0.5, 0}, {});
  EXPECT_EQ(none.status, PairingStatus::NoCandidate);
  EXPECT_EQ(none.facet, -1);
  EXPECT_TRUE(narrow.on_rim(0));   // a corner of the 2 × 2 master
  EXPECT_FALSE(narrow.on_rim(4));  // its centre
  const std::vector<std::int32_t> short_neighbours(s.edge_neighbour.begin(),
                                                   s.edge_neighbour.end() - 1);
  std::vector<std::int32_t> bad_node = s.facets;
  bad_node[0] = 1000;
  EXPECT_THROW(NarrowPhase({s.x, {s.facets, 5}, s.edge_neighbour}), std::invalid_argument);
  EXPECT_THROW(NarrowPhase({s.x, {s.facets, 4}, short_neighbours}), std::invalid_argument);
  EXPECT_THROW(NarrowPhase({s.x, {bad_node, 4}, s.edge_neighbour}), std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
