// Rigid box: signed distance against an independent formula, features, ties, derivatives.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <hypercontact/obstacle.hpp>
#include <hypercontact/rigid_box.hpp>
#include <limits>
#include <random>
#include <utility>

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

// --- Blended rounding: within r/2 of the superellipse-rounded inner solid S ------------------

const RigidBox blended{{-1, -0.5, 0}, {1, 0.5, 0.4}, 0.15, true};

/// Distance from e ≥ 0 (outside the unit-free solid Σ yᵢ⁴ ≤ a⁴ of the positive orthant, all
/// eᵢ > 0 in the first `k` coordinates, zero after) to its surface, by brute force: the surface
/// parametrised as yᵢ = a √uᵢ with u on the unit sphere's positive octant (Σ yᵢ⁴ = a⁴ Σ uᵢ²),
/// a grid and then shrinking local searches. Independent of the library's Lagrange equations.
double brute_force_superellipse_distance(const Eigen::Vector3d& e, double a, int k) {
  const auto point = [&](double t, double f) {  // u = (sin f cos t, sin f sin t, cos f)
    Eigen::Vector3d u =
        k == 2 ? Eigen::Vector3d(std::cos(t), std::sin(t), 0)
               : Eigen::Vector3d(std::sin(f) * std::cos(t), std::sin(f) * std::sin(t), std::cos(f));
    return Eigen::Vector3d(a * u.cwiseMax(0.0).cwiseSqrt());
  };
  const double quarter = std::acos(0.0);
  double best = std::numeric_limits<double>::infinity(), bt = 0, bf = quarter;
  const int n = 400;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= (k == 2 ? 0 : n); ++j) {
      const double t = quarter * i / n, f = k == 2 ? quarter : quarter * j / n;
      const double dist = (e - point(t, f)).norm();
      if (dist < best) best = dist, bt = t, bf = f;
    }
  for (double h = quarter / n; h > 1e-15; h *= 0.7)  // pattern search, the step shrinking
    for (bool moved = true; moved;) {
      moved = false;
      for (const auto& [dt, df] : {std::pair{h, 0.0}, {-h, 0.0}, {0.0, h}, {0.0, -h}}) {
        if (k == 2 && df != 0) continue;
        const double t = std::clamp(bt + dt, 0.0, quarter), f = std::clamp(bf + df, 0.0, quarter);
        const double dist = (e - point(t, f)).norm();
        if (dist < best) best = dist, bt = t, bf = f, moved = true;
      }
    }
  return best;
}

TEST(BlendedBox, SignedDistanceMatchesABruteForceSearch) {
  // Outside S (up to r/2 into the rounding and beyond it outwards), round an edge and a corner.
  const double r = blended.radius, a = r / 2;
  const Eigen::Vector3d corner_of_B(1 - r, -0.5 + r, 0 + r);  // B's corner at +x, −y, −z
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0, penetrated = 0;
  for (int k : {2, 3})
    for (int sample = 0; sample < 20; ++sample) {
      Eigen::Vector3d e(unit(rng), unit(rng), k == 3 ? unit(rng) : 0.0);
      e *= a * (0.6 + 1.4 * unit(rng)) / e.norm();
      if (std::sqrt(std::sqrt(e.array().pow(4).sum())) <= a * (1 + 1e-3)) continue;  // inside S
      // e is measured outwards from B's corner: +x, −z and (at the corner) −y; an edge point
      // is at y = 0.1, inside B's y-range
      const Eigen::Vector3d x(corner_of_B[0] + e[0], k == 2 ? 0.1 : corner_of_B[1] - e[2],
                              corner_of_B[2] - e[1]);
      const ObstacleProjection p = project_to_box(blended, x);
      EXPECT_NEAR(p.gap, brute_force_superellipse_distance(e, a, k) - a, 1e-11)
          << "x = " << x.transpose();
      EXPECT_EQ(p.feature, k == 2 ? Feature::Edge : Feature::Vertex);
      EXPECT_NEAR(p.normal.norm(), 1.0, 1e-14);
      EXPECT_GT(p.normal[0], 0);
      EXPECT_LT(p.normal[2], 0);
      ++checked;
      penetrated += p.gap < 0;
    }
  EXPECT_GE(checked, 20);
  EXPECT_GE(penetrated, 3);  // the sample covers points pressed into the rounding
}

TEST(BlendedBox, FacesAndInsideAreTheCircularBoxs) {
  const RigidBox circular{blended.lo, blended.hi, blended.radius};
  for (const Eigen::Vector3d x :
       {Eigen::Vector3d(0.3, 0.1, -0.02), Eigen::Vector3d(0.3, 0.1, 0.02),
        Eigen::Vector3d(0.3, 0.1, 0.18), Eigen::Vector3d(1.2, 0.1, 0.2)}) {
    const ObstacleProjection p = project_to_box(blended, x), q = project_to_box(circular, x);
    EXPECT_EQ(p.gap, q.gap);
    EXPECT_EQ(p.normal, q.normal);
    EXPECT_EQ(p.dnormal_dx, q.dnormal_dx);
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.3, 1.3);
  const RigidBox sharp_blended{box.lo, box.hi, 0.0, true};
  for (int k = 0; k < 200; ++k) {  // r = 0: the sharp box, blended or not
    const Eigen::Vector3d x(coordinate(rng), coordinate(rng), coordinate(rng));
    EXPECT_EQ(project_to_box(sharp_blended, x).gap, project_to_box(box, x).gap);
  }
}

