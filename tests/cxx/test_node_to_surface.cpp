// Node-to-surface normal penalty against a deformable master facet: the residual against central
// finite differences of the energy and the tangent against central finite differences of the
// residual, over every node of the element (slave and master), on flat and warped quadrilaterals
// (face, edge, vertex), a Gauss-point slave, a triangle, near a centre of curvature; open contact;
// the narrow phase over candidate facets; bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <hypercontact/facet_projection.hpp>
#include <hypercontact/node_to_surface.hpp>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "finite_difference.hpp"
#include "surface_element_fd.hpp"

namespace hypercontact {
namespace {

using test::edge_outward;
using test::fd_gradient_stacked;
using test::fd_jacobian_stacked;
using test::flat_quad;
using test::one_node;
using test::point_at;
using test::relative_error;
using test::single;
using test::stack;
using test::surface_point;
using test::triangle;
using test::unstack;
using test::warped_quad;

constexpr double w = 0.37;
constexpr double eps_n = 250.0;

using test::placed;
const Eigen::Matrix3d& rotation = test::test_rotation;
const Eigen::Vector3d& shift = test::test_shift;

/// Element data and its checks against finite differences over all 3 (ns + nm) coordinates.
struct Element {
  NodeCoordinates slave;
  Eigen::VectorXd weights;
  NodeCoordinates master;

