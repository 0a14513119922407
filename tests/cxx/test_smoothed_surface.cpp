// Deformable-master contact with the smoothed normal law (smoothing δ > 0, penetration.hpp):
// node_to_surface's residual against central finite differences of its energy and its tangent
// against central finite differences of the residual, over every node, on the face (flat and
// warped quadrilaterals, triangle, Gauss point), edge and vertex, with the signed distance below
// the band, in it on both sides of zero, above it (inactive), with λ_N = 0 and λ_N > 0;
// surface_friction in stick and slip in the same regions (tangent including the old-facet
// columns); δ = 0 bit-identical to the calls without the argument; invalid smoothing.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <hypercontact/facet_projection.hpp>
#include <hypercontact/node_to_surface.hpp>
#include <hypercontact/penetration.hpp>
#include <hypercontact/surface_friction.hpp>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "finite_difference.hpp"
#include "surface_element_fd.hpp"

namespace hypercontact {
namespace {

using test::edge_outward;
using test::flat_quad;
using test::one_node;
using test::point_at;
using test::single;
using test::surface_point;
using test::triangle;
using test::warped_quad;
using test::fd_gradient_stacked;
using test::fd_jacobian_stacked;
using test::placed;
using test::relative_error;
using test::stack;
using test::unstack;

constexpr double w = 0.37;
constexpr double eps_n = 250.0;
constexpr double eps_t = 180.0;
constexpr double mu = 0.3;
/// Band half-width: the FD points below are ≥ 10⁴ steps from ĝ − λ/ε_N = ±δ.
constexpr double delta = 0.05;



/// The tests' own smoothed bracket P(s), s = ĝ − λ/ε_N.
double expected_P(double s) {
  if (s <= -delta) return -s;
  if (s >= delta) return 0.0;
  return (delta - s) * (delta - s) / (4 * delta);
}

/// The signed distance ĝ: g on the face, sign(g) |r| off it (sign −1 for g ≤ 0).
double signed_distance(const SurfaceContact& c, const Eigen::Vector3d& x_s,
                       const NodeCoordinates& m) {
  if (c.feature == Feature::Face) return c.gap;
  const double d = (x_s - surface_point(m, c.xi)).norm();
  return c.gap <= 0 ? -d : d;
}

// --- node_to_surface -----------------------------------------------------------------------------

struct Element {
  NodeCoordinates slave;
  Eigen::VectorXd weights;
  NodeCoordinates master;
  double lambda = 0.0;
  double smoothing = delta;

