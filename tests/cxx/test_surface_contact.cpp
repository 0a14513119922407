// Deformable–deformable normal contact, one evaluation per slave point: each element is the
// node_to_surface element of the point against its closest facet (closest_facet), on the dofs of
// [slave nodes, facet]; the stored tangent is the derivative of the stored residual (central
// differences) on faces (nodes and Gauss points), an inner edge, an inner vertex, with
// multipliers and with smoothing; open and unpaired points add nothing.
#include <gtest/gtest.h>

#include <hypercontact/node_to_surface.hpp>
#include <hypercontact/surface_contact.hpp>
#include <set>
#include <stdexcept>
#include <vector>

#include "surface_scene.hpp"

namespace hypercontact {
namespace {

using test::SurfaceScene;

SurfaceContactEvaluation evaluate(const SurfaceScene& s, std::span<const double> y) {
  return evaluate_surface_contact(s.input(y));
}

double tangent_error(const SurfaceScene& s) {
  return test::dense_tangent_error([&s](std::span<const double> y) { return evaluate(s, y); }, s.x);
}

/// Compares every point with the old path (closest_facet, then node_to_surface with the touch
/// tolerance) and returns the features of the closed points.
std::set<Feature> expect_node_to_surface_elements(const SurfaceScene& s) {
  const SurfaceContactEvaluation e = evaluate(s, s.x);
  EXPECT_EQ(e.elements.numbering, DofNumbering::Global);
  std::set<Feature> features;
  std::size_t k = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (std::size_t p = 0; p < s.point_area.size(); ++p) {
    const SurfaceScene::Pairing pr = s.pairing(p);
    const SurfaceContact c =
        node_to_surface(pr.slave, pr.weights, pr.master, pr.closest.projection, s.point_area[p],
                        s.eps_n, pr.touch, s.multiplier(p), s.smoothing);
    EXPECT_EQ(e.status[p], static_cast<std::int32_t>(PairingStatus::Paired));
    EXPECT_EQ(e.facet[p], pr.closest.facet);
    EXPECT_NEAR(e.gap[p], c.gap, 1e-15);
    EXPECT_EQ(e.pressure[p], c.pressure);
    if (!c.closed) continue;
    features.insert(c.feature);
    if (k >= e.elements.size()) {
      ADD_FAILURE() << "no element for closed point " << p;
      return features;
    }
    const std::size_t el = k++;
    EXPECT_EQ(e.elements.point[el], static_cast<std::int32_t>(p));
    const std::vector<std::int32_t> dofs = s.element_dofs(pr);
    EXPECT_EQ(std::vector<std::int32_t>(e.elements.rows(el).begin(), e.elements.rows(el).end()),
              dofs);
    EXPECT_EQ(
        std::vector<std::int32_t>(e.elements.columns(el).begin(), e.elements.columns(el).end()),
        dofs);
    const Eigen::Map<const Eigen::VectorXd> R(e.elements.element_residual(el).data(),
                                              static_cast<Eigen::Index>(dofs.size()));
    EXPECT_LE(test::relative_error(R, c.residual), 1e-14) << "point " << p;
    EXPECT_LE(test::relative_error(e.elements.element_tangent(el), c.tangent), 1e-14)
        << "point " << p;
    for (std::size_t i = 0; i < pr.nodes.size(); ++i) force -= c.residual.segment<3>(3 * i);
  }
  EXPECT_EQ(k, e.elements.size());
  EXPECT_EQ(e.num_closed, static_cast<std::int32_t>(k));
  EXPECT_LE((e.force - force).norm(), 1e-13 * force.norm());
  return features;
}

TEST(SurfaceContactEvaluation, ElementsAreNodeToSurfaceOfTheClosestFacet) {
  EXPECT_EQ(expect_node_to_surface_elements(test::face_scene()), std::set<Feature>{Feature::Face});
  EXPECT_EQ(expect_node_to_surface_elements(test::valley_scene()),
            std::set<Feature>{Feature::Edge});
  EXPECT_EQ(expect_node_to_surface_elements(test::bowl_scene()),
            std::set<Feature>{Feature::Vertex});
  SurfaceScene augmented = test::face_scene();
  augmented.multipliers.assign(augmented.point_area.size(), 30.0);
  expect_node_to_surface_elements(augmented);
  augmented.smoothing = 0.02;
  expect_node_to_surface_elements(augmented);
}

TEST(SurfaceContactEvaluation, TangentIsTheDerivativeOfTheResidualInEveryBranch) {
  const SurfaceScene face = test::face_scene();
  EXPECT_EQ(evaluate(face, face.x).elements.size(), 6u);  // two nodes and four Gauss points
  EXPECT_LE(tangent_error(face), 1e-6);
  EXPECT_LE(tangent_error(test::valley_scene()), 1e-6);
  EXPECT_LE(tangent_error(test::bowl_scene()), 1e-6);
  // With multipliers the node above facet 1 (g ≈ 0.2) stays open, one at g ≈ 0.026 < λ/ε_N = 0.03
  // closes.
  SurfaceScene augmented = test::face_scene();
  augmented.add_slave_node({1.5, 1.5, 0.0}, 0.1);
  augmented.multipliers.assign(augmented.point_area.size(), 30.0);
  const SurfaceContactEvaluation e = evaluate(augmented, augmented.x);
  EXPECT_EQ(e.elements.size(), 7u);
  EXPECT_GT(e.gap.back(), 0);
  EXPECT_LE(tangent_error(augmented), 1e-6);
  augmented.smoothing = 0.05;
  EXPECT_LE(tangent_error(augmented), 1e-6);
}

TEST(SurfaceContactEvaluation, TriangulatedMaster) {
  // Flat: the point (0.7, 0.2, −0.03) is over triangle 0 (nodes (0,0), (1,0), (1,1)) at
  // ξ = (0.5, 0.2), N = (0.3, 0.5, 0.2): R = w ε_N g [n; −N_a n], n = e_z.
  SurfaceScene flat;
  flat.add_master_grid(
      2, 2, 0.0, 0.0, 1.0, [](double, double) { return 0.0; }, true);
  flat.add_slave_node({0.7, 0.2, -0.03}, 0.3);
  const SurfaceContactEvaluation e = evaluate(flat, flat.x);
  ASSERT_EQ(e.elements.size(), 1u);
  EXPECT_EQ(e.facet[0], 0);
  const double f = 0.3 * flat.eps_n * -0.03;
  const std::vector<double> N{0.3, 0.5, 0.2};
  ASSERT_EQ(e.elements.rows(0).size(), 12u);  // the slave node and three master nodes
  EXPECT_NEAR(e.elements.element_residual(0)[2], f, 1e-12);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(e.elements.element_residual(0)[3 * (1 + a) + 2], -f * N[a], 1e-12);
    EXPECT_NEAR(e.elements.element_residual(0)[3 * (1 + a)], 0.0, 1e-15);
  }
  // Warped, with nodes and Gauss points: the old path's elements, and their derivatives.
  const SurfaceScene warped = test::face_scene(true);
  EXPECT_EQ(expect_node_to_surface_elements(warped), std::set<Feature>{Feature::Face});
  EXPECT_EQ(evaluate(warped, warped.x).elements.size(), 6u);
  EXPECT_LE(tangent_error(warped), 1e-6);
  EXPECT_LE(tangent_error(flat), 1e-6);
}

TEST(SurfaceContactEvaluation, OpenOffSurfaceAndUnpairedPointsAddNothing) {
  SurfaceScene s;
  s.add_master_grid(1, 1, 0.0, 0.0, 1.0, [](double, double) { return 0.0; });
  s.add_slave_node({0.5, 0.5, 0.1}, 0.2);   // open
  s.add_slave_node({1.5, 0.5, -0.1}, 0.2);  // beyond the rim: OffSurface
  const std::int32_t n = s.add_node({0.5, 0.5, -0.1});
  s.add_point({n}, {1.0}, 0.2, /*with_candidates=*/false);  // below, but no candidate
  const SurfaceContactEvaluation e = evaluate(s, s.x);
  EXPECT_EQ(e.elements.size(), 0u);
  EXPECT_EQ(e.num_closed, 0);
  EXPECT_EQ(e.status, (std::vector<std::int32_t>{2, 1, 0}));
  EXPECT_GT(e.gap[0], 0);
  EXPECT_NEAR(e.gap[1], std::hypot(0.5, 0.1), 1e-14);  // the distance to the rim
  EXPECT_EQ(e.facet[2], -1);
}

TEST(SurfaceContactEvaluation, RejectsInconsistentInput) {
  SurfaceScene s = test::face_scene();
  s.dofs.pop_back();
  EXPECT_THROW(evaluate(s, s.x), std::invalid_argument);
  s = test::face_scene();
  s.candidates[0] = 99;
  EXPECT_THROW(evaluate(s, s.x), std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