  Eigen::VectorXd x() const { return stack({slave, master}); }
  std::vector<NodeCoordinates> split(const Eigen::VectorXd& y) const {
    return unstack(y, {slave, master});
  }
  double energy(const Eigen::VectorXd& y) const {
    const auto s = split(y);
    return node_to_surface_energy(s[0], weights, s[1], w, eps_n);
  }
  Eigen::VectorXd residual(const Eigen::VectorXd& y) const {
    const auto s = split(y);
    return node_to_surface(s[0], weights, s[1], w, eps_n).residual;
  }
  SurfaceContact evaluate() const { return node_to_surface(slave, weights, master, w, eps_n); }
};

/// Errors of R against FD of W and of K against FD of R.
struct FdErrors {
  double residual;
  double tangent;
};

FdErrors fd_errors(const Element& e, const Eigen::MatrixXd& tangent) {
  const Eigen::VectorXd x = e.x();
  const SurfaceContact c = e.evaluate();
  const Eigen::VectorXd dW =
      fd_gradient_stacked([&](const Eigen::VectorXd& y) { return e.energy(y); }, x);
  const Eigen::MatrixXd dR =
      fd_jacobian_stacked([&](const Eigen::VectorXd& y) { return e.residual(y); }, x);
  return {relative_error(dW, c.residual), relative_error(dR, tangent)};
}

/// Closed contact on the expected feature, exact residual and tangent, symmetric tangent.
SurfaceContact expect_exact(const Element& e, Feature feature) {
  const SurfaceContact c = e.evaluate();
  EXPECT_EQ(c.feature, feature);
  EXPECT_TRUE(c.closed);
  EXPECT_LT(c.gap, 0);
  EXPECT_TRUE(c.residual.allFinite() && c.tangent.allFinite());
  const FdErrors err = fd_errors(e, c.tangent);
  EXPECT_LE(err.residual, 1e-6);
  EXPECT_LE(err.tangent, 1e-6);
  EXPECT_EQ(c.tangent, c.tangent.transpose());
  EXPECT_NEAR(c.pressure, -eps_n * c.gap, 1e-12 * eps_n);
  return c;
}

/// P = [M_i I, −N_a I] at ξ, for the tests' own formulas.
Eigen::MatrixXd P_matrix(const Element& e, const Eigen::Vector2d& xi) {
  const int ns = static_cast<int>(e.slave.cols()), nm = static_cast<int>(e.master.cols());
  const Eigen::VectorXd N = facet_shape_functions(nm, xi);
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3, 3 * (ns + nm));
  for (int i = 0; i < ns; ++i) P.block(0, 3 * i, 3, 3) = e.weights[i] * Eigen::Matrix3d::Identity();
  for (int a = 0; a < nm; ++a) P.block(0, 3 * (ns + a), 3, 3) = -N[a] * Eigen::Matrix3d::Identity();
  return P;
}

TEST(NodeToSurface, FlatQuadFaceMatchesClosedForm) {
  const Eigen::Vector2d xi(0.3, -0.2);
  const double gap = -0.05;
  const Element e{single(point_at(flat_quad, xi, gap)), one_node, flat_quad};
  const SurfaceContact c = expect_exact(e, Feature::Face);
  EXPECT_NEAR(c.gap, gap, 1e-14);
  EXPECT_LE((c.xi - xi).norm(), 1e-12);
  EXPECT_LE((c.normal - rotation.col(2)).norm(), 1e-14);
  // R = w ε_N g [n; −N_a n].
  const Eigen::VectorXd expected = w * eps_n * gap * P_matrix(e, xi).transpose() * c.normal;
  EXPECT_LE(relative_error(c.residual, expected), 1e-12);
  // Newton's equilibrium: the forces on the slave and on the master balance.
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (int a = 0; a < 5; ++a) total += c.residual.segment<3>(3 * a);
  EXPECT_LE(total.norm(), 1e-12 * c.residual.norm());
}

TEST(NodeToSurface, WarpedQuadCurvatureTermsAreNeeded) {
  const Eigen::Vector2d xi(0.3, -0.2);
  const Element e{single(point_at(warped_quad, xi, -0.08)), one_node, warped_quad};
  const SurfaceContact c = expect_exact(e, Feature::Face);

  // The same tangent without B H⁻¹ Bᵀ, and with H reduced to the metric a_α·a_β (no r·x_,αβ):
  // both must fail the finite-difference test by far.
  const Eigen::MatrixXd P = P_matrix(e, c.xi);
  const Eigen::Matrix<double, 4, 2> dN = facet_shape_derivatives(4, c.xi);
  const Eigen::Matrix<double, 3, 2> a = warped_quad * dN;
  const Eigen::Vector3d r = P * e.x();
  Eigen::MatrixXd B(15, 2);
  for (int alpha = 0; alpha < 2; ++alpha) {
    Eigen::MatrixXd P_alpha = Eigen::MatrixXd::Zero(3, 15);
    for (int b = 0; b < 4; ++b)
      P_alpha.block(0, 3 * (1 + b), 3, 3) = -dN(b, alpha) * Eigen::Matrix3d::Identity();
    B.col(alpha) = P_alpha.transpose() * r - P.transpose() * a.col(alpha);
  }
  const Eigen::Matrix2d metric = a.transpose() * a;
  Eigen::Matrix2d H = metric;
  H(0, 1) = H(1, 0) =
      metric(0, 1) - r.dot(warped_quad * facet_shape_second_derivatives(4, c.xi).col(2));
  const Eigen::MatrixXd K_exact = w * eps_n * (P.transpose() * P - B * H.inverse() * B.transpose());
  EXPECT_LE(relative_error(K_exact, c.tangent), 1e-12);  // the tests' formula is the kernel's

  const Eigen::MatrixXd K_without_correction = w * eps_n * P.transpose() * P;
  const Eigen::MatrixXd K_metric_only =
      w * eps_n * (P.transpose() * P - B * metric.inverse() * B.transpose());
  EXPECT_GT(fd_errors(e, K_without_correction).tangent, 1e-2);
  EXPECT_GT(fd_errors(e, K_metric_only).tangent, 1e-3);
}

TEST(NodeToSurface, WarpedQuadAboveAndBelowSeveralPoints) {
  for (const Eigen::Vector2d& xi :
       {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(-0.7, 0.6), Eigen::Vector2d(0.8, 0.85)})
    for (double gap : {-0.2, -0.01}) {
      SCOPED_TRACE("xi = (" + std::to_string(xi[0]) + ", " + std::to_string(xi[1]) +
                   "), g = " + std::to_string(gap));
      const Element e{single(point_at(warped_quad, xi, gap)), one_node, warped_quad};
      const SurfaceContact c = expect_exact(e, Feature::Face);
      EXPECT_NEAR(c.gap, gap, 1e-12);
    }
}

TEST(NodeToSurface, EdgeOfWarpedQuad) {
  const int k = 1;  // node 1 → node 2, ξ1 = 1
  const Eigen::Vector2d xi_edge(1.0, -0.2);
  const Eigen::Vector3d x = surface_point(warped_quad, xi_edge) +
                            0.15 * edge_outward(warped_quad, k, xi_edge) -
                            0.1 * facet_normal(warped_quad, xi_edge);
  const Element e{single(x), one_node, warped_quad};
  const SurfaceContact c = expect_exact(e, Feature::Edge);
  EXPECT_EQ(c.local_index, k);
  EXPECT_EQ(c.xi[0], 1.0);
  EXPECT_NEAR(c.gap, -0.1, 1e-12);
  // Off the face the force acts along r, not n: |R_slave| = w ε_N |r| > p_N w.
  EXPECT_NEAR(c.residual.head<3>().norm(), w * eps_n * std::hypot(0.15, 0.1), 1e-9);
}

TEST(NodeToSurface, VertexOfWarpedQuad) {
  const int k = 2;
  const Eigen::Vector2d xi_v = facet_vertex_xi(4, k);
  const Eigen::Vector3d out =
      edge_outward(warped_quad, 1, xi_v) + edge_outward(warped_quad, 2, xi_v);
  const Eigen::Vector3d x =
      warped_quad.col(k) + 0.1 * out.normalized() - 0.12 * facet_normal(warped_quad, xi_v);
  const Element e{single(x), one_node, warped_quad};
  const SurfaceContact c = expect_exact(e, Feature::Vertex);
  EXPECT_EQ(c.local_index, k);
  // At a vertex ξ* is fixed: K = w ε_N PᵀP.
  const Eigen::MatrixXd P = P_matrix(e, xi_v);
  EXPECT_LE(relative_error(c.tangent, w * eps_n * P.transpose() * P), 1e-14);
}

TEST(NodeToSurface, GaussPointOfASlaveFacet) {
  // Slave quadrilateral below the warped master; the slave point is its Gauss point
  // (−1/√3, 1/√3), M_i the bilinear shape functions there; all 4 + 4 nodes are unknowns.
  const double g = 1 / std::sqrt(3.0);
  const Eigen::VectorXd M = facet_shape_functions(4, Eigen::Vector2d(-g, g));
  NodeCoordinates slave(3, 4);
  slave << point_at(warped_quad, {-0.5, -0.4}, -0.03), point_at(warped_quad, {0.4, -0.6}, -0.06),
      point_at(warped_quad, {0.5, 0.3}, 0.01), point_at(warped_quad, {-0.6, 0.5}, -0.09);
  const Element e{slave, M, warped_quad};
  const SurfaceContact c = expect_exact(e, Feature::Face);
  EXPECT_EQ(c.residual.size(), 24);
  // The slave forces are M_i times the force at the Gauss point.
  for (int i = 0; i < 4; ++i)
    EXPECT_LE((c.residual.segment<3>(3 * i) - M[i] * w * eps_n * c.gap * c.normal).norm(),
              1e-12 * c.residual.norm());
}

TEST(NodeToSurface, TriangleMasterFaceAndEdge) {
  const Element face{single(point_at(triangle, {0.3, 0.25}, -0.04)), one_node, triangle};
  const SurfaceContact c = expect_exact(face, Feature::Face);
  EXPECT_NEAR(c.gap, -0.04, 1e-14);
  const Eigen::Vector2d on_edge(0.6, 0.4);  // edge 1: ξ1 + ξ2 = 1
  const Eigen::Vector3d x =
      surface_point(triangle, on_edge) + 0.1 * edge_outward(triangle, 1, on_edge) - 0.05 * c.normal;
  const SurfaceContact edge = expect_exact(Element{single(x), one_node, triangle}, Feature::Edge);
  EXPECT_EQ(edge.local_index, 1);
  // Gauss point of a slave triangle against the triangle.
  NodeCoordinates slave(3, 3);
  slave << point_at(triangle, {0.1, 0.1}, -0.02), point_at(triangle, {0.6, 0.1}, -0.05),
      point_at(triangle, {0.2, 0.6}, 0.01);
  expect_exact(Element{slave, facet_shape_functions(3, {1.0 / 6, 2.0 / 3}), triangle},
               Feature::Face);
}

TEST(NodeToSurface, CloseToACentreOfCurvatureAndAtIt) {
  // Saddle z = ξ1 ξ2 with the nodes ordered so that n = −z at the centre: a point above it
  // penetrates, and H = [[1, −h], [−h, 1]] at the centre for a point at height h.
  const NodeCoordinates saddle = placed({{-1, 1, -1}, {1, 1, 1}, {1, -1, -1}, {-1, -1, 1}});
  const Eigen::Vector3d up = rotation.col(2);
  expect_exact(
      Element{single(shift + rotation * Eigen::Vector3d(0.05, -0.03, 0.8)), one_node, saddle},
      Feature::Face);
  // h = 1: H singular at the centre, which is still the closest point (a degenerate minimum,
  // F − F* ∝ |ξ|⁴): no tangent, no NaN.
  const Element at_centre{single(shift + up), one_node, saddle};
  const FacetProjection p = project_to_facet(saddle, shift + up);
  ASSERT_EQ(p.feature, Feature::Face);
  ASSERT_LE(p.xi.norm(), 1e-3);
  FacetProjection exact = p;
  exact.xi.setZero();
  EXPECT_THROW(node_to_surface(at_centre.slave, one_node, saddle, exact, w, eps_n),
               std::runtime_error);
  try {  // with the projection found, whichever point of the flat minimum it is
    const SurfaceContact c = at_centre.evaluate();
    EXPECT_TRUE(c.residual.allFinite() && c.tangent.allFinite());
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("centre of curvature"), std::string::npos);
  }
  // The energy needs no tangent.
  EXPECT_NEAR(node_to_surface_energy(at_centre.slave, one_node, saddle, w, eps_n), 0.5 * w * eps_n,
              1e-12);
}

