// Coulomb friction against a smooth master (smooth_master.hpp with a SmoothFrictionHistory;
// evaluate_surface_friction with smooth_master = true): the assembled tangent against central
// differences of the assembled residual on curved, distorted quadrilateral and triangle caps of
// linear and quadratic facets
// (stick and slip, history on the same or a neighbouring facet, with t_old, none, open points;
// penalty, μ = 0, augmented, smoothed), the faceted element on a flat master, the Coulomb law
// and the return map's outputs, force balance, and the total and normal forces.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <hypercontact/smooth_master.hpp>
#include <hypercontact/surface_contact.hpp>
#include <hypercontact/surface_contact_friction.hpp>
#include <string>
#include <vector>

#include "smooth_master_scene.hpp"
#include "surface_scene.hpp"

namespace hypercontact {
namespace {

using test::above;
using test::cap;
using test::dense_residual;
using test::dense_tangent;
using test::relative_error;
using test::SurfaceScene;

constexpr double eps_t = 300.0;
constexpr int open = 0, stick = 1, slip = 2;
constexpr std::int32_t master_nodes = 16;  // the 3 × 3 cap's nodes come first

/// A slave node (w = 0.3) placed `gap` along the normal field over (facet, ξ), its history
/// (old_facet −1: none) with a t_old of length |t_old| tangential to the old facet's smooth
/// normal at ξ_old, and the state meant for it in the penalty variant with μ = 0.4.
struct Point {
  std::int32_t facet;
  Eigen::Vector2d xi;
  double gap;
  std::int32_t old_facet;
  Eigen::Vector2d xi_old;
  double t_old;
  int state;
};

/// The scene and every point's history.
struct FrictionScene {
  SurfaceScene contact;
  std::vector<std::int32_t> old_facet;
  std::vector<double> xi_old, t_old;
  double mu = 0.4;

