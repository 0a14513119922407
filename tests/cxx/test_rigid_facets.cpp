// Facet integration against rigid obstacles (points_per_facet = Q > 0): each slave facet carries
// one pressure, that of the mean gap of its Q Gauss points. Checked: one point per facet is the
// Gauss-point evaluation itself; a facet parallel to a plane carries p = ε_N ⟨−g⟩ over its area,
// spread as the consistent loads Σ_q w_q M_qa; the mean gap, not a point's, opens and closes a
// facet; the tangent is the derivative of the residual (central differences) in every branch
// (face, edge and vertex of a box, a cylinder, a sphere, multipliers, smoothing); bad input is
// refused with the reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <hypercontact/rigid_contact.hpp>
#include <hypercontact/rigid_contact_friction.hpp>
#include <stdexcept>
#include <vector>

#include "contact_elements_fd.hpp"

namespace hypercontact {
namespace {

/// Slave facets of k nodes each (their own nodes, placed around the facet's centre), each with Q
/// Gauss points x_q = Σ_a M_qa y_a of weight w_q.
struct FacetScene {
  Obstacle obstacle;
  std::vector<double> centres;  // nf × 3
  int k, Q;
  std::vector<double> multipliers = {};
  double smoothing = 0.0;
  double eps_n = 60.0;
  std::vector<double> M, w, y;  // weights (nf Q × k), Gauss weights (nf Q), nodes (nf k × 3)
  std::vector<std::int32_t> dofs;

