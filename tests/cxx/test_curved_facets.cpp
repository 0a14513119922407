// Curved master facets — the biquadratic 9-node quadrilateral and the quadratic 6-node triangle:
// the closest-point projection against a brute-force search over the facet, stationarity of the
// closest point, and the normal and friction elements' residuals and tangents against central
// finite differences over every node (slave, current facet, old facet) on the face, a curved edge
// and a vertex, for penalty, augmented Lagrangian and smoothed normal laws, node and Gauss-point
// slaves, stick and slip.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <hypercontact/facet_projection.hpp>
#include <hypercontact/node_to_surface.hpp>
#include <hypercontact/surface_friction.hpp>
#include <random>
#include <string>
#include <vector>

#include "finite_difference.hpp"
#include "surface_element_fd.hpp"

namespace hypercontact {
namespace {

using test::fd_gradient_stacked;
using test::fd_jacobian_stacked;
using test::relative_error;
using test::stack;
using test::unstack;

constexpr double w = 0.37;
constexpr double eps_n = 250.0;
constexpr double eps_t = 180.0;
constexpr double mu = 0.3;

using test::node_xi;

/// A doubly curved surface patch (local frame), its nodes taken at the facet's node ξ, with the
/// edge and centre nodes pushed off the surface a little so that no coefficient is special; then
/// rotated and shifted off the axes. `offset` moves the patch in its plane (neighbours, slave
/// facets) and `lift` along its normal.
NodeCoordinates curved_facet(int n, const Eigen::Vector2d& offset = {0, 0}, double lift = 0.0,
                             double bulge = 1.0) {
  NodeCoordinates x(3, n);
  for (int a = 0; a < n; ++a) {
    const Eigen::Vector2d q = 0.6 * node_xi(n, a) + offset;
    double z = bulge * (0.25 * q[0] * q[0] + 0.15 * q[1] * q[1] + 0.08 * q[0] * q[1]) + lift;
    Eigen::Vector3d local(q[0], q[1], z);
    if (a >= (n == 6 ? 3 : 4)) local += 0.02 * Eigen::Vector3d(std::sin(3.0 * a), std::cos(2.0 * a), 0.5);
    x.col(a) = test::test_rotation * local + test::test_shift;
  }
  return x;
}

Eigen::Vector3d surface_point(const NodeCoordinates& m, const Eigen::Vector2d& xi) {
  return m * facet_shape_functions(static_cast<int>(m.cols()), xi);
}
Eigen::Vector3d point_at(const NodeCoordinates& m, const Eigen::Vector2d& xi, double gap) {
  return surface_point(m, xi) + gap * facet_normal(m, xi);
}
bool in_reference(int n, const Eigen::Vector2d& xi) {
  if (n == 9) return xi.cwiseAbs().maxCoeff() <= 1;
  return xi[0] >= 0 && xi[1] >= 0 && xi[0] + xi[1] <= 1;
}

/// min over a fine ξ grid of |x_s − x_M(ξ)|, refined around the best grid point by a second grid:
/// an upper bound of the true distance within ~1e-9 of it.
double brute_force_distance(const NodeCoordinates& m, const Eigen::Vector3d& xs) {
  const int n = static_cast<int>(m.cols());
  const double lo = n == 9 ? -1.0 : 0.0, span = n == 9 ? 2.0 : 1.0;
  const auto clamp_in = [&](Eigen::Vector2d xi) {
    if (n == 9) return Eigen::Vector2d(xi.cwiseMax(-1.0).cwiseMin(1.0));
    xi = xi.cwiseMax(0.0);
    const double s = xi.sum();
    return s > 1 ? Eigen::Vector2d(xi / s) : xi;
  };
  Eigen::Vector2d best_xi(lo, lo);
  double best = (xs - surface_point(m, best_xi)).norm();
  double h = span / 200;
  Eigen::Vector2d centre = Eigen::Vector2d::Constant(lo + span / 2);
  double half = span / 2;
  for (int level = 0; level < 4; ++level) {
    for (int i = -100; i <= 100; ++i)
      for (int j = -100; j <= 100; ++j) {
        const Eigen::Vector2d xi = clamp_in(centre + h * Eigen::Vector2d(i, j));
        if (!in_reference(n, xi)) continue;
        const double d = (xs - surface_point(m, xi)).norm();
        if (d < best) best = d, best_xi = xi;
      }
    centre = best_xi;
    half = 2 * h;
    h = half / 100;
  }
  return best;
}

TEST(CurvedFacets, ProjectionIsTheClosestPointOfTheFacet) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n : {6, 9}) {
    const NodeCoordinates m = curved_facet(n);
    int faces = 0, edges = 0, vertices = 0;
    // Points around the facet: above, below and beyond its edges, and beyond each corner.
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 60; ++i) {
      const double spread = i % 2 ? 0.9 : 0.5;  // every other point over the facet
      const Eigen::Vector3d local(spread * u(rng) + (n == 6 ? 0.25 : 0.0),
                                  spread * u(rng) + (n == 6 ? 0.25 : 0.0), 0.3 * u(rng));
      points.push_back(test::test_rotation * local + test::test_shift);
    }
    const Eigen::Vector3d centre = m.rowwise().mean();
    for (int k = 0; k < (n == 9 ? 4 : 3); ++k)
      points.push_back(m.col(k) + 0.4 * (m.col(k) - centre) + 0.05 * facet_normal(m, facet_vertex_xi(n, k)));
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d& xs = points[i];
      const FacetProjection p = project_to_facet(m, xs);
      SCOPED_TRACE("n = " + std::to_string(n) + ", point " + std::to_string(i));
      ASSERT_TRUE(p.converged);
      const double brute = brute_force_distance(m, xs);
      EXPECT_LE(p.distance, brute + 1e-12);
      EXPECT_GE(p.distance, brute - 1e-8);
      EXPECT_LE((p.point - surface_point(m, p.xi)).norm(), 1e-14);
      const Eigen::Vector3d r = xs - p.point;
      const Eigen::Matrix<double, 3, 2> a = m * facet_shape_derivatives(n, p.xi);
      if (p.feature == Feature::Face) {
        ++faces;
        EXPECT_LE(std::abs(r.dot(a.col(0))) + std::abs(r.dot(a.col(1))), 1e-10);
        EXPECT_NEAR(std::abs(r.dot(p.normal)), r.norm(), 1e-10);
      } else if (p.feature == Feature::Edge) {
        ++edges;
        const int k = p.local_index;
        const Eigen::Vector2d T = facet_vertex_xi(n, k + 1) - facet_vertex_xi(n, k);
        EXPECT_LE(std::abs(r.dot(a * T)), 1e-10 * (1 + r.norm()));  // stationary along the edge
        // ξ* exactly on the edge's line in ξ.
        const Eigen::Vector2d d = p.xi - facet_vertex_xi(n, k);
        EXPECT_NEAR(d[0] * T[1] - d[1] * T[0], 0.0, 1e-15);
      } else {
        ++vertices;
        EXPECT_EQ(p.xi, facet_vertex_xi(n, p.local_index));
      }
    }
    EXPECT_GT(faces, 5);
    EXPECT_GT(edges, 5);
    EXPECT_GT(vertices, 0);
  }
}

