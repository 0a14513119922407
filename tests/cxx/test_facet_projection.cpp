// Closest-point projection onto one master facet: closed forms on a flat square, thousands of
// seeded random points around distorted, warped quadrilaterals and triangles against brute-force
// sampling, a saddle with two local minima, degenerate facets.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <hypercontact/facet_projection.hpp>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "surface_element_fd.hpp"

namespace hypercontact {
namespace {

/// 3 × n matrix from columns.
NodeCoordinates nodes(std::initializer_list<Eigen::Vector3d> columns) {
  NodeCoordinates x(3, static_cast<Eigen::Index>(columns.size()));
  int j = 0;
  for (const Eigen::Vector3d& c : columns) x.col(j++) = c;
  return x;
}

const NodeCoordinates unit_square = nodes({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});

bool is_finite(const FacetProjection& p) {
  return p.xi.allFinite() && p.point.allFinite() && std::isfinite(p.distance) &&
         p.normal.allFinite();
}

using test::node_xi;

TEST(FacetShape, PartitionOfUnityNodalValuesAndDerivatives) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n : {3, 4, 6, 9}) {
    for (int b = 0; b < n; ++b) {
      const Eigen::VectorXd N = facet_shape_functions(n, node_xi(n, b));
      for (int a = 0; a < n; ++a) EXPECT_NEAR(N[a], a == b ? 1.0 : 0.0, 1e-15) << n << " " << a;
    }
    for (int i = 0; i < 20; ++i) {
      const Eigen::Vector2d xi(u(rng), u(rng));
      EXPECT_NEAR(facet_shape_functions(n, xi).sum(), 1.0, 1e-14);
      // Σ N_a ξ_a = ξ: the facets reproduce linear fields (an affine facet stays affine).
      Eigen::Vector2d reproduced = Eigen::Vector2d::Zero();
      const Eigen::VectorXd N = facet_shape_functions(n, xi);
      for (int a = 0; a < n; ++a) reproduced += N[a] * node_xi(n, a);
      EXPECT_LE((reproduced - xi).norm(), 1e-14);
      // The shape functions are at most quadratic along each ξ_α: central differences have no
      // truncation error, only rounding (h = 1e-3).
      const double h = 1e-3;
      for (int alpha = 0; alpha < 2; ++alpha) {
        const Eigen::Vector2d e = h * Eigen::Vector2d::Unit(alpha);
        const Eigen::VectorXd fd =
            (facet_shape_functions(n, xi + e) - facet_shape_functions(n, xi - e)) / (2 * h);
        EXPECT_LE((fd - facet_shape_derivatives(n, xi).col(alpha)).cwiseAbs().maxCoeff(), 1e-11);
      }
      // Columns 11, 22, 12 of the second derivatives against differences of the first.
      const Eigen::Matrix<double, Eigen::Dynamic, 3> d2N = facet_shape_second_derivatives(n, xi);
      const Eigen::Vector2d e1 = h * Eigen::Vector2d::Unit(0), e2 = h * Eigen::Vector2d::Unit(1);
      const auto dN = [n](const Eigen::Vector2d& x) { return facet_shape_derivatives(n, x); };
      const Eigen::VectorXd fd11 = (dN(xi + e1).col(0) - dN(xi - e1).col(0)) / (2 * h);
      const Eigen::VectorXd fd22 = (dN(xi + e2).col(1) - dN(xi - e2).col(1)) / (2 * h);
      const Eigen::VectorXd fd12 = (dN(xi + e1).col(1) - dN(xi - e1).col(1)) / (2 * h);
      const Eigen::VectorXd fd21 = (dN(xi + e2).col(0) - dN(xi - e2).col(0)) / (2 * h);
      EXPECT_LE((fd11 - d2N.col(0)).cwiseAbs().maxCoeff(), 1e-11) << n;
      EXPECT_LE((fd22 - d2N.col(1)).cwiseAbs().maxCoeff(), 1e-11) << n;
      EXPECT_LE((fd12 - d2N.col(2)).cwiseAbs().maxCoeff(), 1e-11) << n;
      EXPECT_LE((fd21 - d2N.col(2)).cwiseAbs().maxCoeff(), 1e-11) << n;
    }
  }
  EXPECT_THROW(facet_shape_functions(2, {0, 0}), std::invalid_argument);
  EXPECT_THROW(facet_shape_derivatives(5, {0, 0}), std::invalid_argument);
  EXPECT_THROW(facet_shape_second_derivatives(8, {0, 0}), std::invalid_argument);
}

