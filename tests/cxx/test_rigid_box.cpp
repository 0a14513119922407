// Rigid box: signed distance against an independent formula, features, ties, derivatives.
#include <gtest/gtest.h>

#include <cmath>
#include <hypercontact/obstacle.hpp>
#include <hypercontact/rigid_box.hpp>
#include <random>

#include "finite_difference.hpp"

namespace hypercontact {
namespace {

const RigidBox box{{-1, -0.5, 0}, {1, 0.5, 0.4}};

/// Reference signed distance of an axis-aligned box, written independently of the library:
/// with q = max(lo − x, x − hi) componentwise, sdf = |max(q, 0)| + min(max_i q_i, 0).
double reference_sdf(const RigidBox& b, const Eigen::Vector3d& x) {
  const Eigen::Vector3d q = (b.lo - x).cwiseMax(x - b.hi);
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

/// Whether c lies on the surface of b (inside up to tol, on some face plane up to tol).
bool on_surface(const RigidBox& b, const Eigen::Vector3d& c, double tol) {
  const bool within =
      ((c.array() >= b.lo.array() - tol) && (c.array() <= b.hi.array() + tol)).all();
  const bool on_face =
      ((c - b.lo).cwiseAbs().array() <= tol).any() || ((c - b.hi).cwiseAbs().array() <= tol).any();
  return within && on_face;
}

TEST(RigidBox, RandomPointsMatchReferenceSignedDistance) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> coordinate(-1.6, 1.6);
  int inside = 0, outside = 0;
  for (int k = 0; k < 4000; ++k) {
    const Eigen::Vector3d x(coordinate(rng), coordinate(rng), coordinate(rng));
    const ObstacleProjection p = project_to_box(box, x);
    ASSERT_NEAR(p.gap, reference_sdf(box, x), 1e-14) << "x = " << x.transpose();
    ASSERT_TRUE(p.normal.allFinite() && p.dnormal_dx.allFinite());
    ASSERT_NEAR(p.normal.norm(), 1.0, 1e-14);
    // x − g n is a closest point: on the surface, at distance |g| from x.
    ASSERT_TRUE(on_surface(box, x - p.gap * p.normal, 1e-13)) << "x = " << x.transpose();
    // Feature = number of coordinates outside [lo, hi] (Face when inside).
    const int clamped = ((x.array() < box.lo.array()) || (x.array() > box.hi.array())).count();
    const Feature expected[] = {Feature::Face, Feature::Face, Feature::Edge, Feature::Vertex};
    ASSERT_EQ(p.feature, expected[clamped]);
    (p.gap > 0 ? outside : inside) += 1;
  }
  EXPECT_GT(inside, 50);  // the sample covers both branches
  EXPECT_GT(outside, 50);
}

TEST(RigidBox, FeatureClassification) {
  const ObstacleProjection face = project_to_box(box, {0.2, 0.1, -0.3});
  EXPECT_EQ(face.feature, Feature::Face);
  EXPECT_NEAR(face.gap, 0.3, 1e-15);
  EXPECT_EQ(face.normal, Eigen::Vector3d(0, 0, -1));

  const ObstacleProjection edge = project_to_box(box, {1.3, 0.1, -0.4});
  EXPECT_EQ(edge.feature, Feature::Edge);
  EXPECT_NEAR(edge.gap, 0.5, 1e-15);
  EXPECT_LE((edge.normal - Eigen::Vector3d(0.6, 0, -0.8)).norm(), 1e-15);

  const ObstacleProjection vertex = project_to_box(box, {-1.2, 0.7, 0.5});
  EXPECT_EQ(vertex.feature, Feature::Vertex);
  EXPECT_NEAR(vertex.gap, std::sqrt(0.04 + 0.04 + 0.01), 1e-15);

  const ObstacleProjection inside = project_to_box(box, {0.9, 0.0, 0.2});
  EXPECT_EQ(inside.feature, Feature::Face);
  EXPECT_NEAR(inside.gap, -0.1, 1e-15);
  EXPECT_EQ(inside.normal, Eigen::Vector3d(1, 0, 0));
}

TEST(RigidBox, TiesFollowFaceOrder) {
  // Documented order (−z, +z, −x, +x, −y, +y): the first face at minimal distance wins.
  const RigidBox cube{{-1, -1, -1}, {1, 1, 1}};
  EXPECT_EQ(project_to_box(cube, {0, 0, 0}).normal, Eigen::Vector3d(0, 0, -1));      // all six
  EXPECT_EQ(project_to_box(cube, {-0.5, 0, 0.5}).normal, Eigen::Vector3d(0, 0, 1));  // +z, −x
  EXPECT_EQ(project_to_box(cube, {0.5, -0.5, 0}).normal, Eigen::Vector3d(1, 0, 0));  // +x, −y
  EXPECT_EQ(project_to_box(cube, {0, 0.5, 0.5}).normal, Eigen::Vector3d(0, 0, 1));   // +z, +y
  EXPECT_EQ(project_to_box(cube, {-1, -1, 0}).normal, Eigen::Vector3d(-1, 0, 0));    // on edge
}

TEST(RigidBox, PointOnSurfaceIsInsideWithZeroGap) {
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.3, 0.2, 0.0), Eigen::Vector3d(1, 0.5, 0.4),
                                   Eigen::Vector3d(-1, 0, 0.1)}) {
    const ObstacleProjection p = project_to_box(box, x);
    EXPECT_EQ(p.gap, 0.0);
    EXPECT_FALSE(std::signbit(p.gap));
    EXPECT_EQ(p.feature, Feature::Face);
    EXPECT_NEAR(p.normal.norm(), 1.0, 1e-15);
    EXPECT_EQ(p.dnormal_dx, Eigen::Matrix3d::Zero());
  }
}