TEST(CurvedFacets, CurvedEdgeIsNotItsChord) {
  // A point beyond edge 0 of a strongly bulged edge: the closest point is on the parabola
  // through the edge node, nearer than the chord between the corners would give.
  for (int n : {6, 9}) {
    NodeCoordinates m = curved_facet(n, {0, 0}, 0.0, 0.0);  // flat, then bulge edge 0 outward
    const Eigen::Vector3d mid_chord = 0.5 * (m.col(0) + m.col(1));
    const Eigen::Vector3d chord = (m.col(1) - m.col(0)).normalized();
    const Eigen::Vector3d to_centre =
        surface_point(m, n == 9 ? Eigen::Vector2d(0, 0) : Eigen::Vector2d(1.0 / 3, 1.0 / 3)) -
        mid_chord;
    // Inward across the edge, perpendicular to its chord: the apex of the parabola is then the
    // closest point of the edge to x_s.
    const Eigen::Vector3d inward = (to_centre - to_centre.dot(chord) * chord).normalized();
    const int edge_node = n == 9 ? 4 : 3;
    m.col(edge_node) = mid_chord - 0.1 * inward;
    const Eigen::Vector3d xs = mid_chord - 0.3 * inward;
    const FacetProjection p = project_to_facet(m, xs);
    EXPECT_EQ(p.feature, Feature::Edge);
    EXPECT_EQ(p.local_index, 0);
    EXPECT_NEAR(p.distance, 0.2, 1e-12);  // the parabola's apex is its edge node
    EXPECT_NEAR(p.distance, brute_force_distance(m, xs), 1e-8);
  }
}