  SurfaceFrictionInput input(std::span<const double> y, bool smooth = true) const {
    SurfaceFrictionInput in{contact.input(y), old_facet, xi_old, t_old, eps_t, mu};
    in.contact.smooth_master = smooth;
    return in;
  }
  SurfaceFrictionEvaluation evaluate(std::span<const double> y, bool smooth = true) const {
    return evaluate_surface_friction(input(y, smooth));
  }
};

/// Points on the 3 × 3 cap (quads: facet 4 the centre, 5 across its edge 1; triangles: 8 and 9
/// the centre cell, sharing its diagonal): stick and slip with the history on the same facet,
/// stick and slip with it on the neighbour across the edge (|t_old| = 2 and 8), no history, an
/// open point (+0.05) and one at +0.01 (open with the penalty, active augmented or smoothed).
std::vector<Point> points(bool triangles) {
  if (!triangles)
    return {{4, {0.3, -0.2}, -0.05, 4, {0.33, -0.18}, 3.0, stick},
            {4, {-0.3, 0.4}, -0.05, 4, {0.2, -0.3}, 5.0, slip},
            {4, {0.96, 0.1}, -0.04, 5, {-0.97, 0.12}, 2.0, stick},
            {5, {-0.5, -0.3}, -0.05, 4, {0.6, -0.2}, 8.0, slip},
            {3, {0.2, 0.3}, -0.03, -1, {0, 0}, 0.0, stick},
            {1, {0.2, 0.3}, 0.05, 1, {0.1, 0.3}, 1.0, open},
            {7, {0.1, 0.1}, 0.01, 7, {0.12, 0.1}, 0.0, open}};
  return {{8, {0.3, 0.25}, -0.05, 8, {0.33, 0.27}, 3.0, stick},
          {8, {0.6, 0.2}, -0.05, 8, {0.15, 0.1}, 5.0, slip},
          {8, {0.03, 0.5}, -0.04, 9, {0.5, 0.02}, 2.0, stick},
          {9, {0.3, 0.4}, -0.05, 8, {0.5, 0.2}, 8.0, slip},
          {6, {0.2, 0.3}, -0.03, -1, {0, 0}, 0.0, stick},
          {2, {0.2, 0.3}, 0.05, 2, {0.25, 0.3}, 1.0, open},
          {14, {0.25, 0.25}, 0.01, 14, {0.27, 0.25}, 0.0, open}};
}

FrictionScene scene(bool triangles, double radius, const std::vector<Point>& pts, int order = 1) {
  FrictionScene f{cap(triangles, radius, 3, 1.0, true, order), {}, {}, {}};
  SurfaceScene& s = f.contact;
  const SurfaceScene master = s;
  for (const Point& p : pts) {
    s.add_slave_node(above(master, p.facet, p.xi, p.gap), 0.3);
    f.old_facet.push_back(p.old_facet);
    f.xi_old.insert(f.xi_old.end(), {p.xi_old[0], p.xi_old[1]});
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    if (p.old_facet >= 0) {
      const Eigen::Vector3d n_old =
          above(master, p.old_facet, p.xi_old, 1.0) - above(master, p.old_facet, p.xi_old, 0.0);
      t = p.t_old * n_old.cross(Eigen::Vector3d(0.3, -0.5, 0.8)).normalized();
    }
    f.t_old.insert(f.t_old.end(), {t[0], t[1], t[2]});
  }
  return f;
}

/// The variants: 0 penalty, 1 μ = 0, 2 augmented (λ_N = 30), 3 smoothed (δ = 0.02).
const char* const variant_name[] = {"penalty", "mu = 0", "augmented", "smoothed"};

FrictionScene variant(bool triangles, int v, int order = 1) {
  const std::vector<Point> pts = points(triangles);
  FrictionScene f = scene(triangles, 3.0, pts, order);
  if (v == 1) f.mu = 0.0;
  if (v == 2) f.contact.multipliers.assign(pts.size(), 30.0);
  if (v == 3) f.contact.smoothing = 0.02;
  return f;
}

/// The intended states of `variant`: the +0.01 point has p_N = 20 augmented (stick) and 1.25
/// smoothed (slip: |t_trial| ≈ 3); with μ = 0 every closed point slips (t = 0), with or without
/// history (as return_map reports a frictionless point).
std::vector<std::int32_t> intended(bool triangles, int v) {
  std::vector<std::int32_t> out;
  const std::vector<Point> pts = points(triangles);
  for (std::size_t p = 0; p < pts.size(); ++p) {
    int s = pts[p].state;
    if (p == 6) s = v == 2 ? stick : v == 3 ? slip : open;
    if (v == 1 && s != open) s = slip;
    out.push_back(s);
  }
  return out;
}

/// The index of point p's element, elements.size() if it has none.
std::size_t element_of(const ContactElements& e, std::size_t p) {
  return static_cast<std::size_t>(
      std::find(e.point.begin(), e.point.end(), static_cast<std::int32_t>(p)) - e.point.begin());
}

/// Pairing, states, the point without history (its element = the frictionless smooth one: no
/// friction force, no friction tangent) and the assembled tangent against central differences.
void expect_tangents(bool triangles, int order = 1) {
  for (int v = 0; v < 4; ++v) {
    SCOPED_TRACE(std::string(triangles ? "triangles, " : "quads, ") + "order " +
                 std::to_string(order) + ", " + variant_name[v]);
    const FrictionScene f = variant(triangles, v, order);
    const std::vector<Point> pts = points(triangles);
    const SurfaceFrictionEvaluation e = f.evaluate(f.contact.x);
    for (std::size_t p = 0; p < pts.size(); ++p) {
      EXPECT_EQ(e.feature[p], 3) << "point " << p;
      EXPECT_EQ(e.facet[p], pts[p].facet) << "point " << p;
    }
    EXPECT_EQ(e.stick, intended(triangles, v));
    // no history (point 4): traction 0, and its element is that of the frictionless evaluation
    EXPECT_EQ(Eigen::Vector3d(&e.traction[12]).norm(), 0.0);
    const SurfaceContactEvaluation c = evaluate_surface_contact(f.input(f.contact.x).contact);
    const std::size_t k = element_of(e.elements, 4), kc = element_of(c.elements, 4);
    ASSERT_LT(k, e.elements.size());
    ASSERT_LT(kc, c.elements.size());
    const auto r = e.elements.element_residual(k), rc = c.elements.element_residual(kc);
    EXPECT_TRUE(std::equal(r.begin(), r.end(), rc.begin(), rc.end()));
    const auto K = e.elements.element_tangent(k), Kc = c.elements.element_tangent(kc);
    ASSERT_EQ(K.rows(), Kc.rows());
    ASSERT_EQ(K.cols(), Kc.cols());
    EXPECT_EQ((K - Kc).cwiseAbs().maxCoeff(), 0.0);
    // the tangent against central differences, the history held fixed
    const double error = test::dense_tangent_error(
        [&f](std::span<const double> y) { return f.evaluate(y); }, f.contact.x);
    char measured[32];
    std::snprintf(measured, sizeof measured, "%.2e", error);
    ::testing::Test::RecordProperty(
        std::string(triangles ? "fd_error_tri" : "fd_error_quad") +
            std::to_string(order == 1 ? (triangles ? 3 : 4) : (triangles ? 6 : 9)) + "_" +
            std::to_string(v),
        measured);
    EXPECT_LE(error, 1e-6);
  }
}

// Friction tangent = central differences of the assembled residual, curved distorted quads.
TEST(SmoothMasterFrictionTangent, CurvedQuadrilateralsStickSlipHistoryAndLaws) {
  expect_tangents(false);
}

// Friction tangent = central differences of the assembled residual, curved triangles.
TEST(SmoothMasterFrictionTangent, CurvedTrianglesStickSlipHistoryAndLaws) { expect_tangents(true); }

// The same on 9-node facets.
TEST(SmoothMasterFrictionTangent, QuadraticQuadrilateralsStickSlipHistoryAndLaws) {
  expect_tangents(false, 2);
}

// The same on 6-node facets.
TEST(SmoothMasterFrictionTangent, QuadraticTrianglesStickSlipHistoryAndLaws) {
  expect_tangents(true, 2);
}

/// The in-plane unit vectors of the placed flat cap.
Eigen::Matrix<double, 3, 2> in_plane() {
  return test::test_rotation.leftCols<2>();
}

// On a flat master smooth = faceted: residual, traction, Δs, D, state, and the tangent along every
// direction that keeps the master flat (slave dofs, master nodes in plane).
TEST(SmoothMasterFrictionFlat, EqualsTheFacetedFrictionOnAFlatMaster) {
  for (const bool triangles : {false, true})
    for (const int v : {0, 2}) {
      SCOPED_TRACE(std::string(triangles ? "triangles, " : "quads, ") + variant_name[v]);
      std::vector<Point> pts = points(triangles);
      pts.resize(5);  // stick and slip, same and other facet, no history
      FrictionScene f = scene(triangles, 0.0, pts);
      if (v == 2) f.contact.multipliers.assign(pts.size(), 30.0);
      const SurfaceFrictionEvaluation sm = f.evaluate(f.contact.x), fa = f.evaluate(f.contact.x, false);
      const auto n = static_cast<Eigen::Index>(f.contact.x.size());
      EXPECT_EQ(sm.stick, fa.stick);
      EXPECT_EQ(sm.stick, (std::vector<std::int32_t>{stick, slip, stick, slip, stick}));
      EXPECT_EQ(sm.facet, fa.facet);
      const auto close = [](const std::vector<double>& a, const std::vector<double>& b) {
        const Eigen::Map<const Eigen::VectorXd> x(a.data(), Eigen::Index(a.size())),
            y(b.data(), Eigen::Index(b.size()));
        return (x - y).cwiseAbs().maxCoeff() / y.cwiseAbs().maxCoeff();
      };
      EXPECT_LE(close(sm.traction, fa.traction), 1e-11);
      EXPECT_LE(close(sm.slip_increment, fa.slip_increment), 1e-11);
      EXPECT_LE(close(sm.dissipation, fa.dissipation), 1e-11);
      EXPECT_LE(close(sm.pressure, fa.pressure), 1e-11);
      EXPECT_LE((sm.total_force - fa.total_force).norm(), 1e-11 * fa.total_force.norm());
      const Eigen::VectorXd R = dense_residual(fa.elements, n);
      EXPECT_LE(relative_error(dense_residual(sm.elements, n), R), 1e-11);
      // directions along which the master stays flat: every slave dof, master nodes in plane (the
      // full tangents differ, by 4–12 % of max|K|: out of plane, the smooth normal moves with the
      // neighbours' nodal normals, the faceted one with its facet alone)
      Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, 2 * master_nodes + (n - 3 * master_nodes));
      for (Eigen::Index a = 0; a < master_nodes; ++a) D.block<3, 2>(3 * a, 2 * a) = in_plane();
      D.bottomRightCorner(n - 3 * master_nodes, n - 3 * master_nodes).setIdentity();
      const Eigen::MatrixXd KD = dense_tangent(fa.elements, n) * D;
      EXPECT_LE(relative_error(Eigen::MatrixXd(dense_tangent(sm.elements, n) * D), KD), 1e-11);
    }
}

// With μ = 0 a closed point without history reports the faceted path's state, Slip (2)
// (return_map: "μ = 0 is frictionless: Slip"), not Stick.
TEST(SmoothMasterFrictionFlat, NoHistoryAtZeroFrictionReportsTheFacetedState) {
  for (const bool triangles : {false, true}) {
    std::vector<Point> pts = points(triangles);
    pts.resize(5);  // point 4: no history
    FrictionScene f = scene(triangles, 0.0, pts);
    f.mu = 0.0;
    EXPECT_EQ(f.evaluate(f.contact.x).stick, f.evaluate(f.contact.x, false).stick);
  }
}

// Coulomb: slip |t| = μ p_N ⟂ n along t_trial; stick t = (I − n n)(t_old + ε_T (x_s − x_old));
// Δs = (t_trial − t)/ε_T; D = w t·Δs ≥ 0; open points and no history: t = 0.
TEST(SmoothMasterFrictionCoulomb, ReturnMapOnTheSmoothNormal) {
  for (const bool triangles : {false, true})
    for (int v = 0; v < 4; ++v) {
      SCOPED_TRACE(std::string(triangles ? "triangles, " : "quads, ") + variant_name[v]);
      const FrictionScene f = variant(triangles, v);
      const SurfaceScene& s = f.contact;
      const SurfaceFrictionEvaluation e = f.evaluate(s.x);
      int slipping = 0, sticking = 0;
      for (std::size_t p = 0; p < s.point_area.size(); ++p) {
        SCOPED_TRACE("point " + std::to_string(p));
        const Eigen::Vector3d t(&e.traction[3 * p]), ds(&e.slip_increment[3 * p]);
        const Eigen::Vector3d n(&e.normal[3 * p]);
        const double w = s.point_area[p], pn = e.pressure[p];
        if (e.stick[p] == open || f.old_facet[p] < 0) {
          EXPECT_EQ(t.norm(), 0.0);
          EXPECT_EQ(e.dissipation[p], 0.0);
          continue;
        }
        const Eigen::Vector3d x_s(&s.x[3 * static_cast<std::size_t>(s.point_nodes[4 * p])]);
        const Eigen::VectorXd N = facet_shape_functions(s.nodes_per_facet, Eigen::Vector2d(&f.xi_old[2 * p]));
        Eigen::Vector3d x_old = Eigen::Vector3d::Zero();
        for (int b = 0; b < s.nodes_per_facet; ++b)
          x_old += N[b] * Eigen::Vector3d(&s.x[3 * static_cast<std::size_t>(
                                                      s.facets[s.nodes_per_facet * f.old_facet[p] + b])]);
        const Eigen::Matrix3d PT = Eigen::Matrix3d::Identity() - n * n.transpose();
        const Eigen::Vector3d trial = PT * (Eigen::Vector3d(&f.t_old[3 * p]) + eps_t * (x_s - x_old));
        if (e.stick[p] == stick) {
          ++sticking;
          EXPECT_LE(trial.norm(), f.mu * pn);
          EXPECT_LE((t - trial).norm(), 1e-12 * trial.norm());
          EXPECT_LE(ds.norm(), 1e-12 * trial.norm() / eps_t);
        } else {
          ++slipping;
          EXPECT_GT(trial.norm(), f.mu * pn);
          EXPECT_NEAR(t.norm(), f.mu * pn, 1e-12 * pn);
          EXPECT_LE(std::abs(t.dot(n)), 1e-12 * pn);
          EXPECT_LE((t - f.mu * pn * trial.normalized()).norm(), 1e-12 * pn);
          EXPECT_LE((ds - (trial - t) / eps_t).norm(), 1e-12 * trial.norm() / eps_t);
        }
        EXPECT_NEAR(e.dissipation[p], w * t.dot(ds), 1e-12 * w * trial.norm() * trial.norm() / eps_t);
        EXPECT_GE(e.dissipation[p], 0.0);
      }
      EXPECT_GE(sticking, v == 1 ? 0 : 2);
      EXPECT_GE(slipping, 2);
    }
}

// Σ over the rows of every element's residual 3-vectors = 0 (forces balance), stick and slip.
TEST(SmoothMasterFrictionBalance, ForcesOfEveryElementVanish) {
  for (const bool triangles : {false, true})
    for (int v = 0; v < 4; ++v) {
      SCOPED_TRACE(std::string(triangles ? "triangles, " : "quads, ") + variant_name[v]);
      const FrictionScene f = variant(triangles, v);
      const SurfaceFrictionEvaluation e = f.evaluate(f.contact.x);
      ASSERT_EQ(e.elements.size(), v == 0 || v == 1 ? 5u : 6u);
      for (std::size_t k = 0; k < e.elements.size(); ++k) {
        const auto r = e.elements.element_residual(k);
        const auto p = static_cast<std::size_t>(e.elements.point[k]);
        Eigen::Vector3d force = Eigen::Vector3d::Zero(), slave(&r[0]);
        double scale = 0;
        for (std::size_t i = 0; i < r.size() / 3; ++i) {
          force += Eigen::Vector3d(&r[3 * i]);
          scale = std::max(scale, Eigen::Vector3d(&r[3 * i]).norm());
        }
        // the slave row carries the friction: −w p_N n + w t
        const Eigen::Vector3d expected = f.contact.point_area[p] *
            (Eigen::Vector3d(&e.traction[3 * p]) - e.pressure[p] * Eigen::Vector3d(&e.normal[3 * p]));
        EXPECT_LE((slave - expected).norm(), 1e-12 * scale) << "point " << p;
        EXPECT_GT(scale, 0.0);
        EXPECT_LE(force.norm(), 1e-12 * scale) << "point " << p << ", state " << e.stick[p];
      }
    }
}

// total_force = −Σ R over the slave nodes; force (normal part) = Σ w p_N n over closed points.
TEST(SmoothMasterFrictionForces, TotalAndNormalForce) {
  for (const bool triangles : {false, true})
    for (int v = 0; v < 4; ++v) {
      SCOPED_TRACE(std::string(triangles ? "triangles, " : "quads, ") + variant_name[v]);
      const FrictionScene f = variant(triangles, v);
      const SurfaceScene& s = f.contact;
      const SurfaceFrictionEvaluation e = f.evaluate(s.x);
      const Eigen::VectorXd R = dense_residual(e.elements, static_cast<Eigen::Index>(s.x.size()));
      Eigen::Vector3d total = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero(),
                      friction = Eigen::Vector3d::Zero();
      for (std::int32_t a = master_nodes; a < s.num_nodes(); ++a) total -= R.segment<3>(3 * a);
      for (std::size_t p = 0; p < s.point_area.size(); ++p) {
        if (e.stick[p] == open) continue;
        normal += s.point_area[p] * e.pressure[p] * Eigen::Vector3d(&e.normal[3 * p]);
        friction += s.point_area[p] * Eigen::Vector3d(&e.traction[3 * p]);
      }
      EXPECT_LE((e.total_force - total).norm(), 1e-12 * total.norm());
      EXPECT_LE((e.force - normal).norm(), 1e-12 * normal.norm());
      EXPECT_LE((e.total_force - (normal - friction)).norm(), 1e-12 * total.norm());
      if (v != 1) EXPECT_GT(friction.norm(), 1e-3 * normal.norm());  // friction present
    }
}

}  // namespace
}  // namespace hypercontact
