// Rigid sphere: the signed distance, normal and ∂n/∂x against their closed forms, ∂g/∂x = n and
// ∂n/∂x against central differences (outside, inside, near the centre), the centre finite; and
// the rigid-contact and rigid-friction evaluations against a sphere (doubly curved: ∂n/∂x has
// rank 2), their stored tangents against central differences of their residuals in the open,
// stick and slip branches.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <hypercontact/rigid_contact.hpp>
#include <hypercontact/rigid_contact_friction.hpp>
#include <hypercontact/rigid_sphere.hpp>
#include <set>
#include <vector>

#include "contact_elements_fd.hpp"
#include "finite_difference.hpp"

namespace hypercontact {
namespace {

using test::fd_gradient;
using test::fd_jacobian;
using test::relative_error;

const RigidSphere ball{{0.4, -0.2, 1.1}, 0.8};

/// The point at distance `distance` from the ball's centre in the direction `direction`.
Eigen::Vector3d at(const Eigen::Vector3d& direction, double distance) {
  return ball.center + distance * direction.normalized();
}

TEST(RigidSphere, ClosedFormOutsideAndInside) {
  const RigidSphere s{{1.0, 2.0, 3.0}, 2.0};
  // Outside: d = (3, 0, 4), ρ = 5, g = 3, n = (0.6, 0, 0.8).
  const ObstacleProjection out = project_to_sphere(s, Eigen::Vector3d(4.0, 2.0, 7.0));
  const Eigen::Vector3d n(0.6, 0.0, 0.8);
  EXPECT_NEAR(out.gap, 3.0, 1e-15);
  EXPECT_LE((out.normal - n).norm(), 1e-15);
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
  EXPECT_LE((out.dnormal_dx - P / 5.0).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(out.feature, Feature::Face);
  // Inside: d = (0, −0.6, 0.8), ρ = 1, g = −1: the closest surface point is radially outward.
  const ObstacleProjection in = project_to_sphere(s, Eigen::Vector3d(1.0, 1.4, 3.8));
  const Eigen::Vector3d m(0.0, -0.6, 0.8);
  EXPECT_NEAR(in.gap, -1.0, 1e-15);
  EXPECT_LE((in.normal - m).norm(), 1e-15);
  EXPECT_LE((in.dnormal_dx - (Eigen::Matrix3d::Identity() - m * m.transpose())).cwiseAbs().maxCoeff(),
            1e-15);
  EXPECT_EQ(in.feature, Feature::Face);
  // The closest point x − g n lies on the sphere, the normal there is radial.
  for (const ObstacleProjection& p : {out, in}) EXPECT_NEAR(p.normal.norm(), 1.0, 1e-15);
  EXPECT_NEAR((Eigen::Vector3d(4.0, 2.0, 7.0) - out.gap * out.normal - s.center).norm(), 2.0, 1e-14);
  EXPECT_NEAR((Eigen::Vector3d(1.0, 1.4, 3.8) - in.gap * in.normal - s.center).norm(), 2.0, 1e-14);
  // ∂n/∂x is symmetric, n is in its null space and it has rank 2 (both principal curvatures 1/ρ).
  EXPECT_LE((out.dnormal_dx - out.dnormal_dx.transpose()).norm(), 1e-15);
  EXPECT_LE((out.dnormal_dx * out.normal).norm(), 1e-15);
  EXPECT_NEAR(out.dnormal_dx.trace(), 2.0 / 5.0, 1e-15);
}

TEST(RigidSphere, NormalIsGradientOfGapAndItsDerivativeExact) {
  const auto gap = [](const Eigen::Vector3d& y) { return project_to_sphere(ball, y).gap; };
  const auto normal = [](const Eigen::Vector3d& y) { return project_to_sphere(ball, y).normal; };
  const Eigen::Vector3d e(0.3, -0.7, 0.5);
  // far outside, just outside, just inside, half way in, near the centre (1e-2 R and 1e-3 R)
  for (const double distance : {3.0, 0.81, 0.79, 0.4, 8e-3, 8e-4}) {
    const Eigen::Vector3d x = at(e, distance);
    const ObstacleProjection p = project_to_sphere(ball, x);
    EXPECT_NEAR(p.gap, distance - ball.radius, 1e-14);
    // central differences err by O((h/ρ)²) relative: 2e-6 at ρ = 8e-4 with h = 1.1e-6
    const double near_centre = distance < 1e-3 ? 1e-5 : 0.0;
    EXPECT_LE(relative_error(fd_gradient(gap, x), p.normal), std::max(1e-8, near_centre))
        << "ρ = " << distance;
    EXPECT_LE(relative_error(fd_jacobian(normal, x), p.dnormal_dx), std::max(1e-7, near_centre))
        << "ρ = " << distance;
    EXPECT_NEAR(p.normal.norm(), 1.0, 1e-14);
  }
}

TEST(RigidSphere, AtTheCentreIsFinite) {
  for (const Eigen::Vector3d& x : {ball.center, Eigen::Vector3d(ball.center + Eigen::Vector3d(3e-13, 0, 0))}) {
    const ObstacleProjection p = project_to_sphere(ball, x);
    EXPECT_NEAR(p.gap, -ball.radius, 1e-12);
    EXPECT_TRUE(std::isfinite(p.gap) && p.normal.allFinite() && p.dnormal_dx.allFinite());
    EXPECT_NEAR(p.normal.norm(), 1.0, 1e-15);
    EXPECT_EQ(p.dnormal_dx, Eigen::Matrix3d::Zero());
    EXPECT_EQ(p.feature, Feature::Face);
  }
}

TEST(RigidSphere, DispatchedByProject) {
  const Obstacle obstacle = ball;
  const Eigen::Vector3d x(0.9, 0.1, 0.4);
  const ObstacleProjection p = project(obstacle, x), q = project_to_sphere(ball, x);
  EXPECT_EQ(p.gap, q.gap);
  EXPECT_EQ(p.normal, q.normal);
  EXPECT_EQ(p.dnormal_dx, q.dnormal_dx);
}

// --- The evaluations against a sphere -----------------------------------------------------------

constexpr double eps_n = 400.0, eps_t = 300.0, mu = 0.4;

/// Three nodes about the lower pole, two penetrating (by 0.05 and 0.03) and one open (0.02 off
/// the sphere), each coordinate its own dof.
std::vector<double> pole_nodes() {
  std::vector<double> x;
  for (const auto& [direction, distance] :
       {std::pair{Eigen::Vector3d(0.1, 0.05, -1.0), ball.radius - 0.05},
        std::pair{Eigen::Vector3d(-0.3, 0.2, -1.0), ball.radius - 0.03},
        std::pair{Eigen::Vector3d(0.2, -0.4, -1.0), ball.radius + 0.02}}) {
    const Eigen::Vector3d p = at(direction, distance);
    x.insert(x.end(), p.data(), p.data() + 3);
  }
  return x;
}

const std::vector<double> areas = {0.5, 0.25, 0.75};

TEST(RigidSphereEvaluation, NormalPenaltyTangentIsTheDerivativeOfTheResidual) {
  const std::vector<double> x = pole_nodes();
  const std::vector<std::int32_t> dofs = test::identity_dofs(x.size());
  for (const double smoothing : {0.0, 0.01}) {
    const auto evaluate = [&](std::span<const double> y) {
      return evaluate_rigid_contact({Obstacle{ball}, y, areas, dofs, eps_n, {}, smoothing});
    };
    const RigidContactEvaluation e = evaluate(x);
    ASSERT_EQ(e.elements.size(), 2u) << "δ = " << smoothing;  // the open node is beyond the band
    EXPECT_EQ(e.num_closed, 2);
    EXPECT_NEAR(e.gap[0], -0.05, 1e-14);
    EXPECT_NEAR(e.gap[2], 0.02, 1e-14);
    EXPECT_LE(test::dense_tangent_error(evaluate, x), 1e-6) << "δ = " << smoothing;
  }
}

TEST(RigidSphereEvaluation, FrictionTangentIsTheDerivativeOfTheResidualInStickAndSlip) {
  const std::vector<double> x = pole_nodes();
  const std::vector<std::int32_t> dofs = test::identity_dofs(x.size());
  // Node 0 sticks (moved 1e-4 since the last step: ε_T |Δs| = 0.03 < μ p_N = 8), node 1 slips
  // (moved 0.2 across the pole: 60 > μ p_N = 4.8) with a traction from the last step, node 2 is
  // open.
  std::vector<double> xi_old = x, t_old(x.size(), 0.0);
  xi_old[0] -= 1e-4;
  xi_old[3] -= 0.2;
  xi_old[4] += 0.05;
  t_old[3] = 0.5;
  t_old[5] = 0.2;  // a normal component: projected onto the tangent plane
  for (const bool with_normal : {true, false}) {
    const auto evaluate = [&](std::span<const double> y) {
      return evaluate_rigid_friction(
          {{Obstacle{ball}, y, areas, dofs, eps_n}, xi_old, t_old, eps_t, mu, with_normal});
    };
    const RigidFrictionEvaluation e = evaluate(x);
    EXPECT_EQ(e.state, (std::vector<std::int8_t>{static_cast<std::int8_t>(StickSlip::Stick),
                                                 static_cast<std::int8_t>(StickSlip::Slip),
                                                 static_cast<std::int8_t>(StickSlip::Open)}));
    ASSERT_EQ(e.elements.size(), 2u);
    EXPECT_LE(test::dense_tangent_error(evaluate, x), 1e-6) << "with_normal = " << with_normal;
  }
}

}  // namespace
}  // namespace hypercontact