TEST(NodeToSurface, RandomWarpedQuadsAllFeatures) {
  // Seeded random warped quadrilaterals and penetrating slave points over the face, beyond
  // edges and corners; one slave node or a Gauss point of a random slave quadrilateral.
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int counts[3] = {0, 0, 0};
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(3 * u(rng), Eigen::Vector3d(u(rng), u(rng), 1).normalized())
            .toRotationMatrix();
    NodeCoordinates m(3, 4);
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector2d c = facet_vertex_xi(4, a);
      m.col(a) = R * Eigen::Vector3d(c[0] + 0.3 * u(rng), c[1] + 0.3 * u(rng), 0.4 * u(rng));
    }
    const Eigen::Vector2d xi(1.4 * u(rng), 1.4 * u(rng));  // about half off the face
    const Eigen::Vector2d clamped = xi.cwiseMax(-1).cwiseMin(1);
    const Eigen::Vector3d n = facet_normal(m, clamped);
    const Eigen::Vector3d base = surface_point(m, clamped) - (0.02 + 0.1 * (1 + u(rng))) * n;
    const Eigen::Matrix<double, 3, 2> a = m * facet_shape_derivatives(4, clamped);
    const Eigen::Vector3d x = base + a * (xi - clamped);
    Element e{single(x), one_node, m};
    if (trial % 3 == 0) {  // Gauss point of a slave quadrilateral around x
      NodeCoordinates s(3, 4);
      for (int i = 0; i < 4; ++i)
        s.col(i) = x + 0.2 * Eigen::Vector3d(u(rng), u(rng), 0.1 * u(rng));
      const Eigen::VectorXd M = facet_shape_functions(4, Eigen::Vector2d(0.57735, -0.57735));
      s.colwise() += (x - s * M).eval();  // Σ M_i = 1: the Gauss point is x
      e = Element{s, M, m};
    }
    const SurfaceContact c = e.evaluate();
    ASSERT_TRUE(c.residual.allFinite() && c.tangent.allFinite());
    if (!c.closed) continue;
    ++counts[static_cast<int>(c.feature)];
    const FdErrors err = fd_errors(e, c.tangent);
    EXPECT_LE(err.residual, 1e-6) << "trial " << trial;
    EXPECT_LE(err.tangent, 1e-6) << "trial " << trial;
  }
  EXPECT_GT(counts[0], 60);
  EXPECT_GT(counts[1], 30);
  EXPECT_GT(counts[2], 15);
}

