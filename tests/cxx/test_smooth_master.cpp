// Smooth master surface (smooth_master.hpp; evaluate_surface_contact with smooth_master = true):
// the assembled tangent against central differences of the assembled residual on curved,
// distorted quadrilateral and triangle masters of 4-, 3-, 9- and 6-node facets (face, both sides
// of an inner edge, an inner vertex, a Gauss point; open, penalty, augmented, smoothed;
// constrained and renumbered dofs); the faceted element on a flat master; the residual continuous
// across an edge where the faceted one jumps; force and moment balance; bad facets refused; the
// nodal normals against a sphere's and their jacobian against central differences; the
// projection far from the origin.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <hypercontact/facet_projection.hpp>
#include <hypercontact/smooth_master.hpp>
#include <hypercontact/surface_contact.hpp>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "smooth_master_scene.hpp"
#include "surface_scene.hpp"

namespace hypercontact {
namespace {

using test::above;
using test::cap;
using test::connectivity;
using test::dense_residual;
using test::dense_tangent;
using test::relative_error;
using test::SurfaceScene;

/// A slave point placed `gap` along the normal field over (facet, ξ): a node (w = 0.3) or the
/// Gauss point η = (0.3, −0.4) of a distorted slave quadrilateral (w = 0.07).
struct Target {
  std::int32_t facet;
  Eigen::Vector2d xi;
  double gap;
  bool gauss = false;
};

void add_targets(SurfaceScene& s, const std::vector<Target>& targets) {
  for (const Target& t : targets) {
    const Eigen::Vector3d p = above(s, t.facet, t.xi, t.gap);
    if (!t.gauss) {
      s.add_slave_node(p, 0.3);
      continue;
    }
    const Eigen::Vector4d M = facet_shape_functions<4>(Eigen::Vector2d(0.3, -0.4));
    const Eigen::Matrix<double, 3, 4> d = test::test_rotation *
        (Eigen::Matrix<double, 3, 4>() << -0.3, 0.28, 0.32, -0.25, -0.25, -0.3, 0.27, 0.3, 0.02,
         -0.01, 0.03, 0.0).finished();
    const Eigen::Vector3d shift = d * M;
    std::vector<std::int32_t> q;
    for (int i = 0; i < 4; ++i) q.push_back(s.add_node(p + d.col(i) - shift));
    s.add_point(q, {M[0], M[1], M[2], M[3]}, 0.07);
  }
}

SurfaceContactEvaluation evaluate(const SurfaceScene& s, std::span<const double> y,
                                  bool smooth = true) {
  SurfaceContactInput in = s.input(y);
  in.smooth_master = smooth;
  return evaluate_surface_contact(in);
}

/// Every target is paired by the smooth projection (feature 3) on its facet, at its ξ and gap.
void expect_targets(const SurfaceContactEvaluation& e, const std::vector<Target>& targets) {
  for (std::size_t p = 0; p < targets.size(); ++p) {
    SCOPED_TRACE("point " + std::to_string(p));
    EXPECT_EQ(e.feature[p], 3);
    EXPECT_EQ(e.facet[p], targets[p].facet);
    EXPECT_NEAR(e.xi[2 * p], targets[p].xi[0], 1e-9);
    EXPECT_NEAR(e.xi[2 * p + 1], targets[p].xi[1], 1e-9);
    EXPECT_NEAR(e.gap[p], targets[p].gap, 1e-10);
  }
}

double tangent_error(const SurfaceScene& s) {
  return test::dense_tangent_error([&s](std::span<const double> y) { return evaluate(s, y); }, s.x);
}

/// Targets on the 3 × 3 cap: face, both sides of an inner edge and near an inner vertex (1e-3 of
/// a facet from them), a Gauss point, the open point (+0.05), one in the smoothing band (−0.01)
/// and one open but active with λ_N/ε_N = 0.03 or δ = 0.02 (+0.01).
std::vector<Target> cap_targets(bool triangles) {
  if (!triangles)  // facet 4 the centre, 5 across its edge 1 (ξ1 = 1), its corner 2 inner
    return {{4, {0.3, -0.2}, -0.05},          {4, {1 - 2e-3, 0.1}, -0.04},
            {5, {-1 + 2e-3, 0.1}, -0.04},     {4, {1 - 2e-3, 1 - 2e-3}, -0.03},
            {3, {-0.4, 0.5}, -0.03, true},    {1, {0.2, 0.3}, 0.05},
            {6, {0.0, -0.5}, -0.01},          {7, {0.1, 0.1}, 0.01}};
  // triangles 8 = (a, b, c), 9 = (a, c, d) of the centre quad share the diagonal a–c (8's edge 2
  // ξ1 = 0, 9's edge 0 ξ2 = 0); c = 8's corner 2 is inner
  return {{8, {0.3, 0.25}, -0.05},       {8, {1e-3, 0.4}, -0.04},   {9, {0.4, 1e-3}, -0.04},
          {8, {1e-3, 1 - 2e-3}, -0.03},  {6, {0.2, 0.3}, -0.03, true}, {2, {0.2, 0.3}, 0.05},
          {12, {0.3, 0.3}, -0.01},       {14, {0.25, 0.25}, 0.01}};
}

/// Penalty, augmented (λ_N = 30, λ_N/ε_N = 0.03) and smoothed (δ = 0.02): the pairing, the active
/// points, and the tangent against central differences of the assembled residual.
void expect_tangents(bool triangles, int order = 1) {
  const std::vector<Target> targets = cap_targets(triangles);
  SurfaceScene base = cap(triangles, 3.0, 3, 1.0, true, order);
  const std::int32_t master_nodes = (3 * order + 1) * (3 * order + 1);
  add_targets(base, targets);
  for (int variant = 0; variant < 3; ++variant) {
    SCOPED_TRACE(std::string(triangles ? "triangles, " : "quads, ") + "order " +
                 std::to_string(order) + ", " +
                 (variant == 0   ? "penalty"
                  : variant == 1 ? "augmented"
                                 : "smoothed"));
    SurfaceScene s = base;
    if (variant == 1) s.multipliers.assign(targets.size(), 30.0);
    if (variant == 2) s.smoothing = 0.02;
    const SurfaceContactEvaluation e = evaluate(s, s.x);
    expect_targets(e, targets);
    // closed: the six points with g < 0, and +0.01 unless penalty; never the open +0.05 (point 5)
    std::vector<std::int32_t> active{0, 1, 2, 3, 4, 6};
    if (variant > 0) active.push_back(7);
    EXPECT_EQ(e.elements.point, active);
    EXPECT_EQ(e.num_closed, static_cast<std::int32_t>(active.size()));
    if (variant == 1) {
      EXPECT_NEAR(e.pressure[7], 30.0 - 1e3 * 0.01, 1e-8);
    }
    for (std::size_t k = 0; k < e.elements.size(); ++k)  // the stencil adds columns
      EXPECT_GT(e.elements.columns(k).size(), e.elements.rows(k).size());
    // the force on the slave body is −Σ R over the slave nodes (the master nodes first)
    const Eigen::VectorXd R = dense_residual(e.elements, static_cast<Eigen::Index>(s.x.size()));
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    for (std::int32_t a = master_nodes; a < s.num_nodes(); ++a) force -= R.segment<3>(3 * a);
    EXPECT_LE((e.force - force).norm(), 1e-12 * force.norm());
    EXPECT_LE(tangent_error(s), 1e-6);
  }
}

// Tangent = central differences of the assembled residual, curved distorted quadrilaterals.
TEST(SmoothMasterTangent, CurvedQuadrilateralsEveryFeatureAndLaw) { expect_tangents(false); }

// Tangent = central differences of the assembled residual, curved triangles.
TEST(SmoothMasterTangent, CurvedTrianglesEveryFeatureAndLaw) { expect_tangents(true); }

// The same on 9-node facets (nodal normals at corners, edge nodes and centres; curved edges).
TEST(SmoothMasterTangent, QuadraticQuadrilateralsEveryFeatureAndLaw) { expect_tangents(false, 2); }

// The same on 6-node facets.
TEST(SmoothMasterTangent, QuadraticTrianglesEveryFeatureAndLaw) { expect_tangents(true, 2); }

// Constrained (−1) and renumbered dofs: the assembly equals the full one without those rows/columns.
TEST(SmoothMasterTangent, ConstrainedDofsAreSkippedConsistently) {
  SurfaceScene s = cap(false, 3.0);
  add_targets(s, cap_targets(false));
  const auto n = static_cast<Eigen::Index>(s.x.size());
  const SurfaceContactEvaluation full = evaluate(s, s.x);
  const Eigen::VectorXd R = dense_residual(full.elements, n);
  const Eigen::MatrixXd K = dense_tangent(full.elements, n);
  // reversed numbering; node 5 (a corner of facet 4), z of node 10, node 14 (only in the stencil
  // of facet 4's normals) and x of the first slave node constrained
  std::vector<std::int32_t> dofs(s.dofs.size());
  for (std::size_t d = 0; d < dofs.size(); ++d) dofs[d] = static_cast<std::int32_t>(n - 1) - s.dofs[d];
  for (const int d : {15, 16, 17, 32, 42, 43, 44, 48}) dofs[d] = -1;
  SurfaceScene c = s;
  c.dofs = dofs;
  const SurfaceContactEvaluation constrained = evaluate(c, c.x);
  Eigen::VectorXd R_expected = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd K_expected = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (dofs[i] < 0) continue;
    R_expected[dofs[i]] = R[i];
    for (Eigen::Index j = 0; j < n; ++j)
      if (dofs[j] >= 0) K_expected(dofs[i], dofs[j]) = K(i, j);
  }
  EXPECT_LE((dense_residual(constrained.elements, n) - R_expected).cwiseAbs().maxCoeff(),
            1e-14 * R.cwiseAbs().maxCoeff());
  EXPECT_LE((dense_tangent(constrained.elements, n) - K_expected).cwiseAbs().maxCoeff(),
            1e-14 * K.cwiseAbs().maxCoeff());
  // the stencil-only node 14 is a column (constrained) of the element of point 0 on facet 4
  const auto columns = constrained.elements.columns(0);
  EXPECT_EQ(std::count(columns.begin(), columns.end(), -1), 3 + 3 + 1 + 1);  // 5, 14, z 10, x 16
  ASSERT_EQ(full.elements.point[0], 0);
  const auto full_columns = full.elements.columns(0);
  EXPECT_NE(std::find(full_columns.begin(), full_columns.end(), 42), full_columns.end());
}

// On a flat master the smooth element is the faceted one (residual, gap, normal, ξ).
TEST(SmoothMasterFlat, EqualsTheFacetedElementOnAFlatMaster) {
  for (const int order : {1, 2})
    for (const bool triangles : {false, true}) {
      SCOPED_TRACE(std::string(triangles ? "triangles" : "quads") + ", order " +
                   std::to_string(order));
      SurfaceScene s = cap(triangles, 0.0, 3, 1.0, true, order);
      const std::vector<Target> targets =
          triangles ? std::vector<Target>{{8, {0.3, 0.25}, -0.05}, {6, {0.2, 0.3}, -0.03, true}}
                    : std::vector<Target>{{4, {0.3, -0.2}, -0.05}, {3, {-0.4, 0.5}, -0.03, true}};
      add_targets(s, targets);
      const SurfaceContactEvaluation smooth = evaluate(s, s.x), faceted = evaluate(s, s.x, false);
      expect_targets(smooth, targets);
      ASSERT_EQ(smooth.elements.size(), 2u);
      ASSERT_EQ(faceted.elements.size(), 2u);
      for (std::size_t p = 0; p < 2; ++p) {
        EXPECT_EQ(faceted.feature[p], 0);
        EXPECT_EQ(smooth.facet[p], faceted.facet[p]);
        EXPECT_NEAR(smooth.gap[p], faceted.gap[p], 1e-12 * std::abs(faceted.gap[p]));
        EXPECT_NEAR(smooth.pressure[p], faceted.pressure[p], 1e-12 * faceted.pressure[p]);
        for (int k = 0; k < 2; ++k) EXPECT_NEAR(smooth.xi[2 * p + k], faceted.xi[2 * p + k], 1e-12);
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(smooth.normal[3 * p + k], faceted.normal[3 * p + k], 1e-12);
        const auto rows = smooth.elements.rows(p), faceted_rows = faceted.elements.rows(p);
        EXPECT_TRUE(std::equal(rows.begin(), rows.end(), faceted_rows.begin(), faceted_rows.end()));
        const auto r = smooth.elements.element_residual(p),
                   rf = faceted.elements.element_residual(p);
        ASSERT_EQ(r.size(), rf.size());
        EXPECT_LE(
            relative_error(Eigen::Map<const Eigen::VectorXd>(r.data(), Eigen::Index(r.size())),
                           Eigen::Map<const Eigen::VectorXd>(rf.data(), Eigen::Index(rf.size()))),
            1e-12);
      }
    }
}

// Across an inner edge the smooth residual changes by O(ε); the faceted one jumps by O(1).
TEST(SmoothMasterContinuity, ResidualIsContinuousAcrossAnEdgeWhereTheFacetedOneJumps) {
  for (const int order : {1, 2}) {
    SCOPED_TRACE("order " + std::to_string(order));
    SurfaceScene s = cap(false, 3.0, 3, 1.0, true, order);
    const Eigen::Vector2d xi_edge(1.0, 0.1);  // on edge 1 of facet 4, shared with facet 5
    const Eigen::Vector3d base = above(s, 4, xi_edge, -0.05);
    const Eigen::Vector3d n = (above(s, 4, xi_edge, 1.0) - above(s, 4, xi_edge, 0.0)).normalized();
    // the edge's corners: grid points (2, 1) and (2, 2)
    const std::size_t b = order == 1 ? 6 : 18, c = order == 1 ? 10 : 32;
    const Eigen::Vector3d along = Eigen::Vector3d(&s.x[3 * c]) - Eigen::Vector3d(&s.x[3 * b]);
    const Eigen::Vector3d across = along.cross(n).normalized();  // from facet 4 towards 5
    const std::int32_t node = s.add_slave_node(base, 0.3);
    const auto n_dofs = static_cast<Eigen::Index>(s.x.size());
    const auto at = [&](const Eigen::Vector3d& p, bool smooth) {
      std::vector<double> y = s.x;
      for (int k = 0; k < 3; ++k) y[3 * node + k] = p[k];
      return evaluate(s, y, smooth);
    };
    // where the faceted pairing switches from facet 4 to 5 along `across` (bisection)
    double lo = -0.2, hi = 0.2;
    ASSERT_EQ(at(base + lo * across, false).facet[0], 4);
    ASSERT_EQ(at(base + hi * across, false).facet[0], 5);
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (at(base + mid * across, false).facet[0] == 4 ? lo : hi) = mid;
    }
    const Eigen::Vector3d faceted_base = base + 0.5 * (lo + hi) * across;
    const double force = 0.3 * 1e3 * 0.05;  // w ε_N |g|, the slave force at the base
    // the angle between the two facets' normals at the edge point (ξ1 = 1 on 4, −1 on 5)
    const auto facet_nodes = [&](std::int32_t f) {
      NodeCoordinates X(3, s.nodes_per_facet);
      for (int a = 0; a < s.nodes_per_facet; ++a)
        X.col(a) = Eigen::Vector3d(&s.x[3 * static_cast<std::size_t>(connectivity(s).node(f, a))]);
      return X;
    };
    const double kink = std::acos(
        std::min(1.0, facet_normal(facet_nodes(4), xi_edge)
                          .dot(facet_normal(facet_nodes(5), Eigen::Vector2d(-1.0, 0.1)))));
    // linear facets on a sphere of radius 3 meet at about h/R; quadratic ones at far less
    EXPECT_GT(kink, order == 1 ? 0.2 : 1e-3);
    EXPECT_LT(kink, order == 1 ? 0.5 : 0.05);
    for (const double eps : {1e-4, 1e-6, 1e-8}) {
      SCOPED_TRACE("eps = " + std::to_string(eps));
      const SurfaceContactEvaluation minus = at(base - eps * across, true);
      const SurfaceContactEvaluation plus = at(base + eps * across, true);
      EXPECT_EQ(minus.facet[0], 4);
      EXPECT_EQ(plus.facet[0], 5);
      EXPECT_EQ(minus.feature[0], 3);
      EXPECT_EQ(plus.feature[0], 3);
      const Eigen::VectorXd Rm = dense_residual(minus.elements, n_dofs);
      const Eigen::VectorXd Rp = dense_residual(plus.elements, n_dofs);
      EXPECT_LE((Rp - Rm).cwiseAbs().maxCoeff(), 5 * eps * Rm.cwiseAbs().maxCoeff());  // ≈ 1.0
      const SurfaceContactEvaluation fm = at(faceted_base - eps * across, false);
      const SurfaceContactEvaluation fp = at(faceted_base + eps * across, false);
      EXPECT_EQ(fm.facet[0], 4);
      EXPECT_EQ(fp.facet[0], 5);
      const Eigen::VectorXd Fm = dense_residual(fm.elements, n_dofs);
      const Eigen::VectorXd Fp = dense_residual(fp.elements, n_dofs);
      // the slave node's force turns by the angle between the facets (linear: measured 0.39 ×
      // force; quadratic 0.012 ×), where the smooth one changes by O(ε)
      const double jump = (Fp.segment<3>(3 * node) - Fm.segment<3>(3 * node)).norm();
      EXPECT_GE(jump, 0.5 * kink * force);
      if (eps <= 1e-6) EXPECT_GE(jump, 100 * (Rp - Rm).cwiseAbs().maxCoeff());
    }
  }
}

