// Rigid cylinder: signed distance against a brute-force reference, normal and its derivative
// against finite differences, and the normal-penalty and friction tangents on it (the curved
// obstacle's ∂n/∂x terms) against central differences, inside and on both sides of the axis;
// the same for a bore (inside = true: the admissible region within the cylinder).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <hypercontact/coulomb_friction.hpp>
#include <hypercontact/normal_penalty.hpp>
#include <hypercontact/rigid_cylinder.hpp>
#include <random>

#include "finite_difference.hpp"

namespace hypercontact {
namespace {

using test::fd_gradient;
using test::fd_jacobian;
using test::relative_error;

const RigidCylinder die{{2.5, 0.3, 6.0}, Eigen::Vector3d(0.1, 1.0, -0.2).normalized(), 3.0};
const RigidCylinder bore{die.point, die.axis, die.radius, true};

/// Distance from x to the cylinder's surface by brute force: the minimum over a fine sampling
/// of the circle through x's axial station, refined by golden-section search (no formulas
/// shared with the library).
double reference_distance(const RigidCylinder& c, const Eigen::Vector3d& x) {
  const Eigen::Vector3d e1 = c.axis.unitOrthogonal(), e2 = c.axis.cross(e1);
  const Eigen::Vector3d centre = c.point + (x - c.point).dot(c.axis) * c.axis;
  const auto dist = [&](double t) {
    return (centre + c.radius * (std::cos(t) * e1 + std::sin(t) * e2) - x).norm();
  };
  double best = 0, best_d = dist(0);
  for (int k = 1; k < 3600; ++k) {
    const double t = 2 * M_PI * k / 3600;
    if (dist(t) < best_d) best_d = dist(best = t);
  }
  double lo = best - 2 * M_PI / 3600, hi = best + 2 * M_PI / 3600;
  for (int k = 0; k < 100; ++k) {
    const double m1 = hi - (hi - lo) / 1.618033988749895, m2 = lo + (hi - lo) / 1.618033988749895;
    (dist(m1) < dist(m2) ? hi : lo) = (dist(m1) < dist(m2) ? m2 : m1);
  }
  return dist(0.5 * (lo + hi));
}

TEST(RigidCylinder, RandomPointsMatchBruteForceDistance) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-6.0, 6.0);
  int inside = 0;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d x = die.point + Eigen::Vector3d(u(rng), u(rng), u(rng));
    const ObstacleProjection p = project_to_cylinder(die, x);
    const double reference = reference_distance(die, x);
    // |g| is the distance to the surface; its sign says inside (< 0) or outside.
    ASSERT_NEAR(std::abs(p.gap), reference, 1e-9) << "x = " << x.transpose();
    const double axial_offset = ((x - die.point) - (x - die.point).dot(die.axis) * die.axis).norm();
    ASSERT_EQ(p.gap < 0, axial_offset < die.radius);
    inside += p.gap < 0;
    // The closest point x − g n is on the surface.
    ASSERT_NEAR(reference_distance(die, x - p.gap * p.normal), 0.0, 1e-9);
    EXPECT_EQ(p.feature, Feature::Face);
  }
  EXPECT_GT(inside, 20);  // both sides sampled
  EXPECT_LT(inside, 180);
}

TEST(RigidCylinder, NormalIsGradientOfGapAndItsDerivativeExact) {
  const auto gap = [](const Eigen::Vector3d& y) { return project_to_cylinder(die, y).gap; };
  const auto normal = [](const Eigen::Vector3d& y) { return project_to_cylinder(die, y).normal; };
  for (const Eigen::Vector3d& x :
       {Eigen::Vector3d(2.6, 1.0, 2.9), Eigen::Vector3d(5.4, -0.4, 5.0),
        Eigen::Vector3d(1.0, 0.5, 7.0), Eigen::Vector3d(2.2, 0.0, 3.4)}) {
    const ObstacleProjection p = project_to_cylinder(die, x);
    EXPECT_LE(relative_error(fd_gradient(gap, x), p.normal), 1e-8) << x.transpose();
    EXPECT_LE(relative_error(fd_jacobian(normal, x), p.dnormal_dx), 1e-6) << x.transpose();
    EXPECT_NEAR(p.normal.norm(), 1.0, 1e-14);
    EXPECT_NEAR(p.normal.dot(die.axis), 0.0, 1e-14);
  }
}

