// Coulomb friction against a deformable master facet: the tangent against central finite
// differences of the residual over every node (slave, current facet, old facet) in stick and
// slip, on both sides of the transition, with the history on another facet, on edges, vertices,
// Gauss points and triangles; closed forms; frame invariance; a sliding sequence across facets
// against its closed-form dissipation; bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <hypercontact/facet_projection.hpp>
#include <hypercontact/narrow_phase.hpp>
#include <hypercontact/node_to_surface.hpp>
#include <hypercontact/surface_friction.hpp>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "finite_difference.hpp"
#include "surface_element_fd.hpp"

namespace hypercontact {
namespace {

using test::edge_outward;
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

constexpr double w = 0.37;
constexpr double eps_n = 250.0;
constexpr double eps_t = 180.0;
constexpr double mu = 0.3;

using test::placed;
const Eigen::Matrix3d& rotation = test::test_rotation;
const Eigen::Vector3d& shift = test::test_shift;

const NodeCoordinates warped_a =
    placed({{0, 0, 0.2}, {1.2, 0.1, -0.1}, {1.1, 0.9, 0.3}, {-0.1, 1, -0.2}});
/// Shares warped_a's edge 1 (its nodes 1, 2) as its edge 3.
const NodeCoordinates warped_b =
    placed({{1.2, 0.1, -0.1}, {2.3, 0.0, 0.15}, {2.2, 1.1, -0.1}, {1.1, 0.9, 0.3}});

/// A friction element: the unknowns are slave, current facet and old facet nodes.
struct Element {
  NodeCoordinates slave;
  Eigen::VectorXd weights;
  NodeCoordinates master;
  NodeCoordinates old;
  Eigen::Vector2d xi_old;
  Eigen::Vector3d t_old;
  double mu_ = mu;
  double lambda = 0.0;  ///< augmented Lagrangian multiplier λ_N (0: penalty)