TEST(NodeToSurface, OpenContactIsZero) {
  for (const NodeCoordinates& m : {flat_quad, warped_quad, triangle}) {
    const Element e{single(point_at(m, {0.2, 0.3}, 0.05)), one_node, m};
    const SurfaceContact c = e.evaluate();
    EXPECT_FALSE(c.closed);
    EXPECT_NEAR(c.gap, 0.05, 1e-12);
    EXPECT_EQ(c.pressure, 0.0);
    EXPECT_TRUE(c.residual.isZero(0.0));
    EXPECT_TRUE(c.tangent.isZero(0.0));
    EXPECT_EQ(c.residual.size(), 3 * (1 + m.cols()));
    EXPECT_EQ(node_to_surface_energy(e.slave, one_node, m, w, eps_n), 0.0);
    EXPECT_TRUE(fd_jacobian_stacked([&](const Eigen::VectorXd& y) { return e.residual(y); }, e.x())
                    .isZero(0.0));
  }
  // g = 0 counts as closed, with zero force.
  const Eigen::Vector3d on = surface_point(flat_quad, {0.0, 0.0});
  const SurfaceContact touching = node_to_surface(single(on), one_node, flat_quad, w, eps_n);
  EXPECT_TRUE(touching.closed || touching.gap > 0);
  EXPECT_LE(touching.residual.norm(), 1e-10);
}