TEST(RigidCylinder, OnTheAxisIsFiniteAndRadial) {
  const ObstacleProjection p = project_to_cylinder(die, die.point + 2.0 * die.axis);
  EXPECT_NEAR(p.gap, -die.radius, 1e-14);
  EXPECT_TRUE(p.normal.allFinite() && p.dnormal_dx.allFinite());
  EXPECT_NEAR(p.normal.norm(), 1.0, 1e-14);
  EXPECT_NEAR(p.normal.dot(die.axis), 0.0, 1e-14);
}

TEST(RigidCylinder, DispatchedByProject) {
  const Obstacle obstacle = die;
  const Eigen::Vector3d x(2.6, 1.0, 2.9);
  EXPECT_EQ(project(obstacle, x).gap, project_to_cylinder(die, x).gap);
}

constexpr double area = 0.37, eps_n = 250.0, eps_t = 180.0, mu = 0.3;

TEST(RigidCylinder, NormalPenaltyTangentExactWhenPenetrating) {
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(2.6, 1.0, 3.05), Eigen::Vector3d(5.0, -0.4, 4.7)}) {
    ASSERT_LT(project(Obstacle{die}, x).gap, 0);
    const auto energy = [](const Eigen::Vector3d& y) {
      return normal_penalty_energy(project(Obstacle{die}, y), area, eps_n);
    };
    const auto residual = [](const Eigen::Vector3d& y) {
      return normal_penalty(project(Obstacle{die}, y), area, eps_n).residual;
    };
    const NodalContact c = normal_penalty(project(Obstacle{die}, x), area, eps_n);
    ASSERT_TRUE(c.closed);
    EXPECT_LE(relative_error(fd_gradient(energy, x), c.residual), 1e-6);
    EXPECT_LE(relative_error(fd_jacobian(residual, x), c.tangent), 1e-6);
  }
}

TEST(RigidCylinder, FrictionTangentExactInStickAndSlip) {
  const Eigen::Vector3d x(2.9, 1.0, 3.02);
  const ObstacleProjection p = project(Obstacle{die}, x);
  ASSERT_LT(p.gap, -0.01);
  const Eigen::Vector3d t_old(0.3, -0.2, 0.5);  // has a normal component: projected
  const Eigen::Vector3d along = die.axis.cross(p.normal);
  for (const auto& [offset, expected] :
       {std::pair{Eigen::Vector3d(1e-4 * along), StickSlip::Stick},
        std::pair{Eigen::Vector3d(1.0 * along + 0.3 * die.axis), StickSlip::Slip}}) {
    const Eigen::Vector3d xi_old = x - offset;
    const auto residual = [&](const Eigen::Vector3d& y) {
      return coulomb_friction(project(Obstacle{die}, y), y, xi_old, t_old, area, eps_n, eps_t, mu)
          .residual;
    };
    const FrictionResult f = coulomb_friction(p, x, xi_old, t_old, area, eps_n, eps_t, mu);
    ASSERT_EQ(f.state, expected);
    EXPECT_LE(relative_error(fd_jacobian(residual, x), f.tangent), 1e-6);
  }
}

// --- a bore: the body inside the cylinder ----------------------------------------------------