  Eigen::VectorXd x() const { return stack({slave, master, old}); }
  SurfaceFriction evaluate() const {
    return surface_friction(slave, weights, master, old, xi_old, t_old, w, eps_n, eps_t, mu_,
                            lambda);
  }
  Eigen::VectorXd residual(const Eigen::VectorXd& y) const {
    const auto s = unstack(y, {slave, master, old});
    return surface_friction(s[0], weights, s[1], s[2], xi_old, t_old, w, eps_n, eps_t, mu_, lambda)
        .residual;
  }
  double fd_error(const Eigen::MatrixXd& tangent) const {
    const Eigen::MatrixXd J =
        fd_jacobian_stacked([&](const Eigen::VectorXd& y) { return residual(y); }, x());
    return relative_error(J, tangent);
  }
};

/// Branch, feature, exact tangent, bookkeeping shared by every state.
SurfaceFriction expect_exact(const Element& e, StickSlip state, Feature feature) {
  const SurfaceFriction f = e.evaluate();
  EXPECT_EQ(f.state, state);
  EXPECT_EQ(f.feature, feature);
  EXPECT_TRUE(f.residual.allFinite() && f.tangent.allFinite());
  EXPECT_LE(e.fd_error(f.tangent), 1e-6);
  const Eigen::Index dofs = 3 * (e.slave.cols() + e.master.cols());
  EXPECT_TRUE(f.residual.tail(3 * e.old.cols()).isZero(0.0));
  EXPECT_TRUE(f.tangent.bottomRows(3 * e.old.cols()).isZero(0.0));
  // R = w [M_i t; −N_a t]: the forces balance (Σ M_i = 1).
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (Eigen::Index a = 0; a < dofs / 3; ++a) total += f.residual.segment<3>(3 * a);
  EXPECT_LE(total.norm(), 1e-12 * std::max(1.0, f.residual.norm()));
  const double radius = mu * f.pressure;
  EXPECT_LE(f.traction.norm(), e.mu_ * f.pressure * (1 + 1e-12));
  EXPECT_NEAR(f.traction.dot(f.normal), 0.0, 1e-12 * std::max(1.0, radius));
  EXPECT_NEAR(f.dissipation, w * f.traction.dot(f.slip_increment), 1e-12);
  if (state == StickSlip::Slip) {
    EXPECT_NEAR(f.traction.norm(), e.mu_ * f.pressure, 1e-12 * radius);
    EXPECT_NEAR(f.dissipation, e.mu_ * f.pressure * f.slip_increment.norm() * w, 1e-12);
  } else {
    EXPECT_EQ(f.slip_increment, Eigen::Vector3d::Zero());
    EXPECT_EQ(f.dissipation, 0.0);
  }
  return f;
}

/// P = [M_i I, −N_a I, 0] at ξ.
Eigen::MatrixXd P_matrix(const Element& e, const Eigen::Vector2d& xi) {
  const Eigen::Index ns = e.slave.cols(), nm = e.master.cols(), no = e.old.cols();
  const Eigen::VectorXd N = facet_shape_functions(static_cast<int>(nm), xi);
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3, 3 * (ns + nm + no));
  for (Eigen::Index i = 0; i < ns; ++i)
    P.middleCols<3>(3 * i) = e.weights[i] * Eigen::Matrix3d::Identity();
  for (Eigen::Index a = 0; a < nm; ++a)
    P.middleCols<3>(3 * (ns + a)) = -N[a] * Eigen::Matrix3d::Identity();
  return P;
}

TEST(SurfaceFriction, StickOnFlatQuadClosedForm) {
  const Eigen::Vector2d xi(0.3, -0.2), xi_old(0.296, -0.197);
  const Element e{single(point_at(flat_quad, xi, -0.02)),
                  one_node,
                  flat_quad,
                  flat_quad,
                  xi_old,
                  Eigen::Vector3d::Zero()};
  const SurfaceFriction f = expect_exact(e, StickSlip::Stick, Feature::Face);
  EXPECT_NEAR(f.pressure, 5.0, 1e-12);
  const Eigen::Vector3d expected =
      eps_t * (surface_point(flat_quad, xi) - surface_point(flat_quad, xi_old));
  EXPECT_LE((f.traction - expected).norm(), 1e-10 * expected.norm());
  EXPECT_LE(relative_error(f.residual, w * P_matrix(e, f.xi).transpose() * f.traction), 1e-12);
  // The old facet's columns: −ε_T w Pᵀ P_T N_b(ξ_old) (a flat facet, stick).
  const Eigen::Matrix3d P_T = Eigen::Matrix3d::Identity() - f.normal * f.normal.transpose();
  const Eigen::VectorXd N_old = facet_shape_functions(4, xi_old);
  for (int b = 0; b < 4; ++b)
    EXPECT_LE(relative_error(f.tangent.block<3, 3>(0, 15 + 3 * b), -w * eps_t * N_old[b] * P_T),
              1e-12);
}

TEST(SurfaceFriction, SlipOnWarpedQuadSeveralDirectionsWithAndWithoutHistory) {
  const Eigen::Vector2d xi(0.3, -0.2);
  const Eigen::Vector3d x = point_at(warped_a, xi, -0.02);
  const Eigen::Vector3d n = facet_normal(warped_a, xi);
  for (double theta : {0.0, 1.1, 2.5, 4.0, 5.5}) {
    const Eigen::Vector2d xi_old = xi - 0.05 * Eigen::Vector2d(std::cos(theta), std::sin(theta));
    const Eigen::Vector3d tangential = n.unitOrthogonal() * std::cos(theta + 2) +
                                       n.cross(n.unitOrthogonal()) * std::sin(theta + 2);
    for (const Eigen::Vector3d& t_old : {Eigen::Vector3d::Zero().eval(), (0.9 * tangential).eval(),
                                         (0.9 * tangential + 0.4 * n).eval()}) {
      SCOPED_TRACE("theta = " + std::to_string(theta));
      expect_exact(Element{single(x), one_node, warped_a, warped_a, xi_old, t_old}, StickSlip::Slip,
                   Feature::Face);
    }
  }
}

TEST(SurfaceFriction, StickOnWarpedQuadWithHistory) {
  const Eigen::Vector2d xi(-0.4, 0.5);
  const Eigen::Vector3d n = facet_normal(warped_a, xi);
  for (double gap : {-0.02, -0.15}) {
    const Element e{single(point_at(warped_a, xi, gap)),
                    one_node,
                    warped_a,
                    warped_a,
                    xi + Eigen::Vector2d(0.002, 0.001),
                    0.5 * n.unitOrthogonal() + 0.2 * n};
    expect_exact(e, StickSlip::Stick, Feature::Face);
  }
}

/// t_old = −ε_T P_T (x_s − x_old) + target u (u: direction projected on the tangent plane), so
/// that t_trial = target u at the element's current configuration.
Eigen::Vector3d tuned_t_old(const Element& e, const Eigen::Vector3d& direction, double target) {
  const SurfaceFriction f = e.evaluate();
  const Eigen::Matrix3d P_T = Eigen::Matrix3d::Identity() - f.normal * f.normal.transpose();
  const Eigen::Vector3d x_old =
      e.old * facet_shape_functions(static_cast<int>(e.old.cols()), e.xi_old);
  return -eps_t * P_T * (e.slave * e.weights - x_old) + target * (P_T * direction).normalized();
}

TEST(SurfaceFriction, BothSidesOfTheStickSlipTransition) {
  for (const NodeCoordinates& m : {warped_a, triangle}) {
    const Eigen::Vector2d xi(0.3, 0.2);
    const double gap = -0.03, radius = mu * eps_n * 0.03;
    Element e{single(point_at(m, xi, gap)), one_node, m, m, xi - Eigen::Vector2d(0.003, -0.002),
              Eigen::Vector3d::Zero()};
    ASSERT_NEAR(e.evaluate().gap, gap, 1e-12);
    // Φ = ±1e-3 radius, far above what a finite-difference step changes.
    for (const auto& [factor, state] :
         {std::pair{1 - 1e-3, StickSlip::Stick}, std::pair{1 + 1e-3, StickSlip::Slip}}) {
      e.t_old = tuned_t_old(e, Eigen::Vector3d(0.3, -1, 0.5), factor * radius);
      const SurfaceFriction f = expect_exact(e, state, Feature::Face);
      EXPECT_NEAR(f.traction.norm(), std::min(factor, 1.0) * radius, 1e-10 * radius);
    }
  }
}

TEST(SurfaceFriction, HistoryOnAnotherFacet) {
  // The slave point is now over facet B, next to the edge B shares with A; its history is a
  // point of A. The old facet's nodes are unknowns of their own.
  const Eigen::Vector3d x = point_at(warped_b, {-0.99, 0.2}, -0.02);
  ASSERT_EQ(project_to_facet(warped_b, x).feature, Feature::Face);
  // Stick: history on the shared edge (ξ_A = (1, 0.2) is ξ_B = (−1, 0.2)).
  const Element stick{single(x), one_node, warped_b, warped_a, {1.0, 0.2}, Eigen::Vector3d::Zero()};
  const SurfaceFriction f = expect_exact(stick, StickSlip::Stick, Feature::Face);
  EXPECT_GT(f.tangent.rightCols(12).cwiseAbs().maxCoeff(), 1.0);  // x_old depends on A's nodes
  // Slip: history further inside A, with a traction.
  expect_exact(Element{single(x),
                       one_node,
                       warped_b,
                       warped_a,
                       {0.9, 0.25},
                       0.3 * facet_normal(warped_a, {0.9, 0.25}).unitOrthogonal()},
               StickSlip::Slip, Feature::Face);
  // The trial traction sees the old facet's current nodes: B's shared nodes and A's are the
  // same points, so A carried along (here: the shared edge) gives the same x_old as B would.
  const Element same_point{single(x), one_node,    warped_b,
                           warped_b,  {-1.0, 0.2}, Eigen::Vector3d::Zero()};
  EXPECT_LE((same_point.evaluate().traction - f.traction).norm(), 1e-12 * f.traction.norm());
}

TEST(SurfaceFriction, SameFacetAsHistoryColumnsAddUp) {
  // Old facet = current facet: the derivative w.r.t. a master node is the sum of its current and
  // old columns.
  const Eigen::Vector2d xi(0.1, 0.4);
  const Eigen::Vector3d x = point_at(warped_a, xi, -0.04);
  for (const Eigen::Vector2d& xi_old : {Eigen::Vector2d(0.104, 0.397), Eigen::Vector2d(0.2, 0.3)}) {
    const auto residual = [&](const Eigen::VectorXd& y) {
      const auto s = unstack(y, {single(x), warped_a});
      return surface_friction(s[0], one_node, s[1], s[1], xi_old, Eigen::Vector3d::Zero(), w, eps_n,
                              eps_t, mu)
          .residual.head(15)
          .eval();
    };
    const SurfaceFriction f = surface_friction(single(x), one_node, warped_a, warped_a, xi_old,
                                               Eigen::Vector3d::Zero(), w, eps_n, eps_t, mu);
    Eigen::MatrixXd folded = f.tangent.topLeftCorner(15, 15);
    folded.rightCols(12) += f.tangent.block(0, 15, 15, 12);
    EXPECT_LE(relative_error(fd_jacobian_stacked(residual, stack({single(x), warped_a})), folded),
              1e-6);
  }
}

TEST(SurfaceFriction, EdgeVertexGaussPointAndTriangle) {
  // Beyond edge 1 of the warped quad, below its plane; t_old cancels most of the trial traction
  // for stick, or not for slip.
  const Eigen::Vector2d xi_edge(1.0, -0.2);
  const Eigen::Vector3d x_edge = surface_point(warped_a, xi_edge) +
                                 0.15 * edge_outward(warped_a, 1, xi_edge) -
                                 0.1 * facet_normal(warped_a, xi_edge);
  const Eigen::Vector2d xi_v = facet_vertex_xi(4, 2);
  const Eigen::Vector3d x_vertex =
      warped_a.col(2) +
      0.1 * (edge_outward(warped_a, 1, xi_v) + edge_outward(warped_a, 2, xi_v)).normalized() -
      0.12 * facet_normal(warped_a, xi_v);
  for (const auto& [x, feature] :
       {std::pair{x_edge, Feature::Edge}, std::pair{x_vertex, Feature::Vertex}}) {
    Element e{single(x), one_node, warped_a, warped_a, {0.8, -0.1}, Eigen::Vector3d::Zero()};
    expect_exact(e, StickSlip::Slip, feature);
    e.t_old = tuned_t_old(e, Eigen::Vector3d(1, 0.2, -0.3), 0.5 * mu * e.evaluate().pressure);
    expect_exact(e, StickSlip::Stick, feature);
  }
  // Gauss point of a slave quadrilateral against the warped quad, and against a triangle.
  const double g = 1 / std::sqrt(3.0);
  const Eigen::VectorXd M = facet_shape_functions(4, Eigen::Vector2d(g, -g));
  NodeCoordinates slave(3, 4);
  slave << point_at(warped_a, {-0.5, -0.4}, -0.03), point_at(warped_a, {0.4, -0.6}, -0.06),
      point_at(warped_a, {0.5, 0.3}, 0.01), point_at(warped_a, {-0.6, 0.5}, -0.09);
  Element gauss{slave, M, warped_a, warped_a, {0.2, -0.5}, Eigen::Vector3d::Zero()};
  expect_exact(gauss, StickSlip::Slip, Feature::Face);
  gauss.t_old = tuned_t_old(gauss, Eigen::Vector3d(0, 1, 1), 0.7 * mu * gauss.evaluate().pressure);
  expect_exact(gauss, StickSlip::Stick, Feature::Face);
  Element tri{single(point_at(triangle, {0.3, 0.25}, -0.04)),
              one_node,
              triangle,
              warped_a,
              {0.5, 0.5},
              Eigen::Vector3d::Zero()};  // triangle now, history on a quad
  expect_exact(tri, StickSlip::Slip, Feature::Face);
  tri.t_old = tuned_t_old(tri, Eigen::Vector3d(1, 1, 0), 0.6 * mu * tri.evaluate().pressure);
  expect_exact(tri, StickSlip::Stick, Feature::Face);
}

TEST(SurfaceFriction, OpenAndFrictionless) {
  const Eigen::Vector2d xi(0.3, -0.2);
  const Element open{
      single(point_at(warped_a, xi, 0.01)), one_node, warped_a, warped_a, {0.1, 0.1}, {1, 2, 3}};
  const SurfaceFriction f = open.evaluate();
  EXPECT_EQ(f.state, StickSlip::Open);
  EXPECT_TRUE(f.residual.isZero(0.0) && f.tangent.isZero(0.0));
  EXPECT_EQ(f.traction, Eigen::Vector3d::Zero());
  EXPECT_EQ(f.slip_increment, Eigen::Vector3d::Zero());
  EXPECT_EQ(f.dissipation, 0.0);
  EXPECT_EQ(f.residual.size(), 27);
  Element frictionless{single(point_at(warped_a, xi, -0.02)),
                       one_node,
                       warped_a,
                       warped_a,
                       {0.25, -0.1},
                       {0.1, 0.2, 0.3}};
  frictionless.mu_ = 0.0;
  const SurfaceFriction z = frictionless.evaluate();
  EXPECT_EQ(z.state, StickSlip::Slip);
  EXPECT_TRUE(z.residual.isZero(0.0) && z.tangent.isZero(0.0));
  EXPECT_EQ(z.dissipation, 0.0);
  const Eigen::Matrix3d P_T = Eigen::Matrix3d::Identity() - z.normal * z.normal.transpose();
  const Eigen::Vector3d t_trial =
      P_T * (frictionless.t_old +
             eps_t * (frictionless.slave.col(0) - surface_point(warped_a, frictionless.xi_old)));
  EXPECT_LE((z.slip_increment - t_trial / eps_t).norm(), 1e-14);
}

TEST(SurfaceFriction, RigidMotionOfEverything) {
  // Translating all nodes changes nothing; rotating them rotates R and K (and t_old with them).
  const Element e{single(point_at(warped_a, {0.2, 0.1}, -0.03)),
                  one_node,
                  warped_a,
                  warped_b,
                  {-0.9, 0.3},
                  Eigen::Vector3d(0.2, -0.4, 0.1)};
  const SurfaceFriction f = e.evaluate();
  const Eigen::Vector3d d(0.3, -1.2, 2.0);
  const Element moved{e.slave.colwise() + d, one_node, e.master.colwise() + d,
                      e.old.colwise() + d,   e.xi_old, e.t_old};
  const SurfaceFriction g = moved.evaluate();
  EXPECT_EQ(g.state, f.state);
  EXPECT_LE(relative_error(g.residual, f.residual), 1e-12);
  EXPECT_LE(relative_error(g.tangent, f.tangent), 1e-11);
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(1.3, Eigen::Vector3d(0.2, 1, -0.4).normalized()).toRotationMatrix();
  const Element turned{Q * e.slave, one_node, Q * e.master, Q * e.old, e.xi_old, Q * e.t_old};
  const SurfaceFriction h = turned.evaluate();
  Eigen::MatrixXd QQ = Eigen::MatrixXd::Zero(27, 27);
  for (int a = 0; a < 9; ++a) QQ.block<3, 3>(3 * a, 3 * a) = Q;
  EXPECT_LE(relative_error(h.residual, QQ * f.residual), 1e-12);
  EXPECT_LE(relative_error(h.tangent, QQ * f.tangent * QQ.transpose()), 1e-11);
}

TEST(SurfaceFriction, SlidingSequenceAcrossFacetsMatchesClosedForm) {
  // A flat strip of three facets; the slave node keeps a penetration δ and moves by Δu per step
  // along the strip, crossing two facet boundaries. History (facet, ξ*, t) is carried from step
  // to step. Stick while ε_T u_k < μ p_N, then slide with |t| = μ p_N; the total dissipation is
  // μ p_N w (u_total − μ p_N/ε_T), as for a rigid plane.
  std::vector<double> coords;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d p = rotation * Eigen::Vector3d(i, j, 0) + shift;
      coords.insert(coords.end(), {p.x(), p.y(), p.z()});
    }
  const std::vector<std::int32_t> quads{0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6};
  const std::vector<std::int32_t> candidates{0, 1, 2};
  const double depth = 0.02, du = 0.002, p_n = eps_n * depth, radius = mu * p_n;
  const int steps = 1300;  // stick for 4 steps, then slip
  const Eigen::Vector3d e = rotation * Eigen::Vector3d(1, 0.1, 0).normalized();
  const Eigen::Vector3d x0 = rotation * Eigen::Vector3d(0.2, 0.4, -depth) + shift;