// Far from the origin (|x| = 1e3 and 1e4 facet sizes) every target still gets the smooth element:
// the projection's stopping test must be relative to the coordinates' rounding, not to 1e-13 in ξ
// (with that, these points fell back to the faceted element: feature 0 or 1 instead of 3).
TEST(SmoothMasterProjection, ConvergesFarFromTheOrigin) {
  for (const bool triangles : {false, true})
    for (const double offset : {1e3, 1e4}) {
      SCOPED_TRACE(std::string(triangles ? "triangles" : "quads") + ", offset " +
                   std::to_string(offset));
      SurfaceScene s = cap(triangles, 3.0);
      std::vector<Target> targets = cap_targets(triangles);
      targets.resize(3);  // face and both sides of the edge
      add_targets(s, targets);
      for (std::size_t i = 0; i < s.x.size(); ++i) s.x[i] += i % 3 == 0 ? offset : 0.3 * offset;
      expect_targets(evaluate(s, s.x), targets);
    }
}

// Σ R_i = 0 and Σ x_i × R_i = 0 over the rows of every closed smooth element.
TEST(SmoothMasterBalance, ForceAndMomentOfEveryClosedElementVanish) {
  for (const int order : {1, 2})
    for (const bool triangles : {false, true}) {
      SCOPED_TRACE(std::string(triangles ? "triangles" : "quads") + ", order " +
                   std::to_string(order));
      SurfaceScene s = cap(triangles, 3.0, 3, 1.0, true, order);
      add_targets(s, cap_targets(triangles));
      s.multipliers.assign(s.point_area.size(), 30.0);
      const SurfaceContactEvaluation e = evaluate(s, s.x);
      ASSERT_EQ(e.elements.size(), 7u);
      for (std::size_t k = 0; k < e.elements.size(); ++k) {
        const auto rows = e.elements.rows(k);
        const auto r = e.elements.element_residual(k);
        Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
        double scale = 0, moment_scale = 0;
        for (std::size_t i = 0; i < rows.size() / 3; ++i) {
          const Eigen::Vector3d Ri(&r[3 * i]), xi(&s.x[static_cast<std::size_t>(rows[3 * i])]);
          force += Ri;
          moment += xi.cross(Ri);
          scale = std::max(scale, Ri.norm());
          moment_scale = std::max(moment_scale, xi.norm() * Ri.norm());
        }
        EXPECT_GT(scale, 0.0);
        EXPECT_LE(force.norm(), 1e-12 * scale) << "element " << k;
        EXPECT_LE(moment.norm(), 1e-12 * moment_scale) << "element " << k;
      }
    }
}

