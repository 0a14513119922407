// Slave points that are combinations x_p = Σ_a M_a x_a of k nodes (the Gauss points of 6-node
// triangles and 9-node quadrilaterals) against rigid obstacles: each element is its point's
// nodal element spread over the k nodes (R_a = M_a r, K_ab = M_a M_b K), and its tangent is the
// derivative of its residual with respect to the node coordinates (central differences) in every
// branch: open and closed, face, edge and vertex of a box, a cylinder and a sphere, with
// multipliers and smoothing, and with friction in stick and slip.
#include <gtest/gtest.h>

#include <hypercontact/rigid_contact.hpp>
#include <hypercontact/rigid_contact_friction.hpp>
#include <set>
#include <stdexcept>
#include <vector>

#include "contact_elements_fd.hpp"

namespace hypercontact {
namespace {

/// Weights of k nodes summing to 1, some negative (as corner weights of a 9-node facet are at
/// its interior Gauss points).
std::vector<double> weights(int k, int seed) {
  std::vector<double> M(k);
  double sum = 0;
  for (int a = 0; a < k; ++a) sum += M[a] = 0.1 + 0.37 * ((a * 7 + seed * 3) % 5) - (a == 1 ? 0.3 : 0);
  for (double& m : M) m /= sum;
  return M;
}

/// Points at `points` (np × 3), each the combination of its own k nodes placed around it.
struct GaussScene {
  Obstacle obstacle;
  std::vector<double> points, area;
  int k;
  std::vector<double> multipliers = {};
  double smoothing = 0.0;
  std::vector<double> M, y;  // weights (np × k), node coordinates (np k × 3)
  std::vector<std::int32_t> dofs;