  ClosestFacet first = closest_facet(x0, candidates, {quads, 4}, coords);
  std::int32_t facet_old = first.facet;  // first contact: no tangential history
  Eigen::Vector2d xi_old = first.projection.xi;
  Eigen::Vector3d t_old = Eigen::Vector3d::Zero();
  double dissipation = 0, slip = 0;
  std::vector<int> visited;
  for (int k = 1; k <= steps; ++k) {
    const Eigen::Vector3d x = x0 + k * du * e;
    const ClosestFacet c = closest_facet(x, candidates, {quads, 4}, coords);
    if (visited.empty() || visited.back() != c.facet) visited.push_back(c.facet);
    const NodeCoordinates master = gather_facet(c.facet, {quads, 4}, coords);
    const SurfaceFriction f = surface_friction(single(x), one_node, master, c.projection,
                                               gather_facet(facet_old, {quads, 4}, coords), xi_old,
                                               t_old, w, eps_n, eps_t, mu);
    ASSERT_NEAR(f.pressure, p_n, 1e-9);
    if (eps_t * k * du < radius) {
      EXPECT_EQ(f.state, StickSlip::Stick) << "step " << k;
      EXPECT_NEAR(f.traction.norm(), eps_t * k * du, 1e-9);
    } else {
      EXPECT_EQ(f.state, StickSlip::Slip) << "step " << k;
      EXPECT_NEAR(f.traction.norm(), radius, 1e-12 * radius);
      EXPECT_NEAR(f.dissipation, radius * w * f.slip_increment.norm(), 1e-12);
    }
    EXPECT_GE(f.traction.dot(e), 0.0);  // −R on the slave opposes the motion
    dissipation += f.dissipation;
    slip += f.slip_increment.norm();
    facet_old = c.facet;
    xi_old = f.xi;
    t_old = f.traction;
  }
  EXPECT_EQ(visited, (std::vector<int>{0, 1, 2}));
  const double total_slip = steps * du - radius / eps_t;
  EXPECT_NEAR(slip, total_slip, 1e-9 * total_slip);
  EXPECT_NEAR(dissipation, radius * w * total_slip, 1e-9 * radius * w * total_slip);
}