TEST(RigidCylinderBore, GapIsTheDistanceToTheWallPositiveInside) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-6.0, 6.0);
  int admissible = 0;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d x = die.point + Eigen::Vector3d(u(rng), u(rng), u(rng));
    const ObstacleProjection p = project_to_cylinder(bore, x);
    ASSERT_NEAR(std::abs(p.gap), reference_distance(bore, x), 1e-9) << "x = " << x.transpose();
    const double axial_offset = ((x - die.point) - (x - die.point).dot(die.axis) * die.axis).norm();
    ASSERT_EQ(p.gap > 0, axial_offset < die.radius);  // admissible within the wall
    ASSERT_NEAR(reference_distance(bore, x - p.gap * p.normal), 0.0, 1e-9);  // x − g n on the wall
    admissible += p.gap > 0;
  }
  EXPECT_GT(admissible, 20);
  EXPECT_LT(admissible, 180);
}

TEST(RigidCylinderBore, NormalIsGradientOfGapAndItsDerivativeExact) {
  const auto gap = [](const Eigen::Vector3d& y) { return project_to_cylinder(bore, y).gap; };
  const auto normal = [](const Eigen::Vector3d& y) { return project_to_cylinder(bore, y).normal; };
  for (const Eigen::Vector3d& x :
       {Eigen::Vector3d(2.6, 1.0, 2.9), Eigen::Vector3d(5.4, -0.4, 5.0),
        Eigen::Vector3d(1.0, 0.5, 7.0), Eigen::Vector3d(0.2, 0.0, 8.4)}) {
    const ObstacleProjection p = project_to_cylinder(bore, x);
    EXPECT_LE(relative_error(fd_gradient(gap, x), p.normal), 1e-8) << x.transpose();
    EXPECT_LE(relative_error(fd_jacobian(normal, x), p.dnormal_dx), 1e-6) << x.transpose();
    EXPECT_NEAR(p.gap, -project_to_cylinder(die, x).gap, 1e-14);  // the die's surface seen from within
  }
  const ObstacleProjection axis = project_to_cylinder(bore, bore.point + 2.0 * bore.axis);
  EXPECT_NEAR(axis.gap, bore.radius, 1e-14);  // the axis: farthest from the wall, finite
  EXPECT_TRUE(axis.normal.allFinite() && axis.dnormal_dx.allFinite());
}

TEST(RigidCylinderBore, PenaltyAndFrictionTangentsExactBeyondTheWall) {
  // a point beyond the wall (penetrating), radially outward from the axis
  const Eigen::Vector3d radial = die.axis.unitOrthogonal();
  const Eigen::Vector3d x = bore.point + 1.5 * bore.axis + (bore.radius + 0.04) * radial;
  const ObstacleProjection p = project(Obstacle{bore}, x);
  ASSERT_NEAR(p.gap, -0.04, 1e-12);
  ASSERT_NEAR(p.normal.dot(radial), -1.0, 1e-12);  // pointing back in, towards the axis
  const auto residual = [](const Eigen::Vector3d& y) {
    return normal_penalty(project(Obstacle{bore}, y), area, eps_n).residual;
  };
  const NodalContact c = normal_penalty(p, area, eps_n);
  ASSERT_TRUE(c.closed);
  EXPECT_LE(relative_error(fd_jacobian(residual, x), c.tangent), 1e-6);
  const Eigen::Vector3d t_old(0.3, -0.2, 0.5);
  const Eigen::Vector3d along = bore.axis.cross(p.normal);
  for (const auto& [offset, expected] :
       {std::pair{Eigen::Vector3d(1e-4 * along), StickSlip::Stick},
        std::pair{Eigen::Vector3d(1.0 * along + 0.3 * bore.axis), StickSlip::Slip}}) {
    const Eigen::Vector3d xi_old = x - offset;
    const auto friction = [&](const Eigen::Vector3d& y) {
      return coulomb_friction(project(Obstacle{bore}, y), y, xi_old, t_old, area, eps_n, eps_t, mu)
          .residual;
    };
    const FrictionResult f = coulomb_friction(p, x, xi_old, t_old, area, eps_n, eps_t, mu);
    ASSERT_EQ(f.state, expected);
    EXPECT_LE(relative_error(fd_jacobian(friction, x), f.tangent), 1e-6);
  }
}

}  // namespace
}  // namespace hypercontact