/// ∂g/∂x = n and ∂n/∂x = dnormal_dx of the box b by central differences.
void expect_exact_derivatives(const RigidBox& b, const Eigen::Vector3d& x, Feature feature) {
  const ObstacleProjection p = project_to_box(b, x);
  ASSERT_EQ(p.feature, feature);
  const auto gap = [&b](const Eigen::Vector3d& y) { return project_to_box(b, y).gap; };
  const auto normal = [&b](const Eigen::Vector3d& y) { return project_to_box(b, y).normal; };
  EXPECT_LE(test::relative_error(test::fd_gradient(gap, x), p.normal), 1e-6);
  const Eigen::Matrix3d dn = test::fd_jacobian(normal, x);
  if (p.dnormal_dx.isZero(0))
    EXPECT_LE(dn.cwiseAbs().maxCoeff(), 1e-9);
  else
    EXPECT_LE(test::relative_error(dn, p.dnormal_dx), 1e-6);
}

TEST(RigidBox, DerivativesOutsideNearEdge) {
  expect_exact_derivatives(box, {1.05, 0.3, -0.02}, Feature::Edge);
  const ObstacleProjection p = project_to_box(box, {1.05, 0.3, -0.02});
  const Eigen::Vector3d t = Eigen::Vector3d::UnitY();
  const Eigen::Matrix3d expected =
      (Eigen::Matrix3d::Identity() - p.normal * p.normal.transpose() - t * t.transpose()) / p.gap;
  EXPECT_LE((p.dnormal_dx - expected).norm(), 1e-12);
}

TEST(RigidBox, DerivativesOutsideNearVertex) {
  expect_exact_derivatives(box, {1.03, -0.54, -0.02}, Feature::Vertex);
}

TEST(RigidBox, DerivativesOutsideFace) {
  expect_exact_derivatives(box, {0.5, 0.6, 0.2}, Feature::Face);
}

TEST(RigidBox, DerivativesInside) {
  expect_exact_derivatives(box, {0.9, 0.2, 0.03}, Feature::Face);  // under the bottom face
  expect_exact_derivatives(box, {0.97, 0.1, 0.2}, Feature::Face);  // near the +x wall
}

// --- Rounded edges: the points within r of the inner box [lo + r, hi − r] -------------------

const RigidBox rounded{{-1, -0.5, 0}, {1, 0.5, 0.4}, 0.15};

/// The rounded box's signed distance from the reference formula: the inner box's minus r.
double reference_rounded_sdf(const RigidBox& b, const Eigen::Vector3d& x) {
  const RigidBox inner{(b.lo.array() + b.radius).matrix(), (b.hi.array() - b.radius).matrix()};
  return reference_sdf(inner, x) - b.radius;
}

TEST(RoundedBox, RandomPointsMatchReferenceSignedDistance) {
  std::mt19937 rng(20261206);
  std::uniform_real_distribution<double> coordinate(-1.3, 1.3);
  const Eigen::Array3d inner_lo = rounded.lo.array() + rounded.radius;
  const Eigen::Array3d inner_hi = rounded.hi.array() - rounded.radius;
  int inside_rounding = 0, outside = 0;
  for (int k = 0; k < 4000; ++k) {
    const Eigen::Vector3d x(coordinate(rng), coordinate(rng), 0.6 * coordinate(rng));
    const ObstacleProjection p = project_to_box(rounded, x);
    ASSERT_NEAR(p.gap, reference_rounded_sdf(rounded, x), 1e-14) << "x = " << x.transpose();
    ASSERT_TRUE(p.normal.allFinite() && p.dnormal_dx.allFinite());
    ASSERT_NEAR(p.normal.norm(), 1.0, 1e-14);
    // x − g n is on the rounded surface, and n is the reference distance's gradient there.
    ASSERT_NEAR(reference_rounded_sdf(rounded, x - p.gap * p.normal), 0.0, 1e-13);
    const int clamped = ((x.array() < inner_lo) || (x.array() > inner_hi)).count();
    const Feature expected[] = {Feature::Face, Feature::Face, Feature::Edge, Feature::Vertex};
    ASSERT_EQ(p.feature, expected[clamped]);
    if (p.gap < 0 && clamped >= 2) ++inside_rounding;  // penetrated into a rounded edge or corner
    if (p.gap > 0) ++outside;
  }
  EXPECT_GT(inside_rounding, 5);  // the sample covers the curved penetrated branch
  EXPECT_GT(outside, 50);
}