TEST(SurfaceFriction, RejectsBadInput) {
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d x = point_at(flat_quad, {0.1, 0.2}, -0.02);
  const auto call = [&](double ww, double en, double et, double m) {
    return surface_friction(single(x), one_node, flat_quad, flat_quad, {0.1, 0.2},
                            Eigen::Vector3d::Zero(), ww, en, et, m);
  };
  EXPECT_THROW(call(-1e-3, eps_n, eps_t, mu), std::invalid_argument);
  EXPECT_THROW(call(inf, eps_n, eps_t, mu), std::invalid_argument);
  EXPECT_THROW(call(w, 0.0, eps_t, mu), std::invalid_argument);
  EXPECT_THROW(call(w, eps_n, 0.0, mu), std::invalid_argument);
  EXPECT_THROW(call(w, eps_n, eps_t, -0.1), std::invalid_argument);
  EXPECT_THROW(call(w, eps_n, eps_t, nan), std::invalid_argument);
  EXPECT_THROW(surface_friction(single(x), one_node, flat_quad, NodeCoordinates::Zero(3, 2), {0, 0},
                                Eigen::Vector3d::Zero(), w, eps_n, eps_t, mu),
               std::invalid_argument);
  EXPECT_THROW(surface_friction(single(x), one_node, flat_quad, flat_quad, {nan, 0},
                                Eigen::Vector3d::Zero(), w, eps_n, eps_t, mu),
               std::invalid_argument);
  EXPECT_THROW(surface_friction(single(x), one_node, flat_quad, flat_quad, {0, 0},
                                Eigen::Vector3d(0, inf, 0), w, eps_n, eps_t, mu),
               std::invalid_argument);
  EXPECT_THROW(surface_friction(single(x), Eigen::VectorXd::Ones(2), flat_quad, flat_quad, {0, 0},
                                Eigen::Vector3d::Zero(), w, eps_n, eps_t, mu),
               std::invalid_argument);
  NodeCoordinates collapsed = flat_quad;
  collapsed.col(1) = collapsed.col(0);
  EXPECT_THROW(surface_friction(single(x), one_node, collapsed, flat_quad, {0, 0},
                                Eigen::Vector3d::Zero(), w, eps_n, eps_t, mu),
               std::invalid_argument);
  EXPECT_NO_THROW(call(0.0, eps_n, eps_t, mu));
}

