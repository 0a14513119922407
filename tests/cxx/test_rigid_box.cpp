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

/// ∂g/∂x = n and ∂n/∂x = dnormal_dx by central differences.
void expect_exact_derivatives(const Eigen::Vector3d& x, Feature feature) {
  const ObstacleProjection p = project_to_box(box, x);
  ASSERT_EQ(p.feature, feature);
  const auto gap = [](const Eigen::Vector3d& y) { return project_to_box(box, y).gap; };
  const auto normal = [](const Eigen::Vector3d& y) { return project_to_box(box, y).normal; };
  EXPECT_LE(test::relative_error(test::fd_gradient(gap, x), p.normal), 1e-6);
  const Eigen::Matrix3d dn = test::fd_jacobian(normal, x);
  if (p.dnormal_dx.isZero(0))
    EXPECT_LE(dn.cwiseAbs().maxCoeff(), 1e-9);
  else
    EXPECT_LE(test::relative_error(dn, p.dnormal_dx), 1e-6);
}

TEST(RigidBox, DerivativesOutsideNearEdge) {
  expect_exact_derivatives({1.05, 0.3, -0.02}, Feature::Edge);
  const ObstacleProjection p = project_to_box(box, {1.05, 0.3, -0.02});
  const Eigen::Vector3d t = Eigen::Vector3d::UnitY();
  const Eigen::Matrix3d expected =
      (Eigen::Matrix3d::Identity() - p.normal * p.normal.transpose() - t * t.transpose()) / p.gap;
  EXPECT_LE((p.dnormal_dx - expected).norm(), 1e-12);
}

TEST(RigidBox, DerivativesOutsideNearVertex) {
  expect_exact_derivatives({1.03, -0.54, -0.02}, Feature::Vertex);
}

TEST(RigidBox, DerivativesOutsideFace) { expect_exact_derivatives({0.5, 0.6, 0.2}, Feature::Face); }

TEST(RigidBox, DerivativesInside) {
  expect_exact_derivatives({0.9, 0.2, 0.03}, Feature::Face);  // under the bottom face
  expect_exact_derivatives({0.97, 0.1, 0.2}, Feature::Face);  // near the +x wall
}

TEST(Obstacle, ProjectDispatches) {
  const Eigen::Vector3d x(0.3, 0.2, -0.1);
  EXPECT_EQ(project(Obstacle{box}, x).gap, project_to_box(box, x).gap);
  const RigidPlane plane{{0, 0, 0.5}, {0, 0, 1}};
  EXPECT_DOUBLE_EQ(project(Obstacle{plane}, x).gap, -0.6);
}

}  // namespace
}  // namespace hypercontact