TEST(FacetProjection, FlatSquareFaceEdgeVertex) {
  // Interior: ξ = 2x − 1, distance |z|, normal +z (counter-clockwise seen from +z).
  const FacetProjection face = project_to_facet(unit_square, {0.3, 0.6, -0.2});
  EXPECT_EQ(face.feature, Feature::Face);
  EXPECT_EQ(face.local_index, -1);
  EXPECT_LE((face.xi - Eigen::Vector2d(-0.4, 0.2)).norm(), 1e-14);
  EXPECT_LE((face.point - Eigen::Vector3d(0.3, 0.6, 0)).norm(), 1e-14);
  EXPECT_NEAR(face.distance, 0.2, 1e-14);
  EXPECT_LE((face.normal - Eigen::Vector3d(0, 0, 1)).norm(), 1e-15);
  EXPECT_TRUE(face.converged);
  EXPECT_LE(face.iterations, 15);

  // Beyond edge 1 (node 1 → node 2, ξ1 = 1).
  const FacetProjection edge = project_to_facet(unit_square, {1.5, 0.25, 0.1});
  EXPECT_EQ(edge.feature, Feature::Edge);
  EXPECT_EQ(edge.local_index, 1);
  EXPECT_EQ(edge.xi[0], 1.0);
  EXPECT_NEAR(edge.xi[1], -0.5, 1e-15);
  EXPECT_NEAR(edge.distance, std::hypot(0.5, 0.1), 1e-15);
  EXPECT_LE((edge.normal - Eigen::Vector3d(0, 0, 1)).norm(), 1e-15);

  // Beyond edge 3 (node 3 → node 0, ξ1 = −1).
  const FacetProjection edge3 = project_to_facet(unit_square, {-0.5, 0.75, 0.0});
  EXPECT_EQ(edge3.feature, Feature::Edge);
  EXPECT_EQ(edge3.local_index, 3);
  EXPECT_EQ(edge3.xi[0], -1.0);

  // Beyond corner 2 (1, 1).
  const FacetProjection vertex = project_to_facet(unit_square, {1.2, 1.4, -0.3});
  EXPECT_EQ(vertex.feature, Feature::Vertex);
  EXPECT_EQ(vertex.local_index, 2);
  EXPECT_EQ(vertex.xi, Eigen::Vector2d(1, 1));
  EXPECT_EQ(vertex.point, Eigen::Vector3d(1, 1, 0));

  // Exactly above an edge: Face wins the tie.
  const FacetProjection above_edge = project_to_facet(unit_square, {1.0, 0.5, 0.3});
  EXPECT_EQ(above_edge.feature, Feature::Face);
  EXPECT_NEAR(above_edge.distance, 0.3, 1e-15);

  // Clockwise node order flips the normal.
  const NodeCoordinates clockwise = unit_square.rowwise().reverse();
  EXPECT_LE(
      (project_to_facet(clockwise, {0.3, 0.6, -0.2}).normal - Eigen::Vector3d(0, 0, -1)).norm(),
      1e-15);
}

TEST(FacetProjection, TriangleClosedForms) {
  const NodeCoordinates tri = nodes({{0, 0, 1}, {2, 0, 1}, {0, 2, 1}});
  const FacetProjection face = project_to_facet(tri, {0.5, 0.4, 3});
  EXPECT_EQ(face.feature, Feature::Face);
  EXPECT_LE((face.xi - Eigen::Vector2d(0.25, 0.2)).norm(), 1e-15);
  EXPECT_NEAR(face.distance, 2.0, 1e-15);
  EXPECT_LE((face.normal - Eigen::Vector3d(0, 0, 1)).norm(), 1e-15);
  const FacetProjection hyp = project_to_facet(tri, {1.5, 1.5, 1});  // beyond edge 1 (ξ1+ξ2 = 1)
  EXPECT_EQ(hyp.feature, Feature::Edge);
  EXPECT_EQ(hyp.local_index, 1);
  EXPECT_NEAR(hyp.xi.sum(), 1.0, 1e-15);
  EXPECT_NEAR(hyp.distance, std::sqrt(0.5), 1e-15);
  const FacetProjection v = project_to_facet(tri, {-1, -0.5, 1});
  EXPECT_EQ(v.feature, Feature::Vertex);
  EXPECT_EQ(v.local_index, 0);
}