// --- Augmented Lagrangian: the cone radius is μ ⟨λ_N − ε_N g⟩ -----------------------------------

TEST(SurfaceFrictionAugmented, StickAndSlipOnTheFaceBelowAndAbove) {
  const Eigen::Vector2d xi(0.3, 0.2);
  const double lambda = 10.0;  // λ_N/ε_N = 0.04
  for (const NodeCoordinates& m : {warped_a, triangle}) {
    for (double gap : {-0.03, 0.0, 0.02}) {
      SCOPED_TRACE("gap = " + std::to_string(gap));
      Element e{single(point_at(m, xi, gap)), one_node, m, m, xi - Eigen::Vector2d(0.05, -0.03),
                Eigen::Vector3d::Zero()};
      e.lambda = lambda;
      const double p = lambda - eps_n * gap;
      const SurfaceFriction slip = expect_exact(e, StickSlip::Slip, Feature::Face);
      EXPECT_NEAR(slip.pressure, p, 1e-10 * p);
      EXPECT_NEAR(slip.traction.norm(), mu * p, 1e-10 * p);
      e.t_old = tuned_t_old(e, Eigen::Vector3d(0.3, -1, 0.5), 0.6 * mu * p);
      const SurfaceFriction stick = expect_exact(e, StickSlip::Stick, Feature::Face);
      EXPECT_NEAR(stick.traction.norm(), 0.6 * mu * p, 1e-10 * p);
    }
  }
}