TEST(NodeToSurface, TouchToleranceClosesRoundingLevelGaps) {
  // Surfaces meshed in touch have g = ±rounding: with touch > g > 0 the element is closed and
  // its tangent carries the contact stiffness w ε_N n ⊗ n at the slave node; without it, zero.
  const Eigen::Vector3d x = point_at(flat_quad, {0.1, -0.2}, 1e-13);
  const FacetProjection p = project_to_facet(flat_quad, x);
  const SurfaceContact open = node_to_surface(single(x), one_node, flat_quad, p, w, eps_n);
  EXPECT_FALSE(open.closed);
  EXPECT_TRUE(open.tangent.isZero(0.0));
  const SurfaceContact touched =
      node_to_surface(single(x), one_node, flat_quad, p, w, eps_n, 1e-10);
  EXPECT_TRUE(touched.closed);
  const Eigen::Matrix3d expected = w * eps_n * open.normal * open.normal.transpose();
  EXPECT_LT((touched.tangent.topLeftCorner<3, 3>() - expected).cwiseAbs().maxCoeff(),
            1e-9 * expected.cwiseAbs().maxCoeff());
  EXPECT_GT(node_to_surface_energy(single(x), one_node, flat_quad, w, eps_n, 1e-10), 0.0);
  EXPECT_EQ(node_to_surface_energy(single(x), one_node, flat_quad, w, eps_n), 0.0);
  EXPECT_THROW(node_to_surface(single(x), one_node, flat_quad, p, w, eps_n, -1.0),
               std::invalid_argument);
}

TEST(NodeToSurface, GivenProjectionEqualsInternalOne) {
  const Eigen::Vector3d x = point_at(warped_quad, {0.1, 0.4}, -0.03);
  const SurfaceContact a = node_to_surface(single(x), one_node, warped_quad, w, eps_n);
  const SurfaceContact b =
      node_to_surface(single(x), one_node, warped_quad, project_to_facet(warped_quad, x), w, eps_n);
  EXPECT_EQ(a.residual, b.residual);
  EXPECT_EQ(a.tangent, b.tangent);
}