  GaussScene(Obstacle o, std::vector<double> p, std::vector<double> a, int k_)
      : obstacle(std::move(o)), points(std::move(p)), area(std::move(a)), k(k_) {
    const std::size_t np = area.size();
    for (std::size_t i = 0; i < np; ++i) {
      const std::vector<double> w = weights(k, static_cast<int>(i));
      M.insert(M.end(), w.begin(), w.end());
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      std::vector<Eigen::Vector3d> d(k);
      for (int a = 0; a < k; ++a) {
        d[a] = 0.05 * Eigen::Vector3d(std::cos(a + i), std::sin(2.0 * a + i), std::cos(3.0 * a));
        mean += w[a] * d[a];
      }
      for (int a = 0; a < k; ++a)
        for (int j = 0; j < 3; ++j) y.push_back(points[3 * i + j] + d[a][j] - mean[j]);
    }
    dofs = test::identity_dofs(y.size());
  }
  /// The points' coordinates at node coordinates yy.
  std::vector<double> at(std::span<const double> yy) const {
    std::vector<double> x(points.size(), 0.0);
    for (std::size_t i = 0; i < area.size(); ++i)
      for (int a = 0; a < k; ++a)
        for (int j = 0; j < 3; ++j) x[3 * i + j] += M[k * i + a] * yy[3 * (k * i + a) + j];
    return x;
  }
  RigidContactEvaluation evaluate(std::span<const double> yy) const {
    const std::vector<double> x = at(yy);
    return evaluate_rigid_contact({obstacle, x, area, dofs, 60.0, multipliers, smoothing, M});
  }
  double tangent_error() const {
    return test::dense_tangent_error([this](std::span<const double> yy) { return evaluate(yy); }, y);
  }
};

const Obstacle unit_box = RigidBox{{-1, -1, -1}, {1, 1, 1}};

/// Inside under the box's top face, outside by an edge and by a vertex within λ/ε_N, far above.
GaussScene box_scene(int k) {
  GaussScene s(unit_box, {0.2, 0.1, 0.97, 1.02, 0.3, 1.01, 1.01, 1.02, 1.01, 0.2, 0.1, 1.5},
               {0.3, 0.2, 0.4, 0.5}, k);
  s.multipliers = {2.0, 2.0, 2.0, 0.0};
  return s;
}

TEST(RigidGaussPoints, ElementIsThePointsElementSpreadOverItsNodes) {
  for (const int k : {6, 9}) {
    const GaussScene scene = box_scene(k);
    const RigidContactEvaluation e = scene.evaluate(scene.y);
    const std::vector<double> x = scene.at(scene.y);
    const RigidContactEvaluation nodal = evaluate_rigid_contact(
        {unit_box, x, scene.area, test::identity_dofs(x.size()), 60.0, scene.multipliers});
    ASSERT_EQ(e.elements.size(), 3u);
    ASSERT_EQ(nodal.elements.size(), 3u);
    EXPECT_EQ(e.gap, nodal.gap);
    EXPECT_EQ(e.pressure, nodal.pressure);
    EXPECT_LE((e.force - nodal.force).norm(), 1e-14 * nodal.force.norm());
    for (std::size_t el = 0; el < e.elements.size(); ++el) {
      const std::int32_t i = e.elements.point[el];
      const auto rows = e.elements.rows(el);
      ASSERT_EQ(rows.size(), static_cast<std::size_t>(3 * k));
      const auto rs = nodal.elements.element_residual(el);
      const Eigen::Vector3d r(rs[0], rs[1], rs[2]);
      const auto K = nodal.elements.element_tangent(el);
      const auto Ke = e.elements.element_tangent(el);
      for (int a = 0; a < k; ++a) {
        const double Ma = scene.M[k * i + a];
        for (int j = 0; j < 3; ++j) {
          EXPECT_EQ(rows[3 * a + j], 3 * (k * i + a) + j);
          EXPECT_NEAR(e.elements.element_residual(el)[3 * a + j], Ma * r[j], 1e-14 * r.norm());
        }
        for (int b = 0; b < k; ++b)
          EXPECT_LE((Ke.block<3, 3>(3 * a, 3 * b) - Ma * scene.M[k * i + b] * K).norm(),
                    1e-14 * K.norm());
      }
    }
  }
}

TEST(RigidGaussPoints, TangentIsTheDerivativeOfTheResidualInEveryBranch) {
  for (const int k : {3, 6, 9}) {
    GaussScene box = box_scene(k);
    EXPECT_LE(box.tangent_error(), 1e-6) << "box, k = " << k;
    box.smoothing = 0.05;
    EXPECT_LE(box.tangent_error(), 1e-6) << "smoothed box, k = " << k;
    const GaussScene cylinder(RigidCylinder{{0, 0, 1}, Eigen::Vector3d(1, 0.3, 0).normalized(), 1.0},
                              {0.1, 0.05, 0.03, -0.2, 0.4, 0.15, 0.3, -0.6, 0.3}, {0.5, 0.25, 0.75},
                              k);
    ASSERT_EQ(cylinder.evaluate(cylinder.y).elements.size(), 3u);
    EXPECT_LE(cylinder.tangent_error(), 1e-6) << "cylinder, k = " << k;
    const GaussScene sphere(RigidSphere{{0, 0, 2}, 1.0}, {0.1, 0.2, 1.05, 0.5, 0.0, 1.3, 0, 0, 0.5},
                            {0.5, 0.25, 0.75}, k);
    ASSERT_EQ(sphere.evaluate(sphere.y).elements.size(), 2u);  // the third point is open
    EXPECT_LE(sphere.tangent_error(), 1e-6) << "sphere, k = " << k;
  }
}

TEST(RigidGaussPoints, FrictionTangentInStickAndSlip) {
  constexpr double eps_t = 300.0, mu = 0.4;
  for (const int k : {6, 9}) {
    const GaussScene scene(RigidPlane{{0, 0, 0.1}, Eigen::Vector3d(0.3, -0.2, 1).normalized()},
                           {0.0, 0.0, 0.5, 0.1, 0.2, -0.05, -0.3, 0.1, 0.02, 0.4, -0.2, -0.1},
                           {0.75, 0.5, 0.25, 0.4}, k);
    const std::vector<double> xi_old = {0.0, 0.0, 0.5, 0.1001, 0.2, -0.05,
                                        -0.1, 0.1, 0.02, 0.4, -0.2002, -0.1};
    const std::vector<double> t_old = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0.3, 0.1, 0};
    auto evaluate = [&](std::span<const double> yy) {
      const std::vector<double> x = scene.at(yy);
      return evaluate_rigid_friction(
          {{scene.obstacle, x, scene.area, scene.dofs, 400.0, {}, 0.0, scene.M}, xi_old, t_old,
           eps_t, mu, true});
    };
    const RigidFrictionEvaluation e = evaluate(scene.y);
    std::set<std::int8_t> states(e.state.begin(), e.state.end());
    EXPECT_TRUE(states.count(static_cast<std::int8_t>(StickSlip::Stick)));
    EXPECT_TRUE(states.count(static_cast<std::int8_t>(StickSlip::Slip)));
    EXPECT_LE(test::dense_tangent_error(evaluate, scene.y), 1e-6) << "k = " << k;
  }
}

TEST(RigidGaussPoints, RejectsWeightsAndDofsThatDoNotMatch) {
  GaussScene scene = box_scene(6);
  const std::vector<double> x = scene.at(scene.y);
  std::vector<double> M = scene.M;
  M.pop_back();  // not k per point
  EXPECT_THROW(evaluate_rigid_contact({unit_box, x, scene.area, scene.dofs, 60.0, {}, 0.0, M}),
               std::invalid_argument);
  std::vector<std::int32_t> dofs = scene.dofs;
  dofs.resize(dofs.size() - 3);  // one node short
  EXPECT_THROW(evaluate_rigid_contact({unit_box, x, scene.area, dofs, 60.0, {}, 0.0, scene.M}),
               std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