  FacetScene(Obstacle o, std::vector<double> c, int k_, int Q_, double size = 0.1)
      : obstacle(std::move(o)), centres(std::move(c)), k(k_), Q(Q_) {
    const std::size_t nf = centres.size() / 3;
    for (std::size_t f = 0; f < nf; ++f) {
      for (int a = 0; a < k; ++a) {
        const Eigen::Vector3d d =
            size * Eigen::Vector3d(std::cos(2.1 * a + f), std::sin(1.3 * a + 2.0 * f),
                                   0.3 * std::cos(3.0 * a + f));
        for (int j = 0; j < 3; ++j) y.push_back(centres[3 * f + j] + d[j]);
      }
      for (int q = 0; q < Q; ++q) {
        double sum = 0;
        std::vector<double> m(k);
        for (int a = 0; a < k; ++a) sum += m[a] = 0.2 + 0.31 * ((a * 5 + q * 3 + f) % 4);
        for (double& v : m) M.push_back(v / sum);
        w.push_back(0.1 + 0.05 * ((q + f) % 3));
      }
    }
    dofs = test::identity_dofs(y.size());
  }
  std::size_t num_facets() const { return centres.size() / 3; }
  std::vector<double> points(std::span<const double> yy) const {
    std::vector<double> x(3 * Q * num_facets(), 0.0);
    for (std::size_t f = 0; f < num_facets(); ++f)
      for (int q = 0; q < Q; ++q)
        for (int a = 0; a < k; ++a)
          for (int j = 0; j < 3; ++j)
            x[3 * (f * Q + q) + j] += M[k * (f * Q + q) + a] * yy[3 * (k * f + a) + j];
    return x;
  }
  RigidContactInput input(const std::vector<double>& x) const {
    return {obstacle, x, w, dofs, eps_n, multipliers, smoothing, M, Q};
  }
  RigidContactEvaluation evaluate(std::span<const double> yy) const {
    const std::vector<double> x = points(yy);
    return evaluate_rigid_contact(input(x));
  }
  double tangent_error() const {
    return test::dense_tangent_error([this](std::span<const double> yy) { return evaluate(yy); },
                                     y);
  }
};

const Obstacle unit_box = RigidBox{{-1, -1, -1}, {1, 1, 1}};

TEST(RigidFacets, OnePointPerFacetIsTheGaussPointEvaluation) {
  FacetScene facets(unit_box, {0.2, 0.1, 0.97, 1.02, 0.3, 1.01, 1.01, 1.02, 1.01, 0.2, 0.1, 1.5}, 6,
                    1);
  facets.multipliers = {2.0, 2.0, 2.0, 0.0};
  const std::vector<double> x = facets.points(facets.y);
  const RigidContactEvaluation e = facets.evaluate(facets.y);
  const RigidContactEvaluation points = evaluate_rigid_contact(
      {unit_box, x, facets.w, facets.dofs, facets.eps_n, facets.multipliers, 0.0, facets.M});
  ASSERT_EQ(e.elements.size(), points.elements.size());
  ASSERT_GE(e.elements.size(), 3u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(e.gap[i], points.gap[i], 1e-15);
    EXPECT_NEAR(e.pressure[i], points.pressure[i], 1e-12 * (1 + points.pressure[i]));
  }
  EXPECT_LE((e.force - points.force).norm(), 1e-13 * points.force.norm());
  for (std::size_t el = 0; el < e.elements.size(); ++el) {
    EXPECT_EQ(e.elements.point[el], points.elements.point[el]);
    EXPECT_LE(
        test::relative_error(e.elements.element_tangent(el), points.elements.element_tangent(el)),
        1e-12);
    const auto r = e.elements.element_residual(el), rp = points.elements.element_residual(el);
    for (std::size_t j = 0; j < r.size(); ++j)
      EXPECT_NEAR(r[j], rp[j], 1e-12 * (1 + std::abs(rp[j])));
  }
}

TEST(RigidFacets, AFlatFacetOnAPlaneCarriesItsConsistentLoads) {
  // All nodes 0.01 below the plane z = 0: every Gauss point has g = −0.01.
  FacetScene s(RigidPlane{{0, 0, 0}, {0, 0, 1}}, {0.0, 0.0, 0.0}, 6, 6);
  for (std::size_t i = 2; i < s.y.size(); i += 3) s.y[i] = -0.01;
  const RigidContactEvaluation e = s.evaluate(s.y);
  ASSERT_EQ(e.elements.size(), 1u);
  double area = 0;
  for (double wq : s.w) area += wq;
  const double p = s.eps_n * 0.01;
  EXPECT_NEAR(e.gap[0], -0.01, 1e-15);
  EXPECT_NEAR(e.pressure[0], p, 1e-12);
  EXPECT_NEAR(e.force[2], p * area, 1e-12);
  const auto r = e.elements.element_residual(0);
  for (int a = 0; a < s.k; ++a) {
    double load = 0;  // Σ_q w_q M_qa: node a's share of a uniform pressure
    for (int q = 0; q < s.Q; ++q) load += s.w[q] * s.M[s.k * q + a];
    EXPECT_NEAR(r[3 * a + 2], -p * load, 1e-13);
    EXPECT_NEAR(r[3 * a], 0.0, 1e-15);
  }
}

TEST(RigidFacets, TheMeanGapOpensAndClosesAFacet) {
  // A flat facet tilted across the plane z = 0: half of its Gauss points penetrate.
  FacetScene s(RigidPlane{{0, 0, 0}, {0, 0, 1}}, {0.0, 0.0, 0.0}, 3, 3);
  auto tilt = [&](double offset) {
    std::vector<double> yy = s.y;
    for (int a = 0; a < s.k; ++a) yy[3 * a + 2] = offset + 0.5 * yy[3 * a];
    return yy;
  };
  for (const double offset : {0.004, -0.004}) {
    const std::vector<double> yy = tilt(offset);
    const std::vector<double> x = s.points(yy);
    double mean = 0, area = 0;
    int penetrating = 0;
    for (int q = 0; q < s.Q; ++q) {
      mean += s.w[q] * x[3 * q + 2];
      area += s.w[q];
      penetrating += x[3 * q + 2] < 0;
    }
    mean /= area;
    ASSERT_GT(penetrating, 0);
    ASSERT_LT(penetrating, s.Q);
    const RigidContactEvaluation e = s.evaluate(yy);
    EXPECT_NEAR(e.gap[0], mean, 1e-15);
    EXPECT_EQ(e.elements.size(), mean < 0 ? 1u : 0u);
    EXPECT_NEAR(e.pressure[0], s.eps_n * std::max(-mean, 0.0), 1e-13);
  }
}

TEST(RigidFacets, TangentIsTheDerivativeOfTheResidualInEveryBranch) {
  for (const auto [k, Q] : {std::pair{3, 3}, std::pair{6, 6}, std::pair{9, 9}, std::pair{4, 4}}) {
    // Facets under the box's top face, by an edge and by a vertex (closed by λ/ε_N = 0.033), and
    // far above (open); then the first three pressed in without multipliers.
    FacetScene box(unit_box, {0.2, 0.1, 0.97, 1.02, 0.3, 1.01, 1.01, 1.02, 1.01, 0.2, 0.1, 1.5}, k,
                   Q, 0.02);
    box.multipliers = {2.0, 2.0, 2.0, 0.0};
    ASSERT_EQ(box.evaluate(box.y).elements.size(), 3u) << "k = " << k;
    std::vector<Feature> features;
    for (int q = 0; q < Q; ++q) {  // the points of the edge facet: on its edge
      const std::vector<double> x = box.points(box.y);
      features.push_back(project(unit_box, Eigen::Vector3d(&x[3 * (Q + q)])).feature);
    }
    EXPECT_EQ(std::count(features.begin(), features.end(), Feature::Edge), Q) << "k = " << k;
    EXPECT_LE(box.tangent_error(), 1e-6) << "box with multipliers, k = " << k;
    FacetScene pressed = box;
    pressed.multipliers.clear();
    for (std::size_t i = k; i < 3 * static_cast<std::size_t>(k); ++i)  // the edge and vertex facets
      for (int j = 0; j < 3; ++j) pressed.y[3 * i + j] -= 0.05;
    ASSERT_EQ(pressed.evaluate(pressed.y).elements.size(), 3u) << "k = " << k;
    EXPECT_LE(pressed.tangent_error(), 1e-6) << "box, penalty, k = " << k;
    box.smoothing = 0.05;
    EXPECT_LE(box.tangent_error(), 1e-6) << "smoothed box, k = " << k;
    const FacetScene cylinder(
        RigidCylinder{{0, 0, 1}, Eigen::Vector3d(1, 0.3, 0).normalized(), 1.0},
        {0.1, 0.05, 0.03, -0.2, 0.4, 0.15, 0.3, -0.6, 0.3}, k, Q);
    ASSERT_EQ(cylinder.evaluate(cylinder.y).elements.size(), 3u);
    EXPECT_LE(cylinder.tangent_error(), 1e-6) << "cylinder, k = " << k;
    const FacetScene sphere(RigidSphere{{0, 0, 2}, 1.0}, {0.1, 0.2, 1.05, 0.5, 0.0, 1.3, 0, 0, 0.5},
                            k, Q);
    ASSERT_EQ(sphere.evaluate(sphere.y).elements.size(), 2u);  // the third facet is open
    EXPECT_LE(sphere.tangent_error(), 1e-6) << "sphere, k = " << k;
    const FacetScene rounded(RigidBox{{-1, -1, -1}, {1, 1, 1}, 0.4, true},
                             {0.8, 0.1, 0.85, 0.8, 0.8, 0.85}, k, Q, 0.03);
    ASSERT_EQ(rounded.evaluate(rounded.y).elements.size(), 2u);
    EXPECT_LE(rounded.tangent_error(), 1e-6) << "blended box, k = " << k;
  }
}

TEST(RigidFacets, AProcessWithoutFacetsEvaluatesNothing) {
  const std::vector<double> none;
  const std::vector<std::int32_t> no_dofs;
  const RigidContactEvaluation e =
      evaluate_rigid_contact({unit_box, none, none, no_dofs, 60.0, {}, 0.0, none, 6});
  EXPECT_TRUE(e.gap.empty());
  EXPECT_EQ(e.elements.size(), 0u);
  EXPECT_EQ(e.num_closed, 0);
  // a bad parameter is refused there too, as on the processes that have facets
  EXPECT_THROW(evaluate_rigid_contact({unit_box, none, none, no_dofs, 0.0, {}, 0.0, none, 6}),
               std::invalid_argument);
}

TEST(RigidFacets, RejectsInputThatIsNotWholeFacets) {
  const FacetScene s(unit_box, {0.2, 0.1, 0.97, 1.0, 0.3, 0.99}, 6, 6);
  const std::vector<double> x = s.points(s.y);
  RigidContactInput in = s.input(x);
  in.points_per_facet = 5;  // 12 points are not whole facets of 5
  EXPECT_THROW(evaluate_rigid_contact(in), std::invalid_argument);
  in = s.input(x);
  const std::vector<double> one = {1.0};
  in.multipliers = one;  // one per facet: 2
  EXPECT_THROW(evaluate_rigid_contact(in), std::invalid_argument);
  in = s.input(x);
  std::vector<std::int32_t> dofs = s.dofs;
  dofs.resize(dofs.size() - 3);
  in.dofs = dofs;
  EXPECT_THROW(evaluate_rigid_contact(in), std::invalid_argument);
  in = s.input(x);
  const std::vector<double> zero(s.w.size(), 0.0);
  in.area = zero;
  try {
    evaluate_rigid_contact(in);
    ADD_FAILURE() << "a facet of zero area was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("slave facet 0 has area"), std::string::npos);
  }
  in = s.input(x);
  in.points_per_facet = -1;
  EXPECT_THROW(evaluate_rigid_contact(in), std::invalid_argument);
  // friction needs a slip per point: facet integration is refused there
  const std::vector<double> zeros(x.size(), 0.0);
  EXPECT_THROW(evaluate_rigid_friction({s.input(x), zeros, zeros, 100.0, 0.3, true}),
               std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