TEST(NodeToSurface, RejectsBadInput) {
  const Eigen::Vector3d x = point_at(flat_quad, {0.1, 0.2}, -0.01);
  const FacetProjection p = project_to_facet(flat_quad, x);
  const auto call = [&](const NodeCoordinates& s, const Eigen::VectorXd& M,
                        const NodeCoordinates& m, double ww,
                        double e) { return node_to_surface(s, M, m, p, ww, e); };
  EXPECT_THROW(call(single(x), one_node, flat_quad, -1e-3, eps_n), std::invalid_argument);
  EXPECT_THROW(call(single(x), one_node, flat_quad, w, 0.0), std::invalid_argument);
  EXPECT_THROW(call(single(x), one_node, flat_quad, std::nan(""), eps_n), std::invalid_argument);
  EXPECT_THROW(call(single(x), Eigen::VectorXd::Ones(2), flat_quad, w, eps_n),
               std::invalid_argument);
  EXPECT_THROW(call(NodeCoordinates(3, 0), Eigen::VectorXd(0), flat_quad, w, eps_n),
               std::invalid_argument);
  EXPECT_THROW(call(single(x), one_node, NodeCoordinates::Random(3, 5), w, eps_n),
               std::invalid_argument);
  NodeCoordinates bad = flat_quad;
  bad(0, 0) = std::nan("");
  EXPECT_THROW(call(single(x), one_node, bad, w, eps_n), std::invalid_argument);
  FacetProjection wrong = p;
  wrong.feature = Feature::Edge;
  wrong.local_index = 4;
  EXPECT_THROW(node_to_surface(single(x), one_node, flat_quad, wrong, w, eps_n),
               std::invalid_argument);
  NodeCoordinates collapsed = flat_quad;
  collapsed.col(3) = collapsed.col(2);
  EXPECT_THROW(node_to_surface(single(x), one_node, collapsed, w, eps_n), std::invalid_argument);
  EXPECT_THROW(node_to_surface_energy(single(x), one_node, collapsed, w, eps_n),
               std::invalid_argument);
  EXPECT_NO_THROW(call(single(x), one_node, flat_quad, 0.0, eps_n));
}

// --- Augmented Lagrangian: multiplier λ_N > 0, p_N = ⟨λ_N − ε_N ĝ⟩ ------------------------------

/// An element with a multiplier: W = w ⟨λ_N − ε_N ĝ⟩² / (2 ε_N), R against FD of W, K against FD
/// of R.
struct AugmentedElement {
  NodeCoordinates slave;
  Eigen::VectorXd weights;
  NodeCoordinates master;
  double lambda;

  Eigen::VectorXd x() const { return stack({slave, master}); }
  double energy(const Eigen::VectorXd& y) const {
    const auto s = unstack(y, {slave, master});
    return node_to_surface_energy(s[0], weights, s[1], w, eps_n, 0.0, lambda);
  }
  Eigen::VectorXd residual(const Eigen::VectorXd& y) const {
    const auto s = unstack(y, {slave, master});
    return node_to_surface(s[0], weights, s[1], w, eps_n, lambda).residual;
  }
  SurfaceContact evaluate() const {
    return node_to_surface(slave, weights, master, w, eps_n, lambda);
  }
};

/// The signed distance ĝ of the tests' own: g on the face, sign(g) |r| off it.
double signed_distance(const SurfaceContact& c, const Eigen::Vector3d& x_s,
                       const NodeCoordinates& m) {
  if (c.feature == Feature::Face) return c.gap;
  const double d = (x_s - surface_point(m, c.xi)).norm();
  return c.gap <= 0 ? -d : d;
}

/// Active (λ_N − ε_N ĝ > 0) on the expected feature: p_N, exact R and K, symmetric K, and the
/// force of magnitude w p_N along ∇ĝ's direction (on the face: −w p_N n on the slave).
SurfaceContact expect_augmented(const AugmentedElement& e, Feature feature) {
  const SurfaceContact c = e.evaluate();
  EXPECT_EQ(c.feature, feature);
  EXPECT_TRUE(c.closed);
  const double g_hat = signed_distance(c, e.slave * e.weights, e.master);
  EXPECT_NEAR(c.pressure, e.lambda - eps_n * g_hat, 1e-12 * e.lambda);
  EXPECT_GT(c.pressure, 0);
  EXPECT_TRUE(c.residual.allFinite() && c.tangent.allFinite());
  const Eigen::VectorXd x = e.x();
  const Eigen::VectorXd dW =
      fd_gradient_stacked([&](const Eigen::VectorXd& y) { return e.energy(y); }, x);
  const Eigen::MatrixXd dR =
      fd_jacobian_stacked([&](const Eigen::VectorXd& y) { return e.residual(y); }, x);
  EXPECT_LE(relative_error(dW, c.residual), 1e-6);
  EXPECT_LE(relative_error(dR, c.tangent), 1e-6);
  EXPECT_EQ(c.tangent, c.tangent.transpose());
  Eigen::Vector3d slave_force = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < e.slave.cols(); ++i) slave_force += c.residual.segment<3>(3 * i);
  EXPECT_NEAR(slave_force.norm(), w * c.pressure, 1e-10 * w * c.pressure);
  if (feature == Feature::Face)
    EXPECT_LE((slave_force + w * c.pressure * c.normal).norm(), 1e-10 * w * c.pressure);
  return c;
}