// Facets of another node count, or a node index out of range, throw invalid_argument naming
// what is wrong.
TEST(SmoothMasterInput, BadFacetsAreRefused) {
  const std::vector<std::int32_t> five{0, 1, 2, 3, 4};
  try {
    static_cast<void>(NodeFacets(FacetConnectivity{five, 5}, 5));
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("3, 4, 6 or 9 nodes"), std::string::npos)
        << error.what();
  }
  const std::vector<std::int32_t> nine{0, 1, 2, 3, 4, 5, 6, 7, 9};
  try {
    static_cast<void>(NodeFacets(FacetConnectivity{nine, 9}, 9));
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("out of range"), std::string::npos) << error.what();
  }
}

// The nodal normals of a distorted sphere-cap mesh converge to the sphere's normal.
TEST(SmoothMasterNodalNormal, ApproximatesTheSphereNormalWithRefinement) {
  for (const int order : {1, 2})
    for (const bool triangles : {false, true}) {
      std::vector<double> errors;
      for (const int n : {4, 8, 16}) {
        const double radius = 2.0;
        const SurfaceScene s = cap(triangles, radius, n, 2.0 / n, false, order);
        const NodeFacets at(connectivity(s), s.x.size() / 3);
        double error = 0;  // over the inner nodes (on the rim the normal is one-sided)
        for (int j = 1; j < order * n; ++j)
          for (int i = 1; i < order * n; ++i) {
            const std::int32_t a = j * (order * n + 1) + i;
            const Eigen::Vector3d x(&s.x[3 * static_cast<std::size_t>(a)]);
            const Eigen::Vector3d exact = (x - Eigen::Vector3d(0, 0, -radius)).normalized();
            error =
                std::max(error, (nodal_normal_value(a, at, connectivity(s), s.x) - exact).norm());
          }
        errors.push_back(error);
      }
      SCOPED_TRACE(std::string(triangles ? "triangles" : "quads") + ", order " +
                   std::to_string(order) + ": errors " + std::to_string(errors[0]) + ", " +
                   std::to_string(errors[1]) + ", " + std::to_string(errors[2]));
      // first order on a jittered mesh (second on a uniform one): about halved per halving of h
      EXPECT_LT(errors[0], 0.1);
      EXPECT_LT(errors[1], 0.75 * errors[0]);
      EXPECT_LT(errors[2], 0.75 * errors[1]);
      EXPECT_LT(errors[2], 0.4 * errors[0]);
    }
}