/// A random rotation.
Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Vector3d axis(u(rng), u(rng), u(rng));
  if (axis.norm() < 1e-3) axis = Eigen::Vector3d::UnitX();
  return Eigen::AngleAxisd(3.14159 * u(rng), axis.normalized()).toRotationMatrix();
}

/// Distance from x to a dense sampling of the facet: a grid in ξ (boundary included) plus a
/// finer sampling of each edge.
struct Sampler {
  std::vector<Eigen::Vector3d> points;
  Sampler(const NodeCoordinates& x, int grid, int per_edge) {
    const int n = static_cast<int>(x.cols());
    for (int i = 0; i <= grid; ++i)
      for (int j = 0; j <= grid; ++j) {
        Eigen::Vector2d xi;
        if (n == 4) {
          xi = Eigen::Vector2d(-1 + 2.0 * i / grid, -1 + 2.0 * j / grid);
        } else {
          if (i + j > grid) continue;
          xi = Eigen::Vector2d(double(i) / grid, double(j) / grid);
        }
        points.push_back(x * facet_shape_functions(n, xi));
      }
    for (int k = 0; k < n; ++k)
      for (int i = 0; i <= per_edge; ++i) {
        const double t = double(i) / per_edge;
        points.push_back((1 - t) * x.col(k) + t * x.col((k + 1) % n));
      }
  }
  double distance(const Eigen::Vector3d& x) const {
    double d2 = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : points) d2 = std::min(d2, (x - p).squaredNorm());
    return std::sqrt(d2);
  }
};

/// Checks one projection against brute force and the classification rules; counts features.
void check_projection(const NodeCoordinates& x, const Eigen::Vector3d& xs, const Sampler& sampler,
                      double L, const Eigen::Vector3d& outward, int counts[3]) {
  const int n = static_cast<int>(x.cols());
  const FacetProjection p = project_to_facet(x, xs);
  ASSERT_TRUE(is_finite(p));
  EXPECT_TRUE(p.converged);
  // The returned point is x_M(ξ*) at the returned distance.
  EXPECT_LE((p.point - x * facet_shape_functions(n, p.xi)).norm(), 1e-13 * L);
  EXPECT_NEAR(p.distance, (xs - p.point).norm(), 1e-13 * L);
  // Never farther than any sample of the facet; close to the best sample.
  const double sampled = sampler.distance(xs);
  EXPECT_LE(p.distance, sampled + 1e-12 * L) << "xs = " << xs.transpose();
  EXPECT_GE(p.distance, sampled - 1e-2 * L);
  // Normal: unit a_1 × a_2 at ξ*, outward.
  const Eigen::Matrix<double, 3, 2> a = x * facet_shape_derivatives(n, p.xi);
  EXPECT_LE((p.normal - a.col(0).cross(a.col(1)).normalized()).norm(), 1e-12);
  EXPECT_GT(p.normal.dot(outward), 0);
  const Eigen::Vector3d r = xs - p.point;
  switch (p.feature) {
    case Feature::Face: {
      ++counts[0];
      EXPECT_EQ(p.local_index, -1);
      if (n == 4) {
        EXPECT_LE(p.xi.cwiseAbs().maxCoeff(), 1 + 1e-10);
      } else {
        EXPECT_GE(p.xi.minCoeff(), -1e-10);
        EXPECT_LE(p.xi.sum(), 1 + 1e-10);
      }
      // Stationary: r ⟂ a_α.
      EXPECT_LE((a.transpose() * r).cwiseAbs().maxCoeff(), 1e-10 * L * L);
      break;
    }
    case Feature::Edge: {
      ++counts[1];
      const int k = p.local_index;
      ASSERT_TRUE(k >= 0 && k < n);
      const Eigen::Vector2d xk = facet_vertex_xi(n, k), xk1 = facet_vertex_xi(n, k + 1);
      // ξ* strictly between the two vertices on the reference edge.
      const Eigen::Vector2d d = xk1 - xk;
      const double t = (p.xi - xk).dot(d) / d.squaredNorm();
      EXPECT_GT(t, 0);
      EXPECT_LT(t, 1);
      EXPECT_LE((p.xi - (xk + t * d)).norm(), 2e-16);
      if (n == 4) {  // the constant coordinate is exact
        const int fixed = d[0] == 0 ? 0 : 1;
        EXPECT_EQ(p.xi[fixed], xk[fixed]);
      }
      // r ⟂ edge, and the unconstrained minimiser is not inside the facet (or is farther).
      const Eigen::Vector3d e = x.col((k + 1) % n) - x.col(k);
      EXPECT_LE(std::abs(r.dot(e)), 1e-12 * L * (L + r.norm()));
      break;
    }
    case Feature::Vertex: {
      ++counts[2];
      const int k = p.local_index;
      ASSERT_TRUE(k >= 0 && k < n);
      EXPECT_EQ(p.xi, facet_vertex_xi(n, k));
      EXPECT_LE((p.point - x.col(k)).norm(), 1e-14 * L);
      // r points away from both adjacent edges.
      EXPECT_LE(r.dot(x.col((k + 1) % n) - x.col(k)), 1e-12 * L * L);
      EXPECT_LE(r.dot(x.col((k + n - 1) % n) - x.col(k)), 1e-12 * L * L);
      break;
    }
  }
}