void expect_open(const AugmentedElement& e) {
  const SurfaceContact c = e.evaluate();
  EXPECT_FALSE(c.closed);
  EXPECT_EQ(c.pressure, 0.0);
  EXPECT_TRUE(c.residual.isZero(0.0));
  EXPECT_TRUE(c.tangent.isZero(0.0));
  EXPECT_EQ(e.energy(e.x()), 0.0);
}

TEST(NodeToSurfaceAugmented, FaceClosedTouchingPositiveGapAndOpen) {
  // Warped quad: the curvature terms (n·x_,12 ≠ 0) are scaled by p_N, not by ε_N ⟨−g⟩.
  const Eigen::Vector2d xi(0.3, -0.2);
  const double lambda = 10.0;  // λ_N/ε_N = 0.04
  for (double gap : {-0.05, 0.0, 0.02, 0.039}) {
    SCOPED_TRACE("gap = " + std::to_string(gap));
    const AugmentedElement e{single(point_at(warped_quad, xi, gap)), one_node, warped_quad, lambda};
    const SurfaceContact c = expect_augmented(e, Feature::Face);
    EXPECT_NEAR(c.gap, gap, 1e-12);
  }
  // λ_N − ε_N g < 0: open although the penalty alone would be too.
  expect_open({single(point_at(warped_quad, xi, 0.041)), one_node, warped_quad, lambda});
  expect_open({single(point_at(warped_quad, xi, 0.3)), one_node, warped_quad, lambda});
  // The geometric term is there: at g > 0 the penalty tangent's curvature part has the wrong
  // sign and size; K − w ε_N ∇g ∇gᵀ is −w p_N ∇²g ≠ 0.
  const AugmentedElement e{single(point_at(warped_quad, xi, 0.02)), one_node, warped_quad, lambda};
  const SurfaceContact c = e.evaluate();
  const Eigen::VectorXd grad = -c.residual / (w * c.pressure);
  EXPECT_GT((c.tangent - w * eps_n * grad * grad.transpose()).norm(), 1e-3 * c.tangent.norm());
}

TEST(NodeToSurfaceAugmented, EdgeAndVertexBelowAndAbove) {
  const int k = 1;
  const Eigen::Vector2d xi_edge(1.0, -0.2);
  const Eigen::Vector3d out_e = edge_outward(warped_quad, k, xi_edge);
  const Eigen::Vector3d n_e = facet_normal(warped_quad, xi_edge);
  const Eigen::Vector2d xi_v = facet_vertex_xi(4, 2);
  const Eigen::Vector3d out_v =
      (edge_outward(warped_quad, 1, xi_v) + edge_outward(warped_quad, 2, xi_v)).normalized();
  const Eigen::Vector3d n_v = facet_normal(warped_quad, xi_v);
  const double lambda = 20.0;  // λ_N/ε_N = 0.08
  struct Case {
    Eigen::Vector3d x;
    Feature feature;
    bool active;
  };
  const Eigen::Vector3d edge_point = surface_point(warped_quad, xi_edge);
  const Eigen::Vector3d vertex = warped_quad.col(2);
  for (const Case& c : {
           Case{edge_point + 0.15 * out_e - 0.1 * n_e, Feature::Edge, true},    // g < 0
           Case{edge_point + 0.03 * out_e + 0.05 * n_e, Feature::Edge, true},   // 0 < |r| < λ/ε
           Case{edge_point + 0.06 * out_e + 0.06 * n_e, Feature::Edge, false},  // |r| > λ/ε
           Case{vertex + 0.1 * out_v - 0.12 * n_v, Feature::Vertex, true},      // g < 0
           Case{vertex + 0.03 * out_v + 0.04 * n_v, Feature::Vertex, true},     // 0 < |r| < λ/ε
           Case{vertex + 0.07 * out_v + 0.05 * n_v, Feature::Vertex, false},    // |r| > λ/ε
       }) {
    SCOPED_TRACE("feature " + std::to_string(static_cast<int>(c.feature)) + ", active " +
                 std::to_string(c.active));
    const AugmentedElement e{single(c.x), one_node, warped_quad, lambda};
    if (c.active) {
      const SurfaceContact r = expect_augmented(e, c.feature);
      // Off the face the force acts along r: on the slave w p_N s r/|r| with the sign of −ĝ.
      const Eigen::Vector3d rv = c.x - surface_point(warped_quad, r.xi);
      const double s = r.gap <= 0 ? -1.0 : 1.0;
      EXPECT_LE((r.residual.head<3>() + w * r.pressure * s * rv.normalized()).norm(),
                1e-10 * w * r.pressure);
    } else {
      EXPECT_EQ(e.evaluate().feature, c.feature);
      expect_open(e);
    }
  }
}