// nodal_normal's value and jacobian (over its stencil, zero elsewhere) = central differences.
TEST(SmoothMasterNodalNormal, JacobianIsTheDerivativeOfTheValue) {
  for (const int order : {1, 2})
    for (const bool triangles : {false, true}) {
      const SurfaceScene s = cap(triangles, 3.0, 3, 1.0, true, order);
      const NodeFacets at(connectivity(s), s.x.size() / 3);
      // order 1: inner, boundary, two corners of the 4 × 4 grid; order 2 (7 × 7 grid): an inner
      // corner, an inner edge node, a cell centre (the diagonal's middle on triangles), a boundary
      // edge node, two corners of the cap
      const std::vector<std::int32_t> nodes = order == 1
                                                  ? std::vector<std::int32_t>{5, 1, 0, 15}
                                                  : std::vector<std::int32_t>{16, 17, 24, 1, 0, 48};
      for (const std::int32_t node : nodes) {
        SCOPED_TRACE(std::string(triangles ? "triangles" : "quads") + ", order " +
                     std::to_string(order) + ", node " + std::to_string(node));
        const NodalNormal m = nodal_normal(node, at, connectivity(s), s.x);
        EXPECT_LE((m.m - nodal_normal_value(node, at, connectivity(s), s.x)).norm(), 1e-15);
        ASSERT_EQ(m.nodes.front(), node);
        ASSERT_EQ(m.jacobian.cols(), 3 * static_cast<Eigen::Index>(m.nodes.size()));
        Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, static_cast<Eigen::Index>(s.x.size()));
        for (std::size_t j = 0; j < m.nodes.size(); ++j)
          J.middleCols<3>(3 * m.nodes[j]) +=
              m.jacobian.middleCols<3>(3 * static_cast<Eigen::Index>(j));
        const Eigen::MatrixXd fd = test::fd_jacobian_stacked(
            [&](const Eigen::VectorXd& y) {
              const std::vector<double> v(y.data(), y.data() + y.size());
              return Eigen::VectorXd(nodal_normal_value(node, at, connectivity(s), v));
            },
            Eigen::Map<const Eigen::VectorXd>(s.x.data(), static_cast<Eigen::Index>(s.x.size())));
        EXPECT_LE(relative_error(fd, J), 1e-7);
      }
    }
}

}  // namespace
}  // namespace hypercontact