TEST(FacetProjection, RandomDistortedWarpedQuadrilateralsMatchBruteForce) {
  std::mt19937 rng(20240901);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int counts[3] = {0, 0, 0};
  int points = 0;
  for (int f = 0; f < 250; ++f) {
    const Eigen::Matrix3d R = random_rotation(rng);
    const double scale = std::exp(u(rng)), warp = f % 2 == 0 ? 0.5 : 1.5;
    const Eigen::Vector3d shift(5 * u(rng), 5 * u(rng), 5 * u(rng));
    NodeCoordinates x(3, 4);
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector2d corner = facet_vertex_xi(4, a);
      // In-plane perturbation ≤ 0.35 keeps the projection onto the plane convex (not folded).
      const Eigen::Vector3d local(corner[0] + 0.35 * u(rng), corner[1] + 0.35 * u(rng),
                                  warp * u(rng));
      x.col(a) = shift + scale * R * local;
    }
    const Sampler sampler(x, 150, 3000);
    const double L = (x.col(1) - x.col(0)).norm() + (x.col(2) - x.col(1)).norm();
    const Eigen::Vector3d outward = R.col(2);
    const Eigen::Vector3d centre = x.rowwise().mean();
    for (int i = 0; i < 10; ++i, ++points) {
      // Mostly near the facet (above, below, beyond edges and corners), some far away.
      const double reach = i < 8 ? 1.5 : 6.0;
      const Eigen::Vector3d local(reach * u(rng), reach * u(rng), reach * u(rng));
      check_projection(x, centre + scale * R * local, sampler, L, outward, counts);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  EXPECT_GE(points, 2000);
  EXPECT_GT(counts[0], 300);  // every classification is exercised
  EXPECT_GT(counts[1], 300);
  EXPECT_GT(counts[2], 100);
}

TEST(FacetProjection, RandomTrianglesMatchBruteForce) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int counts[3] = {0, 0, 0};
  int points = 0;
  for (int f = 0; f < 250; ++f) {
    const Eigen::Matrix3d R = random_rotation(rng);
    const double scale = std::exp(u(rng));
    Eigen::Vector2d p[3];
    do {  // a counter-clockwise triangle, not too flat
      for (auto& q : p) q = Eigen::Vector2d(u(rng), u(rng));
    } while ((p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x() < 0.1);
    NodeCoordinates x(3, 3);
    const Eigen::Vector3d shift(5 * u(rng), 5 * u(rng), 5 * u(rng));
    for (int a = 0; a < 3; ++a)
      x.col(a) = shift + scale * R * Eigen::Vector3d(p[a].x(), p[a].y(), 0);
    const Sampler sampler(x, 200, 3000);
    const double L = (x.col(1) - x.col(0)).norm() + (x.col(2) - x.col(1)).norm();
    const Eigen::Vector3d centre = x.rowwise().mean();
    for (int i = 0; i < 10; ++i, ++points) {
      const double reach = i < 5 ? 0.6 : 1.5;
      const Eigen::Vector3d local(reach * u(rng), reach * u(rng), 1.5 * u(rng));
      check_projection(x, centre + scale * R * local, sampler, L, R.col(2), counts);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  EXPECT_GE(points, 2000);
  EXPECT_GT(counts[0], 300);
  EXPECT_GT(counts[1], 300);
  EXPECT_GT(counts[2], 100);
}

TEST(FacetProjection, SaddleWithTwoLocalMinimaFindsTheGlobalOne) {
  // z = c ξ1 ξ2 over [−1, 1]²: along the diagonal ξ1 = ξ2 the surface is a parabola opening
  // towards +z. A point high on the axis sees the centre as a saddle of F and two minima on
  // the diagonal; a small offset makes one of them the global minimum.
  const double c = 1.0;
  const NodeCoordinates saddle = nodes({{-1, -1, c}, {1, -1, -c}, {1, 1, c}, {-1, 1, -c}});
  const Sampler sampler(saddle, 400, 4000);
  for (const Eigen::Vector3d& xs :
       {Eigen::Vector3d(0.0, 0.0, 1.5), Eigen::Vector3d(0.01, 0.012, 1.5),
        Eigen::Vector3d(-0.02, -0.01, 1.4), Eigen::Vector3d(0.0, 0.0, -1.5)}) {
    const FacetProjection p = project_to_facet(saddle, xs);
    ASSERT_TRUE(is_finite(p));
    EXPECT_EQ(p.feature, Feature::Face);  // minima at |ξ1| = |ξ2| ≈ 0.7 (s² = (c h − 1)/c²)
    EXPECT_GT(p.xi.norm(), 0.5) << "stopped at the saddle";
    EXPECT_LE(p.distance, sampler.distance(xs) + 1e-12);
    EXPECT_LT(p.distance, (xs - Eigen::Vector3d(0, 0, 0)).norm() - 1e-3);
  }
}

TEST(FacetProjection, FarPointsAndLargeCoordinatesStayFinite) {
  const Eigen::Vector3d far_shift(1e6, -2e6, 3e5);
  const NodeCoordinates x =
      nodes({{0, 0, 0.2}, {1.2, 0.1, -0.1}, {1.1, 0.9, 0.3}, {-0.1, 1.0, -0.2}}).colwise() +
      far_shift;
  for (const Eigen::Vector3d& d :
       {Eigen::Vector3d(0.5, 0.5, 1e4), Eigen::Vector3d(1e5, 3e4, 0),
        Eigen::Vector3d(0.4, 0.6, -1e-9), Eigen::Vector3d(0.5, 0.5, 0)}) {
    const FacetProjection p = project_to_facet(x, far_shift + d);
    EXPECT_TRUE(is_finite(p));
    EXPECT_TRUE(p.converged);
  }
}

TEST(FacetProjection, RejectsDegenerateFacetsAndBadInput) {
  const double nan = std::nan("");
  const Eigen::Vector3d xs(0.2, 0.3, 0.1);
  // Zero area.
  EXPECT_THROW(project_to_facet(nodes({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}), xs),
               std::invalid_argument);
  EXPECT_THROW(project_to_facet(nodes({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}), xs),
               std::invalid_argument);
  EXPECT_THROW(project_to_facet(nodes({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}), xs),
               std::invalid_argument);
  // A bow tie: the diagonals are parallel.
  EXPECT_THROW(project_to_facet(nodes({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}), xs),
               std::invalid_argument);
  // Two coincident nodes (a triangle in disguise) and a straight corner.
  EXPECT_THROW(project_to_facet(nodes({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 0}}), xs),
               std::invalid_argument);
  EXPECT_THROW(project_to_facet(nodes({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}}), xs),
               std::invalid_argument);
  // Wrong size, non-finite input.
  EXPECT_THROW(project_to_facet(NodeCoordinates::Zero(3, 2), xs), std::invalid_argument);
  EXPECT_THROW(project_to_facet(NodeCoordinates::Zero(3, 5), xs), std::invalid_argument);
  NodeCoordinates bad = unit_square;
  bad(1, 2) = nan;
  EXPECT_THROW(project_to_facet(bad, xs), std::invalid_argument);
  EXPECT_THROW(project_to_facet(unit_square, Eigen::Vector3d(0, nan, 0)), std::invalid_argument);
  // A dart (planar, non-convex): a_1 × a_2 vanishes on a line inside; facet_normal there throws.
  const NodeCoordinates dart = nodes({{0, 0, 0}, {2, 0, 0}, {0.3, 0.3, 0}, {0, 2, 0}});
  const auto jz = [&](double s) {
    const Eigen::Matrix<double, 3, 2> a = dart * facet_shape_derivatives(4, {s, s});
    return a.col(0).cross(a.col(1)).z();
  };
  double lo = -1, hi = 1;  // jz(−1) > 0 > jz(1)
  ASSERT_GT(jz(lo), 0);
  ASSERT_LT(jz(hi), 0);
  for (int i = 0; i < 200; ++i) (jz(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  EXPECT_THROW(facet_normal(dart, {lo, lo}), std::invalid_argument);
  EXPECT_NO_THROW(facet_normal(dart, {-0.9, -0.9}));
}

}  // namespace
}  // namespace hypercontact