TEST(BlendedBox, DerivativesInEveryBranch) {
  // ∂g/∂x = n and ∂n/∂x exact: outside and pressed into an edge and a corner (less than r/2
  // deep), and the face branches.
  const auto check = [](const Eigen::Vector3d& x, Feature feature, bool penetrated) {
    ASSERT_EQ(project_to_box(blended, x).gap < 0, penetrated) << x.transpose();
    expect_exact_derivatives(blended, x, feature);
  };
  check({0.95, 0.1, -0.02}, Feature::Edge, false);
  check({0.9, 0.1, 0.02}, Feature::Edge, true);
  check({0.86, 0.1, -0.001}, Feature::Edge, false);  // just past the junction, nearly flat
  check({0.95, -0.42, -0.02}, Feature::Vertex, false);
  check({0.9, -0.4, 0.02}, Feature::Vertex, true);
  check({0.3, 0.1, -0.02}, Feature::Face, false);
  check({0.3, 0.1, 0.02}, Feature::Face, true);
  // Deeper than r/2 into the rounding, the level set of ρ₄ stands in for the distance: n turns
  // as ∂n/∂x says along the level set (directions v ⊥ n).
  const Eigen::Vector3d deep(0.87, 0.1, 0.09);
  const ObstacleProjection p = project_to_box(blended, deep);
  ASSERT_LT(p.gap, -blended.radius / 2);
  EXPECT_EQ(p.feature, Feature::Edge);
  const auto normal = [](const Eigen::Vector3d& y) { return project_to_box(blended, y).normal; };
  const Eigen::Matrix3d dn = test::fd_jacobian(normal, deep);
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - p.normal * p.normal.transpose();
  EXPECT_LE(test::relative_error(dn * P, p.dnormal_dx * P), 1e-6);
  EXPECT_LE((p.dnormal_dx - p.dnormal_dx.transpose()).norm(), 1e-12 * p.dnormal_dx.norm());
}

TEST(BlendedBox, ContinuousAcrossItsBranches) {
  // The exact branch meets the level-set branch at ρ₄(e) = r/2 (g = −r/2): the same g, n, ∂n/∂x
  // on both sides. Along the diagonal of the +x/−z edge, e = (t, t), ρ₄ = 2^¼ t.
  const double a = blended.radius / 2, t = a / std::pow(2.0, 0.25), h = 1e-9;
  const Eigen::Vector3d B_edge(1 - blended.radius, 0.1, blended.radius);
  const ObstacleProjection in =
      project_to_box(blended, B_edge + (t - h) * Eigen::Vector3d(1, 0, -1));
  const ObstacleProjection out =
      project_to_box(blended, B_edge + (t + h) * Eigen::Vector3d(1, 0, -1));
  EXPECT_NEAR(in.gap, -a, 1e-8);
  EXPECT_NEAR(out.gap, -a, 1e-8);
  EXPECT_LE((in.normal - out.normal).norm(), 1e-7);
  EXPECT_LE((in.dnormal_dx - out.dnormal_dx).norm(), 1e-6 * out.dnormal_dx.norm());
}

TEST(BlendedBox, CurvatureIsContinuousWhereTheFaceEnds) {
  // A point sliding under the bottom face (0.01 below it) across x = hi_x − r, where the face
  // ends: the circular rounding's ∂n/∂x jumps there from 0 to about 1/(r + 0.01); the blended
  // one's rises from 0 continuously (as the square of the distance past the junction).
  const RigidBox circular{blended.lo, blended.hi, blended.radius};
  const double junction = 1 - blended.radius;
  for (double h : {1e-3, 1e-4}) {
    const Eigen::Vector3d past(junction + h, 0.1, -0.01);
    EXPECT_GT(project_to_box(circular, past).dnormal_dx.norm(), 0.9 / (blended.radius + 0.01));
    EXPECT_LE(project_to_box(blended, past).dnormal_dx.norm(), 1e4 * h * h);
  }
  // Round the edge on the surface (g = 0) the largest curvature is that of the 45° point:
  // κ = κ_S/(1 + κ_S r/2), κ_S = 3·2^¼/(√2 · r/2) the superellipse's there, ≈ 1.43/r; the
  // circular rounding's is 1/r everywhere.
  double largest = 0;
  for (int i = 1; i < 200; ++i) {
    const double angle = std::acos(0.0) * i / 200;
    Eigen::Vector3d x = Eigen::Vector3d(junction + 0.1 * std::cos(angle), 0.1,
                                        blended.radius - 0.1 * std::sin(angle));
    for (int it = 0; it < 3; ++it) {  // onto the surface along the normal
      const ObstacleProjection p = project_to_box(blended, x);
      x -= p.gap * p.normal;
    }
    largest = std::max(largest, project_to_box(blended, x).dnormal_dx.norm());
  }
  const double a = blended.radius / 2, kappa_S = 3 * std::pow(2.0, 0.25) / (std::sqrt(2.0) * a);
  EXPECT_NEAR(largest, kappa_S / (1 + kappa_S * a), 1e-3 * largest);
}

TEST(Obstacle, ProjectDispatches) {
  const Eigen::Vector3d x(0.3, 0.2, -0.1);
  EXPECT_EQ(project(Obstacle{box}, x).gap, project_to_box(box, x).gap);
  const RigidPlane plane{{0, 0, 0.5}, {0, 0, 1}};
  EXPECT_DOUBLE_EQ(project(Obstacle{plane}, x).gap, -0.6);
}

}  // namespace
}  // namespace hypercontact