// ---------------------------------------------------------------- normal element

struct NormalElement {
  NodeCoordinates slave;
  Eigen::VectorXd weights;
  NodeCoordinates master;
  double lambda = 0.0, smoothing = 0.0;

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

void expect_exact(const NormalElement& e, Feature feature) {
  const SurfaceContact c = e.evaluate();
  EXPECT_EQ(c.feature, feature);
  ASSERT_TRUE(c.closed);
  ASSERT_TRUE(c.residual.allFinite() && c.tangent.allFinite());
  const Eigen::VectorXd x = e.x();
  const Eigen::VectorXd dW =
      fd_gradient_stacked([&](const Eigen::VectorXd& y) { return e.energy(y); }, x);
  const Eigen::MatrixXd dR =
      fd_jacobian_stacked([&](const Eigen::VectorXd& y) { return e.residual(y); }, x);
  EXPECT_LE(relative_error(dW, c.residual), 1e-6);
  EXPECT_LE(relative_error(dR, c.tangent), 1e-6);
  EXPECT_EQ(c.tangent, c.tangent.transpose());
}

/// The slave as one node, or as a Gauss point of a curved slave facet over the master.
struct Slave {
  NodeCoordinates x;
  Eigen::VectorXd weights;
};
Slave node_slave(const Eigen::Vector3d& p) { return {p, Eigen::VectorXd::Ones(1)}; }
/// A Gauss point of a curved slave facet of n nodes placed so that the point sits at `target`.
Slave gauss_slave(int n, const Eigen::Vector3d& target) {
  const Eigen::Vector2d xi_g = n == 9 ? Eigen::Vector2d(0.3, -0.5) : Eigen::Vector2d(0.2, 0.3);
  NodeCoordinates x = curved_facet(n, {0.1, -0.05}, 0.05);
  const Eigen::VectorXd M = facet_shape_functions(n, xi_g);
  x.colwise() += target - x * M;
  return {x, M};
}

TEST(CurvedFacets, NormalElementFaceEdgeVertexAgainstFiniteDifferences) {
  for (int n : {6, 9}) {
    const NodeCoordinates m = curved_facet(n);
    const Eigen::Vector2d xi_face = n == 9 ? Eigen::Vector2d(0.35, -0.25) : Eigen::Vector2d(0.3, 0.25);
    for (int slave_nodes : {1, 6, 9}) {
      SCOPED_TRACE("facet " + std::to_string(n) + ", slave of " + std::to_string(slave_nodes));
      const auto slave_at = [&](const Eigen::Vector3d& p) {
        return slave_nodes == 1 ? node_slave(p) : gauss_slave(slave_nodes, p);
      };
      // Face: penalty at two depths (the curvature terms scale with g).
      for (double gap : {-0.02, -0.12}) {
        const Slave s = slave_at(point_at(m, xi_face, gap));
        expect_exact({s.x, s.weights, m}, Feature::Face);
      }
      // Augmented (an open gap inside λ/ε_N) and smoothed.
      {
        const Slave s = slave_at(point_at(m, xi_face, 0.004));
        expect_exact({s.x, s.weights, m, 2.0}, Feature::Face);
        const Slave t = slave_at(point_at(m, xi_face, -0.003));
        expect_exact({t.x, t.weights, m, 0.0, 0.01}, Feature::Face);
        expect_exact({t.x, t.weights, m, 1.5, 0.01}, Feature::Face);
      }
      // Beyond curved edge 0 (the middle of the edge, pushed out in the tangent plane and in).
      {
        const Eigen::Vector2d xi_e = n == 9 ? Eigen::Vector2d(0.2, -1) : Eigen::Vector2d(0.45, 0);
        const Eigen::Vector3d nrm = facet_normal(m, xi_e);
        const Eigen::Vector3d along = (m * facet_shape_derivatives(n, xi_e)) *
                                      (facet_vertex_xi(n, 1) - facet_vertex_xi(n, 0));
        const Eigen::Vector3d out = along.cross(nrm).normalized();
        const Slave s = slave_at(surface_point(m, xi_e) + 0.03 * out - 0.05 * nrm);
        expect_exact({s.x, s.weights, m}, Feature::Edge);
        expect_exact({s.x, s.weights, m, 1.0}, Feature::Edge);
      }
      // Beyond corner 2.
      {
        const Eigen::Vector2d xi_v = facet_vertex_xi(n, 2);
        const Eigen::Vector3d nrm = facet_normal(m, xi_v);
        const Eigen::Vector3d c = surface_point(m, n == 9 ? Eigen::Vector2d(0, 0)
                                                          : Eigen::Vector2d(1.0 / 3, 1.0 / 3));
        const Eigen::Vector3d away = (m.col(2) - c).normalized();
        const Slave s = slave_at(m.col(2) + 0.08 * away - 0.04 * nrm);
        expect_exact({s.x, s.weights, m}, Feature::Vertex);
      }
    }
  }
}

TEST(CurvedFacets, TangentNeedsTheFacetsPureSecondDerivatives) {
  // On a curved face with g ≠ 0 the Hessian of the distance holds r·x_,11 and r·x_,22; the
  // bilinear element's tangent (only x_,12) is off by much more than the finite-difference error.
  for (int n : {6, 9}) {
    const NodeCoordinates m = curved_facet(n, {0, 0}, 0.0, 4.0);
    const Eigen::Vector2d xi = n == 9 ? Eigen::Vector2d(0.1, 0.2) : Eigen::Vector2d(0.3, 0.3);
    const double gap = -0.15;
    const NormalElement e{point_at(m, xi, gap), Eigen::VectorXd::Ones(1), m};
    const SurfaceContact c = e.evaluate();
    ASSERT_EQ(c.feature, Feature::Face);
    const Eigen::Matrix2d H_full = [&] {
      const Eigen::Matrix<double, 3, 2> a = m * facet_shape_derivatives(n, c.xi);
      return distance_hessian(a, gap * c.normal,
                              m * facet_shape_second_derivatives(n, c.xi));
    }();
    const Eigen::Matrix<double, 3, 2> a = m * facet_shape_derivatives(n, c.xi);
    const Eigen::Matrix2d metric = a.transpose() * a;
    // The pure second derivatives change H by a fraction that the tangent must see.
    EXPECT_GT((H_full - metric).diagonal().cwiseAbs().maxCoeff(), 0.05 * metric.trace());
    const Eigen::MatrixXd dR = fd_jacobian_stacked(
        [&](const Eigen::VectorXd& y) { return e.residual(y); }, e.x());
    EXPECT_LE(relative_error(dR, c.tangent), 1e-6);
  }
}

// ---------------------------------------------------------------- friction element

struct FrictionElement {
  NodeCoordinates slave;
  Eigen::VectorXd weights;
  NodeCoordinates master, old;
  Eigen::Vector2d xi_old;
  Eigen::Vector3d t_old;
  double lambda = 0.0;