  Eigen::VectorXd x() const { return stack({slave, master}); }
  double energy(const Eigen::VectorXd& y) const {
    const auto s = unstack(y, {slave, master});
    return node_to_surface_energy(s[0], weights, s[1], w, eps_n, 0.0, lambda, smoothing);
  }
  Eigen::VectorXd residual(const Eigen::VectorXd& y) const {
    const auto s = unstack(y, {slave, master});
    return node_to_surface(s[0], weights, s[1], w, eps_n, lambda, smoothing).residual;
  }
  SurfaceContact evaluate() const {
    return node_to_surface(slave, weights, master, w, eps_n, lambda, smoothing);
  }
};

/// Active on the expected feature with ĝ − λ/ε_N = shifted: p_N = ε_N P, R = FD of W,
/// K = FD of R, K symmetric, forces balanced, slave force w p_N along −∇ĝ.
SurfaceContact expect_smoothed(const Element& e, Feature feature, double shifted) {
  const SurfaceContact c = e.evaluate();
  EXPECT_EQ(c.feature, feature);
  EXPECT_TRUE(c.closed);
  const double g_hat = signed_distance(c, e.slave * e.weights, e.master);
  EXPECT_NEAR(g_hat - e.lambda / eps_n, shifted, 1e-9);
  EXPECT_NEAR(c.pressure, eps_n * expected_P(g_hat - e.lambda / eps_n), 1e-10 * eps_n);
  EXPECT_GT(c.pressure, 0.0);
  EXPECT_TRUE(c.residual.allFinite() && c.tangent.allFinite());
  const Eigen::VectorXd x = e.x();
  const Eigen::VectorXd dW =
      fd_gradient_stacked([&](const Eigen::VectorXd& y) { return e.energy(y); }, x);
  const Eigen::MatrixXd dR =
      fd_jacobian_stacked([&](const Eigen::VectorXd& y) { return e.residual(y); }, x);
  EXPECT_LE(relative_error(dW, c.residual), 1e-6);
  EXPECT_LE(relative_error(dR, c.tangent), 1e-6);
  EXPECT_EQ(c.tangent, c.tangent.transpose());
  Eigen::Vector3d slave_force = Eigen::Vector3d::Zero(), total = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < e.slave.cols(); ++i) slave_force += c.residual.segment<3>(3 * i);
  for (Eigen::Index i = 0; i < c.residual.size() / 3; ++i) total += c.residual.segment<3>(3 * i);
  EXPECT_LE(total.norm(), 1e-12 * c.residual.norm());
  EXPECT_NEAR(slave_force.norm(), w * c.pressure, 1e-10 * w * c.pressure);
  if (feature == Feature::Face)
    EXPECT_LE((slave_force + w * c.pressure * c.normal).norm(), 1e-10 * w * c.pressure);
  return c;
}

void expect_inactive(const Element& e) {
  const SurfaceContact c = e.evaluate();
  EXPECT_FALSE(c.closed);
  EXPECT_EQ(c.pressure, 0.0);
  EXPECT_TRUE(c.residual.isZero(0.0));
  EXPECT_TRUE(c.tangent.isZero(0.0));
  EXPECT_EQ(e.energy(e.x()), 0.0);
}

/// Shifted gaps ĝ − λ/ε_N of the three active regions, and one above the band.
constexpr double s_closed = -0.08, s_band_closed = -0.02, s_band_open = 0.03, s_inactive = 0.07;

TEST(SmoothedNodeToSurface, FaceOfFlatAndWarpedQuadsAndTriangle) {
  for (double lambda : {0.0, 5.0}) {  // λ/ε_N = 0, 0.02
    for (const auto& [m, xi] : {std::pair{flat_quad, Eigen::Vector2d(0.3, -0.2)},
                                std::pair{warped_quad, Eigen::Vector2d(0.3, -0.2)},
                                std::pair{warped_quad, Eigen::Vector2d(-0.7, 0.6)},
                                std::pair{triangle, Eigen::Vector2d(0.3, 0.25)}}) {
      for (double s : {s_closed, s_band_closed, s_band_open}) {
        SCOPED_TRACE("lambda = " + std::to_string(lambda) + ", nodes " +
                     std::to_string(m.cols()) + ", s = " + std::to_string(s));
        const double g = s + lambda / eps_n;
        const Element e{single(point_at(m, xi, g)), one_node, m, lambda};
        const SurfaceContact c = expect_smoothed(e, Feature::Face, s);
        EXPECT_NEAR(c.gap, g, 1e-12);
        EXPECT_NEAR(e.energy(e.x()),
                    w * eps_n * penetration_energy(s, delta), 1e-12);
      }
      expect_inactive({single(point_at(m, xi, s_inactive + lambda / eps_n)), one_node, m, lambda});
    }
  }
}

TEST(SmoothedNodeToSurface, WarpedFaceCurvatureTermIsScaledByThePressure) {
  // In the band (open side) K = −w ε_N P' ∇g ∇gᵀ − w p_N ∇²g: the curvature part is there.
  const Element e{single(point_at(warped_quad, {0.3, -0.2}, s_band_open)), one_node, warped_quad};
  const SurfaceContact c = e.evaluate();
  const Eigen::VectorXd grad = -c.residual / (w * c.pressure);
  const double slope = (delta - s_band_open) / (2 * delta);  // −P'
  const Eigen::MatrixXd material = w * eps_n * slope * grad * grad.transpose();
  EXPECT_GT((c.tangent - material).norm(), 1e-3 * c.tangent.norm());
  // And the material part alone fails the finite-difference check.
  const Eigen::MatrixXd dR =
      fd_jacobian_stacked([&](const Eigen::VectorXd& y) { return e.residual(y); }, e.x());
  EXPECT_GT(relative_error(dR, material), 1e-3);
  EXPECT_LE(relative_error(dR, c.tangent), 1e-6);
}

TEST(SmoothedNodeToSurface, EdgeAndVertexEveryRegion) {
  // x = x_M + a (outward in-plane) + b n: g = b, |r| = hypot(a, b), ĝ = sign(b) |r|; every
  // point keeps |g| ≥ 0.008, far from the jump of ĝ at g = 0.
  const Eigen::Vector2d xi_edge(1.0, -0.2);
  const Eigen::Vector3d edge_point = surface_point(warped_quad, xi_edge);
  const Eigen::Vector3d out_e = edge_outward(warped_quad, 1, xi_edge);
  const Eigen::Vector3d n_e = facet_normal(warped_quad, xi_edge);
  const Eigen::Vector2d xi_v = facet_vertex_xi(4, 2);
  const Eigen::Vector3d out_v =
      (edge_outward(warped_quad, 1, xi_v) + edge_outward(warped_quad, 2, xi_v)).normalized();
  const Eigen::Vector3d n_v = facet_normal(warped_quad, xi_v);
  const Eigen::Vector3d vertex = warped_quad.col(2);
  struct Case {
    double a, b, lambda;  // ĝ = sign(b) hypot(a, b), s = ĝ − λ/ε_N
  };
  for (const Case& k : {
           Case{0.048, -0.064, 0.0},   // ĝ = −0.08: below the band
           Case{0.012, -0.016, 0.0},   // ĝ = −0.02: band, closed
           Case{0.018, 0.024, 0.0},    // ĝ = +0.03: band, open geometrically
           Case{0.036, -0.048, 5.0},   // ĝ = −0.06, s = −0.08
           Case{0.009, -0.012, 5.0},   // ĝ = −0.015, s = −0.035
           Case{0.012, 0.016, 10.0},   // ĝ = +0.02, s = −0.02
           Case{0.03, 0.04, 5.0},      // ĝ = +0.05, s = +0.03
       }) {
    const double g_hat = std::copysign(std::hypot(k.a, k.b), k.b);
    const double s = g_hat - k.lambda / eps_n;
    for (const auto& [x, feature] :
         {std::pair{(edge_point + k.a * out_e + k.b * n_e).eval(), Feature::Edge},
          std::pair{(vertex + k.a * out_v + k.b * n_v).eval(), Feature::Vertex}}) {
      SCOPED_TRACE("feature " + std::to_string(static_cast<int>(feature)) + ", g_hat = " +
                   std::to_string(g_hat) + ", lambda = " + std::to_string(k.lambda));
      const Element e{single(x), one_node, warped_quad, k.lambda};
      const SurfaceContact c = expect_smoothed(e, feature, s);
      EXPECT_NEAR(c.gap, k.b, 1e-10);
      EXPECT_NEAR(e.energy(e.x()), w * eps_n * penetration_energy(s, delta), 1e-12);
      // The force acts along r: on the slave −w p_N sign(g) r/|r|.
      const Eigen::Vector3d r = x - surface_point(warped_quad, c.xi);
      EXPECT_LE((c.residual.head<3>() + w * c.pressure * (k.b > 0 ? 1.0 : -1.0) * r.normalized())
                    .norm(),
                1e-10 * w * c.pressure);
    }
  }
  // Above the band: inactive (λ = 0: ĝ = 0.07; λ = 5: ĝ = 0.09).
  for (const auto& [a, b, lambda] : {std::tuple{0.042, 0.056, 0.0}, std::tuple{0.054, 0.072, 5.0}}) {
    expect_inactive({single(edge_point + a * out_e + b * n_e), one_node, warped_quad, lambda});
    expect_inactive({single(vertex + a * out_v + b * n_v), one_node, warped_quad, lambda});
  }
}

TEST(SmoothedNodeToSurface, TriangleEdgeAndGaussPoints) {
  const Eigen::Vector2d on_edge(0.6, 0.4);  // edge 1 of the triangle
  const Eigen::Vector3d out = edge_outward(triangle, 1, on_edge);
  const Eigen::Vector3d n = facet_normal(triangle, on_edge);
  for (const auto& [a, b] : {std::pair{0.012, -0.016}, std::pair{0.018, 0.024}, std::pair{0.06, -0.08}}) {
    const Element e{single(surface_point(triangle, on_edge) + a * out + b * n), one_node, triangle};
    expect_smoothed(e, Feature::Edge, std::copysign(std::hypot(a, b), b));
  }
  // Gauss point of a slave quadrilateral against the warped quad, ĝ in the band on both sides,
  // with and without λ; Gauss point of a slave triangle against the triangle.
  const double gp = 1 / std::sqrt(3.0);
  const Eigen::VectorXd M = facet_shape_functions(4, Eigen::Vector2d(-gp, gp));
  for (const auto& [offset, lambda] : {std::pair{0.0, 0.0}, std::pair{0.04, 0.0}, std::pair{0.04, 5.0}}) {
    NodeCoordinates slave(3, 4);
    slave << point_at(warped_quad, {-0.5, -0.4}, offset - 0.03),
        point_at(warped_quad, {0.4, -0.6}, offset - 0.02),
        point_at(warped_quad, {0.5, 0.3}, offset + 0.01),
        point_at(warped_quad, {-0.6, 0.5}, offset - 0.01);
    const Element e{slave, M, warped_quad, lambda};
    const SurfaceContact c = e.evaluate();
    SCOPED_TRACE("gap " + std::to_string(c.gap) + ", lambda " + std::to_string(lambda));
    const double s = c.gap - lambda / eps_n;
    ASSERT_LT(std::abs(s), 0.04);  // in the band, away from its edges
    expect_smoothed(e, Feature::Face, s);
  }
  NodeCoordinates slave(3, 3);
  slave << point_at(triangle, {0.1, 0.1}, 0.01), point_at(triangle, {0.6, 0.1}, -0.02),
      point_at(triangle, {0.2, 0.6}, 0.03);
  const Element tri{slave, facet_shape_functions(3, {1.0 / 6, 2.0 / 3}), triangle};
  expect_smoothed(tri, Feature::Face, tri.evaluate().gap);
}

TEST(SmoothedNodeToSurface, ZeroSmoothingIsBitIdentical) {
  const Eigen::Vector2d xi_edge(1.0, -0.2);
  const Eigen::Vector3d out = edge_outward(warped_quad, 1, xi_edge);
  const Eigen::Vector3d n = facet_normal(warped_quad, xi_edge);
  std::vector<Eigen::Vector3d> points;
  for (double g : {-0.05, -0.01, 0.0, 0.02})
    points.push_back(point_at(warped_quad, {0.3, -0.2}, g));
  points.push_back(surface_point(warped_quad, xi_edge) + 0.15 * out - 0.1 * n);
  points.push_back(surface_point(warped_quad, xi_edge) + 0.03 * out + 0.05 * n);
  points.push_back(warped_quad.col(2) + Eigen::Vector3d(0.05, 0.04, -0.03));
  for (const Eigen::Vector3d& x : points) {
    const NodeCoordinates s = single(x);
    const FacetProjection p = project_to_facet(warped_quad, x);
    for (double lambda : {0.0, 5.0}) {
      const SurfaceContact a = node_to_surface(s, one_node, warped_quad, w, eps_n, lambda);
      const SurfaceContact b = node_to_surface(s, one_node, warped_quad, w, eps_n, lambda, 0.0);
      EXPECT_EQ(a.residual, b.residual);
      EXPECT_EQ(a.tangent, b.tangent);
      EXPECT_EQ(a.pressure, b.pressure);
      EXPECT_EQ(a.closed, b.closed);
      const SurfaceContact c = node_to_surface(s, one_node, warped_quad, p, w, eps_n, 0.0, lambda);
      const SurfaceContact d =
          node_to_surface(s, one_node, warped_quad, p, w, eps_n, 0.0, lambda, 0.0);
      EXPECT_EQ(c.residual, d.residual);
      EXPECT_EQ(c.tangent, d.tangent);
      EXPECT_EQ(c.pressure, d.pressure);
      EXPECT_EQ(node_to_surface_energy(s, one_node, warped_quad, w, eps_n, 0.0, lambda),
                node_to_surface_energy(s, one_node, warped_quad, w, eps_n, 0.0, lambda, 0.0));
    }
    // With touch.
    const SurfaceContact t0 = node_to_surface(s, one_node, warped_quad, p, w, eps_n, 1e-10);
    const SurfaceContact t1 = node_to_surface(s, one_node, warped_quad, p, w, eps_n, 1e-10, 0.0, 0.0);
    EXPECT_EQ(t0.residual, t1.residual);
    EXPECT_EQ(t0.tangent, t1.tangent);
  }
}

TEST(SmoothedNodeToSurface, InvalidSmoothingThrows) {
  const Eigen::Vector3d x = point_at(warped_quad, {0.3, -0.2}, -0.01);
  const Eigen::Vector3d far = point_at(warped_quad, {0.3, -0.2}, 0.5);  // open: still checked
  for (const Eigen::Vector3d& y : {x, far}) {
    const NodeCoordinates s = single(y);
    const FacetProjection p = project_to_facet(warped_quad, y);
    for (double bad : {-1e-3, std::nan(""), std::numeric_limits<double>::infinity()}) {
      EXPECT_THROW(node_to_surface(s, one_node, warped_quad, w, eps_n, 0.0, bad),
                   std::invalid_argument);
      EXPECT_THROW(node_to_surface(s, one_node, warped_quad, p, w, eps_n, 0.0, 0.0, bad),
                   std::invalid_argument);
      EXPECT_THROW(node_to_surface_energy(s, one_node, warped_quad, w, eps_n, 0.0, 0.0, bad),
                   std::invalid_argument);
      EXPECT_THROW(surface_friction(s, one_node, warped_quad, warped_quad, {0.3, -0.2},
                                    Eigen::Vector3d::Zero(), w, eps_n, eps_t, mu, 0.0, bad),
                   std::invalid_argument);
      EXPECT_THROW(surface_friction(s, one_node, warped_quad, p, warped_quad, {0.3, -0.2},
                                    Eigen::Vector3d::Zero(), w, eps_n, eps_t, mu, 5.0, bad),
                   std::invalid_argument);
    }
  }
}

// --- surface_friction ----------------------------------------------------------------------------

struct FrictionElement {
  NodeCoordinates slave;
  Eigen::VectorXd weights;
  NodeCoordinates master;
  NodeCoordinates old;
  Eigen::Vector2d xi_old;
  Eigen::Vector3d t_old;
  double lambda = 0.0;