TEST(SurfaceFrictionAugmented, BothSidesOfTheStickSlipTransitionAtAPositiveGap) {
  const Eigen::Vector2d xi(0.3, 0.2);
  const double gap = 0.01, lambda = 6.0, radius = mu * (lambda - eps_n * gap);
  Element e{single(point_at(warped_a, xi, gap)),
            one_node,
            warped_a,
            warped_a,
            xi - Eigen::Vector2d(0.003, -0.002),
            Eigen::Vector3d::Zero()};
  e.lambda = lambda;
  for (const auto& [factor, state] :
       {std::pair{1 - 1e-3, StickSlip::Stick}, std::pair{1 + 1e-3, StickSlip::Slip}}) {
    e.t_old = tuned_t_old(e, Eigen::Vector3d(0.3, -1, 0.5), factor * radius);
    const SurfaceFriction f = expect_exact(e, state, Feature::Face);
    EXPECT_NEAR(f.traction.norm(), std::min(factor, 1.0) * radius, 1e-10 * radius);
  }
}

TEST(SurfaceFrictionAugmented, EdgeAndVertex) {
  const Eigen::Vector2d xi_edge(1.0, -0.2);
  const Eigen::Vector3d out_e = edge_outward(warped_a, 1, xi_edge),
                        n_e = facet_normal(warped_a, xi_edge);
  const Eigen::Vector2d xi_v = facet_vertex_xi(4, 2);
  const Eigen::Vector3d out_v =
      (edge_outward(warped_a, 1, xi_v) + edge_outward(warped_a, 2, xi_v)).normalized();
  const Eigen::Vector3d n_v = facet_normal(warped_a, xi_v);
  const double lambda = 20.0;
  const Eigen::Vector3d edge_point = surface_point(warped_a, xi_edge);
  for (const auto& [x, feature] :
       {std::pair{(edge_point + 0.15 * out_e - 0.1 * n_e).eval(), Feature::Edge},
        std::pair{(edge_point + 0.03 * out_e + 0.05 * n_e).eval(), Feature::Edge},
        std::pair{(warped_a.col(2) + 0.1 * out_v - 0.12 * n_v).eval(), Feature::Vertex},
        std::pair{(warped_a.col(2) + 0.03 * out_v + 0.04 * n_v).eval(), Feature::Vertex}}) {
    Element e{single(x), one_node, warped_a, warped_a, {0.8, -0.1}, Eigen::Vector3d::Zero()};
    e.lambda = lambda;
    const SurfaceFriction slip = expect_exact(e, StickSlip::Slip, feature);
    EXPECT_NEAR(slip.pressure, lambda - eps_n * slip.gap, 1e-10 * lambda);
    e.t_old = tuned_t_old(e, Eigen::Vector3d(1, 0.2, -0.3), 0.5 * mu * slip.pressure);
    expect_exact(e, StickSlip::Stick, feature);
  }
}