  Eigen::VectorXd x() const { return stack({slave, master, old}); }
  SurfaceFriction evaluate() const {
    return surface_friction(slave, weights, master, old, xi_old, t_old, w, eps_n, eps_t, mu,
                            lambda);
  }
  Eigen::VectorXd residual(const Eigen::VectorXd& y) const {
    const auto s = unstack(y, {slave, master, old});
    return surface_friction(s[0], weights, s[1], s[2], xi_old, t_old, w, eps_n, eps_t, mu, lambda)
        .residual;
  }
};

void expect_exact(const FrictionElement& e, StickSlip state) {
  const SurfaceFriction f = e.evaluate();
  EXPECT_EQ(f.state, state);
  ASSERT_TRUE(f.residual.allFinite() && f.tangent.allFinite());
  const Eigen::MatrixXd J =
      fd_jacobian_stacked([&](const Eigen::VectorXd& y) { return e.residual(y); }, e.x());
  EXPECT_LE(relative_error(J, f.tangent), 1e-6);
  EXPECT_LE(f.traction.norm(), mu * f.pressure * (1 + 1e-12));
  if (state == StickSlip::Slip) EXPECT_NEAR(f.traction.norm(), mu * f.pressure, 1e-12 * f.pressure);
}

TEST(CurvedFacets, FrictionStickAndSlipAgainstFiniteDifferences) {
  for (int n : {6, 9}) {
    const NodeCoordinates m = curved_facet(n);
    // The old facet: a neighbour patch of the same surface kind.
    const NodeCoordinates old = curved_facet(n, {0.5, 0.1});
    const Eigen::Vector2d xi = n == 9 ? Eigen::Vector2d(0.3, -0.2) : Eigen::Vector2d(0.3, 0.25);
    for (int slave_nodes : {1, 9}) {
      SCOPED_TRACE("facet " + std::to_string(n) + ", slave of " + std::to_string(slave_nodes));
      const Eigen::Vector3d target = point_at(m, xi, -0.03);
      const Slave s = slave_nodes == 1 ? node_slave(target) : gauss_slave(9, target);
      const Eigen::Vector3d nrm = facet_normal(m, xi);
      // Stick: a history a hair away on the same facet.
      expect_exact({s.x, s.weights, m, m, xi + Eigen::Vector2d(0.002, 0.001), 0.2 * nrm.unitOrthogonal()},
                   StickSlip::Stick);
      // Slip: history far away on the old facet, with and without a stored traction.
      for (const Eigen::Vector3d& t_old : {Eigen::Vector3d::Zero().eval(),
                                           (0.9 * nrm.unitOrthogonal() + 0.3 * nrm).eval()}) {
        expect_exact({s.x, s.weights, m, old, Eigen::Vector2d(0.1, 0.1), t_old}, StickSlip::Slip);
        expect_exact({s.x, s.weights, m, old, Eigen::Vector2d(0.1, 0.1), t_old, 1.0},
                     StickSlip::Slip);
      }
    }
  }
}

TEST(CurvedFacets, OldFacetOfAnotherKindIsRefused) {
  const NodeCoordinates m = curved_facet(9);
  const NodeCoordinates quad = m.leftCols(4);
  const Eigen::Vector3d xs = point_at(m, {0.1, 0.1}, -0.02);
  EXPECT_THROW(surface_friction(xs, Eigen::VectorXd::Ones(1), m, quad, {0, 0},
                                Eigen::Vector3d::Zero(), w, eps_n, eps_t, mu),
               std::invalid_argument);
  EXPECT_THROW(surface_friction(xs, Eigen::VectorXd::Ones(1), quad, m, {0, 0},
                                Eigen::Vector3d::Zero(), w, eps_n, eps_t, mu),
               std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