TEST(RoundedBox, NormalTurnsContinuouslyRoundTheEdge) {
  // Under the bottom face towards the +x edge (z = −0.01 below lo_z = 0): the normal is −z up
  // to the start of the rounding at x = hi_x − r = 0.85, then turns towards +x; the sharp box's
  // normal jumps there from −z to the +x face's side. At 45° round the edge it is (1, 0, −1)/√2.
  const double h = 1e-9;
  const Eigen::Vector3d before(0.85 - h, 0.1, -0.01), after(0.85 + h, 0.1, -0.01);
  EXPECT_LE((project_to_box(rounded, before).normal - project_to_box(rounded, after).normal).norm(),
            1e-6);
  const double s = 0.15 + 0.02;  // 0.02 outside the rounding, at 45°
  const ObstacleProjection p =
      project_to_box(rounded, {0.85 + s / std::sqrt(2.0), 0.0, 0.15 - s / std::sqrt(2.0)});
  EXPECT_EQ(p.feature, Feature::Edge);
  EXPECT_NEAR(p.gap, 0.02, 1e-14);
  EXPECT_LE((p.normal - Eigen::Vector3d(1, 0, -1) / std::sqrt(2.0)).norm(), 1e-14);
  // The sharp box's corner fills the rounding: the same point is inside it, on its diagonal,
  // 0.15 − s/√2 from both the bottom and the +x face.
  EXPECT_NEAR(project_to_box(box, {0.85 + s / std::sqrt(2.0), 0.0, 0.15 - s / std::sqrt(2.0)}).gap,
              -(0.15 - s / std::sqrt(2.0)), 1e-14);
}

/// The rounded box's derivatives at a point outside (g > 0) or pressed in (g < 0).
void expect_exact_rounded_derivatives(const Eigen::Vector3d& x, Feature feature, bool penetrated) {
  ASSERT_EQ(project_to_box(rounded, x).gap < 0, penetrated);
  expect_exact_derivatives(rounded, x, feature);
}

TEST(RoundedBox, DerivativesInEveryBranch) {
  expect_exact_rounded_derivatives({0.95, 0.1, -0.02}, Feature::Edge, false);  // outside the edge
  expect_exact_rounded_derivatives({0.92, 0.1, 0.03}, Feature::Edge, true);    // into the edge
  expect_exact_rounded_derivatives({0.95, -0.42, -0.02}, Feature::Vertex, false);
  expect_exact_rounded_derivatives({0.92, -0.4, 0.03}, Feature::Vertex, true);  // into the corner
  expect_exact_rounded_derivatives({0.3, 0.1, -0.02}, Feature::Face, false);    // under the face
  expect_exact_rounded_derivatives({0.3, 0.1, 0.02}, Feature::Face, true);      // into the face
  expect_exact_rounded_derivatives({0.3, 0.1, 0.18}, Feature::Face, true);      // inside B
  // In the rounding ∂n/∂x is the cylinder's (I − n nᵀ − t tᵀ)/ρ with ρ = g + r, also when g < 0.
  const ObstacleProjection p = project_to_box(rounded, {0.92, 0.1, 0.03});
  const Eigen::Vector3d t = Eigen::Vector3d::UnitY();
  const Eigen::Matrix3d expected =
      (Eigen::Matrix3d::Identity() - p.normal * p.normal.transpose() - t * t.transpose()) /
      (p.gap + rounded.radius);
  EXPECT_LE((p.dnormal_dx - expected).norm(), 1e-12 * expected.norm());
}

TEST(RoundedBox, ZeroRadiusIsTheSharpBox) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1.3, 1.3);
  const RigidBox sharp{box.lo, box.hi, 0.0};
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d x(coordinate(rng), coordinate(rng), coordinate(rng));
    const ObstacleProjection a = project_to_box(sharp, x), b = project_to_box(box, x);
    ASSERT_EQ(a.gap, b.gap);
    ASSERT_EQ(a.normal, b.normal);
    ASSERT_EQ(a.dnormal_dx, b.dnormal_dx);
  }
  EXPECT_FALSE(std::signbit(project_to_box(sharp, {0.3, 0.2, 0.0}).gap));  // on the surface: +0
}

TEST(Obstacle, ProjectDispatches) {
  const Eigen::Vector3d x(0.3, 0.2, -0.1);
  EXPECT_EQ(project(Obstacle{box}, x).gap, project_to_box(box, x).gap);
  const RigidPlane plane{{0, 0, 0.5}, {0, 0, 1}};
  EXPECT_DOUBLE_EQ(project(Obstacle{plane}, x).gap, -0.6);
}

}  // namespace
}  // namespace hypercontact