TEST(SurfaceFrictionAugmented, OpenWhereTheAugmentedPressureVanishesZeroIsPenalty) {
  const Eigen::Vector2d xi(0.3, -0.2);
  Element e{single(point_at(warped_a, xi, 0.05)), one_node, warped_a, warped_a, xi,
            Eigen::Vector3d(0.5, 0.1, 0)};
  e.lambda = 10.0;  // λ_N − ε_N g = −2.5 < 0
  const SurfaceFriction open = e.evaluate();
  EXPECT_EQ(open.state, StickSlip::Open);
  EXPECT_TRUE(open.residual.isZero(0.0) && open.tangent.isZero(0.0));
  EXPECT_EQ(open.pressure, 0.0);
  // λ_N = 0 is the penalty call, bit for bit.
  Element pen{single(point_at(warped_a, xi, -0.03)),
              one_node,
              warped_a,
              warped_a,
              xi - Eigen::Vector2d(0.05, -0.03),
              Eigen::Vector3d::Zero()};
  const SurfaceFriction a = pen.evaluate();
  const SurfaceFriction b = surface_friction(pen.slave, one_node, warped_a, warped_a, pen.xi_old,
                                             pen.t_old, w, eps_n, eps_t, mu);
  EXPECT_EQ(a.residual, b.residual);
  EXPECT_EQ(a.tangent, b.tangent);
  EXPECT_EQ(a.traction, b.traction);
  EXPECT_THROW(surface_friction(pen.slave, one_node, warped_a, warped_a, pen.xi_old, pen.t_old, w,
                                eps_n, eps_t, mu, -1.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