TEST(NodeToSurfaceAugmented, GaussPointAndTriangle) {
  const double g = 1 / std::sqrt(3.0);
  const Eigen::VectorXd M = facet_shape_functions(4, Eigen::Vector2d(-g, g));
  NodeCoordinates slave(3, 4);
  slave << point_at(warped_quad, {-0.5, -0.4}, 0.01), point_at(warped_quad, {0.4, -0.6}, -0.02),
      point_at(warped_quad, {0.5, 0.3}, 0.03), point_at(warped_quad, {-0.6, 0.5}, 0.02);
  const SurfaceContact c = expect_augmented({slave, M, warped_quad, 5.0}, Feature::Face);
  EXPECT_GT(c.gap, 0);  // active at a positive gap
  expect_augmented({single(point_at(triangle, {0.3, 0.25}, 0.01)), one_node, triangle, 5.0},
                   Feature::Face);
  expect_augmented({single(point_at(triangle, {0.3, 0.25}, -0.04)), one_node, triangle, 5.0},
                   Feature::Face);
}

TEST(NodeToSurfaceAugmented, ZeroMultiplierIsThePenaltyAndBadMultipliersThrow) {
  const Eigen::Vector2d xi(0.3, -0.2);
  for (double gap : {-0.05, 0.02}) {
    const NodeCoordinates s = single(point_at(warped_quad, xi, gap));
    const SurfaceContact a = node_to_surface(s, one_node, warped_quad, w, eps_n);
    const SurfaceContact b = node_to_surface(s, one_node, warped_quad, w, eps_n, 0.0);
    EXPECT_EQ(a.residual, b.residual);
    EXPECT_EQ(a.tangent, b.tangent);
    EXPECT_EQ(a.pressure, b.pressure);
    EXPECT_EQ(a.closed, b.closed);
  }
  // At g < 0 the augmented element with λ_N is the penalty element plus −w λ_N ∇g
  // (∇g = −R_penalty / (w p_penalty) on the face).
  const NodeCoordinates s = single(point_at(warped_quad, xi, -0.05));
  const SurfaceContact pen = node_to_surface(s, one_node, warped_quad, w, eps_n);
  const SurfaceContact al = node_to_surface(s, one_node, warped_quad, w, eps_n, 3.0);
  EXPECT_LE((al.residual - pen.residual - 3.0 * w * pen.residual / (w * pen.pressure)).norm(),
            1e-10 * al.residual.norm());
  EXPECT_NEAR(al.pressure, pen.pressure + 3.0, 1e-10);
  for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(node_to_surface(s, one_node, warped_quad, w, eps_n, bad), std::invalid_argument);
    EXPECT_THROW(node_to_surface_energy(s, one_node, warped_quad, w, eps_n, 0.0, bad),
                 std::invalid_argument);
  }
}

}  // namespace
}  // namespace hypercontact