  Eigen::VectorXd x() const { return stack({slave, master, old}); }
  SurfaceFriction evaluate() const {
    return surface_friction(slave, weights, master, old, xi_old, t_old, w, eps_n, eps_t, mu,
                            lambda, delta);
  }
  Eigen::VectorXd residual(const Eigen::VectorXd& y) const {
    const auto s = unstack(y, {slave, master, old});
    return surface_friction(s[0], weights, s[1], s[2], xi_old, t_old, w, eps_n, eps_t, mu, lambda,
                            delta)
        .residual;
  }
};

/// t_old such that t_trial = target · (P_T direction)/|P_T direction| now.
Eigen::Vector3d tuned_t_old(const FrictionElement& e, const Eigen::Vector3d& direction,
                            double target) {
  const SurfaceFriction f = e.evaluate();
  const Eigen::Matrix3d P_T = Eigen::Matrix3d::Identity() - f.normal * f.normal.transpose();
  const Eigen::Vector3d x_old =
      e.old * facet_shape_functions(static_cast<int>(e.old.cols()), e.xi_old);
  return -eps_t * P_T * (e.slave * e.weights - x_old) + target * (P_T * direction).normalized();
}

SurfaceFriction expect_smoothed_friction(const FrictionElement& e, StickSlip state,
                                         Feature feature) {
  const SurfaceFriction f = e.evaluate();
  EXPECT_EQ(f.state, state);
  EXPECT_EQ(f.feature, feature);
  const double p = eps_n * expected_P(f.gap - e.lambda / eps_n);
  EXPECT_NEAR(f.pressure, p, 1e-10 * eps_n);
  EXPECT_GT(f.pressure, 0.0);
  EXPECT_TRUE(f.residual.allFinite() && f.tangent.allFinite());
  const Eigen::MatrixXd J =
      fd_jacobian_stacked([&](const Eigen::VectorXd& y) { return e.residual(y); }, e.x());
  EXPECT_LE(relative_error(J, f.tangent), 1e-6);
  EXPECT_TRUE(f.residual.tail(3 * e.old.cols()).isZero(0.0));
  EXPECT_LE(f.traction.norm(), mu * p * (1 + 1e-12));
  EXPECT_NEAR(f.dissipation, w * f.traction.dot(f.slip_increment), 1e-12);
  if (state == StickSlip::Slip) EXPECT_NEAR(f.traction.norm(), mu * p, 1e-10 * mu * p);
  return f;
}

TEST(SmoothedSurfaceFriction, FaceStickAndSlipEveryRegion) {
  const Eigen::Vector2d xi(0.3, 0.2);
  for (const NodeCoordinates& m : {warped_quad, triangle}) {
    for (double lambda : {0.0, 10.0}) {  // λ/ε_N = 0, 0.04
      for (double s : {s_closed, s_band_closed, s_band_open}) {
        SCOPED_TRACE("nodes " + std::to_string(m.cols()) + ", lambda = " + std::to_string(lambda) +
                     ", s = " + std::to_string(s));
        const double g = s + lambda / eps_n;
        FrictionElement e{single(point_at(m, xi, g)), one_node, m, m,
                          xi - Eigen::Vector2d(0.05, -0.03), Eigen::Vector3d::Zero(), lambda};
        const double p = eps_n * expected_P(s);
        // |t_trial| ≥ 2: m's curvature ε_T/|t_trial| stays small against the FD step.
        e.t_old = tuned_t_old(e, Eigen::Vector3d(0.3, -1, 0.5), std::max(2.0 * mu * p, 2.0));
        const SurfaceFriction slip = expect_smoothed_friction(e, StickSlip::Slip, Feature::Face);
        EXPECT_NEAR(slip.gap, g, 1e-12);
        e.t_old = tuned_t_old(e, Eigen::Vector3d(0.3, -1, 0.5), 0.5 * mu * p);
        const SurfaceFriction stick = expect_smoothed_friction(e, StickSlip::Stick, Feature::Face);
        EXPECT_NEAR(stick.traction.norm(), 0.5 * mu * p, 1e-10 * p);
      }
      // Above the band: open.
      const FrictionElement open{single(point_at(m, xi, s_inactive + lambda / eps_n)), one_node, m,
                                 m, xi, Eigen::Vector3d(1, 2, 3), lambda};
      const SurfaceFriction f = open.evaluate();
      EXPECT_EQ(f.state, StickSlip::Open);
      EXPECT_TRUE(f.residual.isZero(0.0));
      EXPECT_TRUE(f.tangent.isZero(0.0));
      EXPECT_EQ(f.pressure, 0.0);
    }
  }
}

TEST(SmoothedSurfaceFriction, EdgeVertexAndHistoryOnAnotherFacet) {
  const Eigen::Vector2d xi_edge(1.0, -0.2);
  const Eigen::Vector3d edge_point = surface_point(warped_quad, xi_edge);
  const Eigen::Vector3d out_e = edge_outward(warped_quad, 1, xi_edge);
  const Eigen::Vector3d n_e = facet_normal(warped_quad, xi_edge);
  const Eigen::Vector2d xi_v = facet_vertex_xi(4, 2);
  const Eigen::Vector3d out_v =
      (edge_outward(warped_quad, 1, xi_v) + edge_outward(warped_quad, 2, xi_v)).normalized();
  const Eigen::Vector3d n_v = facet_normal(warped_quad, xi_v);
  for (double g : {s_closed, s_band_closed, s_band_open}) {
    for (const auto& [x, feature] :
         {std::pair{(edge_point + 0.1 * out_e + g * n_e).eval(), Feature::Edge},
          std::pair{(warped_quad.col(2) + 0.1 * out_v + g * n_v).eval(), Feature::Vertex}}) {
      SCOPED_TRACE("feature " + std::to_string(static_cast<int>(feature)) + ", g = " +
                   std::to_string(g));
      FrictionElement e{single(x), one_node, warped_quad, triangle, {0.3, 0.3},
                        Eigen::Vector3d::Zero()};  // history on another facet
      const double p = eps_n * expected_P(e.evaluate().gap);
      e.t_old = tuned_t_old(e, Eigen::Vector3d(1, 0.2, -0.3), std::max(2.0 * mu * p, 2.0));
      expect_smoothed_friction(e, StickSlip::Slip, feature);
      e.t_old = tuned_t_old(e, Eigen::Vector3d(1, 0.2, -0.3), 0.5 * mu * p);
      expect_smoothed_friction(e, StickSlip::Stick, feature);
    }
  }
}

TEST(SmoothedSurfaceFriction, ZeroSmoothingIsBitIdentical) {
  const Eigen::Vector2d xi(0.3, 0.2);
  for (double g : {-0.05, -0.01, 0.0, 0.02}) {
    const NodeCoordinates s = single(point_at(warped_quad, xi, g));
    const FacetProjection p = project_to_facet(warped_quad, s.col(0));
    for (double lambda : {0.0, 10.0}) {
      for (const Eigen::Vector2d& xi_old : {Eigen::Vector2d(0.298, 0.201), Eigen::Vector2d(0.25, 0.23)}) {
        const Eigen::Vector3d t_old(0.1, -0.2, 0.05);
        const SurfaceFriction a = surface_friction(s, one_node, warped_quad, warped_quad, xi_old,
                                                   t_old, w, eps_n, eps_t, mu, lambda);
        const SurfaceFriction b = surface_friction(s, one_node, warped_quad, warped_quad, xi_old,
                                                   t_old, w, eps_n, eps_t, mu, lambda, 0.0);
        EXPECT_EQ(a.state, b.state);
        EXPECT_EQ(a.residual, b.residual);
        EXPECT_EQ(a.tangent, b.tangent);
        EXPECT_EQ(a.traction, b.traction);
        EXPECT_EQ(a.pressure, b.pressure);
        const SurfaceFriction c = surface_friction(s, one_node, warped_quad, p, warped_quad, xi_old,
                                                   t_old, w, eps_n, eps_t, mu, lambda);
        const SurfaceFriction d = surface_friction(s, one_node, warped_quad, p, warped_quad, xi_old,
                                                   t_old, w, eps_n, eps_t, mu, lambda, 0.0);
        EXPECT_EQ(c.residual, d.residual);
        EXPECT_EQ(c.tangent, d.tangent);
      }
    }
  }
}

}  // namespace
}  // namespace hypercontact
