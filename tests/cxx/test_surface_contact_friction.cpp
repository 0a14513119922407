// Coulomb friction against a deformable master surface, one evaluation per slave point: each
// element is the normal element plus the surface_friction of the point against its closest
// facet with its history (rows [slave, facet], columns [slave, facet, old facet]); the stored
// tangent is the derivative of the stored residual (central differences) in stick and slip, on
// a face (nodes and Gauss points), an inner edge and an inner vertex, with the history on the
// same or another facet or none, with multipliers and with smoothing.
#include <gtest/gtest.h>

#include <hypercontact/node_to_surface.hpp>
#include <hypercontact/surface_contact_friction.hpp>
#include <hypercontact/surface_friction.hpp>
#include <set>
#include <stdexcept>
#include <vector>

#include "surface_scene.hpp"

namespace hypercontact {
namespace {

using test::SurfaceScene;

constexpr double eps_t = 300.0, mu = 0.4;

/// A scene and every point's history.
struct FrictionScene {
  SurfaceScene contact;
  std::vector<std::int32_t> old_facet;
  std::vector<double> xi_old, t_old;

  SurfaceFrictionEvaluation evaluate(std::span<const double> y) const {
    return evaluate_surface_friction({contact.input(y), old_facet, xi_old, t_old, eps_t, mu});
  }
  double tangent_error() const {
    return test::dense_tangent_error([this](std::span<const double> y) { return evaluate(y); },
                                     contact.x);
  }
};

/// face_scene with histories: point 0 on its own facet close by (stick), point 1 on another
/// facet far away (slip), point 2 (open) none; Gauss points: none, none, the same facet with a
/// traction, another facet. (On the triangulated master the facets are the first triangles of
/// the same cells, and the history ξ's other points of them.)
FrictionScene face_friction(bool triangles = false) {
  return {test::face_scene(triangles),
          {0, 2, -1, -1, -1, 2, 3},
          {-0.2, 0.21, 0.5, -0.9, 0, 0, 0, 0, 0, 0, -0.3, 0.1, -0.5, -0.9},
          {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2.0, -1.0, 0.5, 0, 0, 0, 0, 0, 0}};
}

/// The valley's edge point and the bowl's vertex point, with a history on facet 1 (slip).
FrictionScene feature_friction(SurfaceScene scene, Eigen::Vector2d xi_old) {
  return {std::move(scene), {1}, {xi_old[0], xi_old[1]}, {0.5, 0.2, 0.0}};
}

std::set<StickSlip> states(const SurfaceFrictionEvaluation& e) {
  std::set<StickSlip> s;
  for (std::int32_t v : e.stick) s.insert(static_cast<StickSlip>(v));
  return s;
}

/// Compares every point with the old path (closest_facet, node_to_surface, surface_friction
/// with the history or, without one, the current point).
void expect_normal_plus_friction_elements(const FrictionScene& f) {
  const SurfaceScene& s = f.contact;
  const SurfaceFrictionEvaluation e = f.evaluate(s.x);
  std::size_t k = 0;
  for (std::size_t p = 0; p < s.point_area.size(); ++p) {
    const SurfaceScene::Pairing pr = s.pairing(p);
    const double lambda = s.multiplier(p);
    const SurfaceContact c =
        node_to_surface(pr.slave, pr.weights, pr.master, pr.closest.projection, s.point_area[p],
                        s.eps_n, pr.touch, lambda, s.smoothing);
    const bool history = f.old_facet[p] >= 0;
    const std::int32_t old = history ? f.old_facet[p] : pr.closest.facet;
    const NodeCoordinates old_master = gather_facet(old, {s.facets, s.nodes_per_facet}, s.x);
    const Eigen::Vector2d xi_old =
        history ? Eigen::Vector2d(&f.xi_old[2 * p]) : pr.closest.projection.xi;
    const Eigen::Vector3d t_old =
        history ? Eigen::Vector3d(&f.t_old[3 * p]) : Eigen::Vector3d::Zero();
    const SurfaceFriction fr =
        surface_friction(pr.slave, pr.weights, pr.master, pr.closest.projection, old_master, xi_old,
                         t_old, s.point_area[p], s.eps_n, eps_t, mu, lambda, s.smoothing);
    if (!c.closed) {
      EXPECT_EQ(e.stick[p], static_cast<std::int32_t>(StickSlip::Open));
      continue;
    }
    EXPECT_EQ(e.stick[p], static_cast<std::int32_t>(fr.state));
    EXPECT_EQ(Eigen::Vector3d(&e.traction[3 * p]), fr.traction);
    EXPECT_EQ(e.dissipation[p], fr.dissipation);
    const std::size_t el = k++;
    ASSERT_LT(el, e.elements.size());
    std::vector<std::int32_t> columns = s.element_dofs(pr);
    const auto n = static_cast<Eigen::Index>(columns.size());
    const int k = s.nodes_per_facet;
    for (int a = 0; a < k; ++a)
      for (int d = 0; d < 3; ++d) columns.push_back(s.dofs[3 * s.facets[k * old + a] + d]);
    EXPECT_EQ(
        std::vector<std::int32_t>(e.elements.columns(el).begin(), e.elements.columns(el).end()),
        columns);
    const Eigen::VectorXd R = c.residual + fr.residual.head(n);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n + 3 * k);
    K.leftCols(n) = c.tangent;
    if (history) K += fr.tangent.topRows(n);
    const Eigen::Map<const Eigen::VectorXd> stored(e.elements.element_residual(el).data(), n);
    EXPECT_LE(test::relative_error(stored, R), 1e-14) << "point " << p;
    EXPECT_LE(test::relative_error(e.elements.element_tangent(el), K), 1e-14) << "point " << p;
  }
  EXPECT_EQ(k, e.elements.size());
}

TEST(SurfaceFrictionEvaluation, ElementsAreNormalPlusFrictionWithTheHistory) {
  const FrictionScene face = face_friction();
  EXPECT_EQ(states(face.evaluate(face.contact.x)),
            (std::set<StickSlip>{StickSlip::Open, StickSlip::Stick, StickSlip::Slip}));
  expect_normal_plus_friction_elements(face);
  expect_normal_plus_friction_elements(feature_friction(test::valley_scene(), {0.5, 0.3}));
  expect_normal_plus_friction_elements(feature_friction(test::bowl_scene(), {0.5, 0.5}));
  FrictionScene augmented = face_friction();
  augmented.contact.multipliers.assign(augmented.contact.point_area.size(), 30.0);
  expect_normal_plus_friction_elements(augmented);
}

TEST(SurfaceFrictionEvaluation, TangentIsTheDerivativeOfTheResidualInEveryBranch) {
  EXPECT_LE(face_friction().tangent_error(), 1e-6);
  for (auto [f, feature] : {std::pair{feature_friction(test::valley_scene(), {0.5, 0.3}), 1},
                            std::pair{feature_friction(test::bowl_scene(), {0.5, 0.5}), 2}}) {
    const SurfaceFrictionEvaluation e = f.evaluate(f.contact.x);
    ASSERT_EQ(e.elements.size(), 1u);
    EXPECT_EQ(e.feature[0], feature);  // 1 edge, 2 vertex
    EXPECT_EQ(e.stick[0], static_cast<std::int32_t>(StickSlip::Slip));
    EXPECT_LE(f.tangent_error(), 1e-6);
    f.xi_old = {e.xi[0], e.xi[1]};  // the same material point: stick
    f.old_facet = {e.facet[0]};
    EXPECT_EQ(f.evaluate(f.contact.x).stick[0], static_cast<std::int32_t>(StickSlip::Stick));
    EXPECT_LE(f.tangent_error(), 1e-6);
  }
  FrictionScene augmented = face_friction();
  augmented.contact.multipliers.assign(augmented.contact.point_area.size(), 30.0);
  EXPECT_LE(augmented.tangent_error(), 1e-6);
  augmented.contact.smoothing = 0.05;
  EXPECT_LE(augmented.tangent_error(), 1e-6);
}

TEST(SurfaceFrictionEvaluation, TriangulatedMaster) {
  const FrictionScene f = face_friction(true);
  const SurfaceFrictionEvaluation e = f.evaluate(f.contact.x);
  EXPECT_EQ(e.elements.size(), 6u);
  EXPECT_TRUE(states(e).count(StickSlip::Slip));
  expect_normal_plus_friction_elements(f);
  EXPECT_LE(f.tangent_error(), 1e-6);
}

TEST(SurfaceFrictionEvaluation, RejectsAnInconsistentHistory) {
  FrictionScene f = face_friction();
  f.old_facet[0] = 4;  // 4 facets
  EXPECT_THROW(f.evaluate(f.contact.x), std::invalid_argument);
  f = face_friction();
  f.xi_old.pop_back();
  EXPECT_THROW(f.evaluate(f.contact.x), std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
