// Normal penalty: r = ∂W/∂x and K = ∂r/∂x against central finite differences, every branch.
#include <gtest/gtest.h>

#include <cmath>
#include <hypercontact/normal_penalty.hpp>
#include <hypercontact/obstacle.hpp>
#include <stdexcept>

#include "finite_difference.hpp"

namespace hypercontact {
namespace {

using test::fd_gradient;
using test::fd_jacobian;
using test::relative_error;

constexpr double area = 0.37;
constexpr double eps_n = 250.0;
const RigidBox box{{-1, -1, 0}, {1, 1, 0.4}};

/// Checks r against the FD gradient of W and K against the FD Jacobian of r, for a closed
/// contact, with the projection x ↦ project_at(x).
template <typename Project>
void expect_exact_derivatives_along(Project project_at, const Eigen::Vector3d& x) {
  const auto energy = [&](const Eigen::Vector3d& y) {
    return normal_penalty_energy(project_at(y), area, eps_n);
  };
  const auto residual = [&](const Eigen::Vector3d& y) {
    return normal_penalty(project_at(y), area, eps_n).residual;
  };
  const NodalContact c = normal_penalty(project_at(x), area, eps_n);
  ASSERT_TRUE(c.closed);
  EXPECT_LE(relative_error(fd_gradient(energy, x), c.residual), 1e-6);
  EXPECT_LE(relative_error(fd_jacobian(residual, x), c.tangent), 1e-6);
}

void expect_exact_derivatives(const Obstacle& obstacle, const Eigen::Vector3d& x) {
  expect_exact_derivatives_along([&](const Eigen::Vector3d& y) { return project(obstacle, y); }, x);
}

TEST(NormalPenalty, TiltedPlaneClosed) {
  const RigidPlane plane{{0.1, -0.2, 0.3}, Eigen::Vector3d(0.3, -0.2, 1.0).normalized()};
  const Eigen::Vector3d x = plane.point + Eigen::Vector3d(0.5, 0.4, 0.2) - 0.3 * plane.normal;
  const NodalContact c = normal_penalty(project(plane, x), area, eps_n);
  const double g = project(plane, x).gap;
  EXPECT_LT(g, 0);
  EXPECT_NEAR(c.pressure, -eps_n * g, 1e-12);
  EXPECT_NEAR(normal_penalty_energy(project(plane, x), area, eps_n), 0.5 * area * eps_n * g * g,
              1e-12);
  expect_exact_derivatives(plane, x);
}

TEST(NormalPenalty, PlaneOpenIsZero) {
  const RigidPlane plane{{0, 0, 0}, Eigen::Vector3d(0.3, -0.2, 1.0).normalized()};
  const Eigen::Vector3d x(0.2, 0.1, 0.05);
  const NodalContact c = normal_penalty(project(plane, x), area, eps_n);
  EXPECT_FALSE(c.closed);
  EXPECT_EQ(c.residual, Eigen::Vector3d::Zero());
  EXPECT_EQ(c.tangent, Eigen::Matrix3d::Zero());
  EXPECT_EQ(c.pressure, 0.0);
  EXPECT_EQ(normal_penalty_energy(project(plane, x), area, eps_n), 0.0);
}

TEST(NormalPenalty, TouchingCountsAsClosed) {
  const RigidPlane plane{{0, 0, 0}, {0, 0, 1}};
  const NodalContact c = normal_penalty(project(plane, {0.3, 0.4, 0.0}), area, eps_n);
  EXPECT_TRUE(c.closed);
  EXPECT_EQ(c.residual, Eigen::Vector3d::Zero());
  EXPECT_EQ(c.pressure, 0.0);
  const Eigen::Matrix3d expected =
      area * eps_n * Eigen::Vector3d::UnitZ() * Eigen::Vector3d::UnitZ().transpose();
  EXPECT_EQ(c.tangent, expected);
}

TEST(NormalPenalty, BoxInsideUnderBottomFaceNearEdge) {
  // Face distances: bottom 0.03, +x 0.1, others larger: the bottom face is closest.
  const Eigen::Vector3d x(0.9, 0.2, 0.03);
  const ObstacleProjection p = project(box, x);
  EXPECT_EQ(p.normal, Eigen::Vector3d(0, 0, -1));
  EXPECT_NEAR(p.gap, -0.03, 1e-15);
  expect_exact_derivatives(box, x);
}

TEST(NormalPenalty, BoxInsideNearSideWall) {
  // Face distances: +x 0.03, bottom and top 0.2: the +x wall is closest.
  const Eigen::Vector3d x(0.97, 0.1, 0.2);
  const ObstacleProjection p = project(box, x);
  EXPECT_EQ(p.normal, Eigen::Vector3d(1, 0, 0));
  EXPECT_NEAR(p.gap, -0.03, 1e-15);
  expect_exact_derivatives(box, x);
}

TEST(NormalPenalty, BoxOutsideIsOpen) {
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(1.05, 0.3, -0.02),    // edge
                                   Eigen::Vector3d(1.03, -1.04, -0.02),  // vertex
                                   Eigen::Vector3d(0.5, 0.5, -0.1)}) {   // face
    const NodalContact c = normal_penalty(project(box, x), area, eps_n);
    EXPECT_FALSE(c.closed);
    EXPECT_EQ(c.residual, Eigen::Vector3d::Zero());
    EXPECT_EQ(c.tangent, Eigen::Matrix3d::Zero());
  }
}

/// A curved obstacle (sphere of radius R about c), written here to exercise the g ∂n/∂x term,
/// which no flat obstacle has in the closed state.
ObstacleProjection project_to_sphere(const Eigen::Vector3d& x) {
  const Eigen::Vector3d center(0.2, -0.1, -1.0);
  const double radius = 1.0;
  const Eigen::Vector3d d = x - center;
  const double r = d.norm();
  const Eigen::Vector3d n = d / r;
  return {r - radius, n, (Eigen::Matrix3d::Identity() - n * n.transpose()) / r, Feature::Face};
}

TEST(NormalPenalty, CurvedObstacleClosed) {
  const Eigen::Vector3d x(0.4, 0.2, -0.3);
  ASSERT_LT(project_to_sphere(x).gap, -0.1);
  expect_exact_derivatives_along(project_to_sphere, x);
}

TEST(NormalPenalty, RejectsBadParameters) {
  const ObstacleProjection p = project(RigidPlane{{0, 0, 0}, {0, 0, 1}}, {0, 0, -0.1});
  EXPECT_THROW(normal_penalty(p, -1e-3, eps_n), std::invalid_argument);
  EXPECT_THROW(normal_penalty(p, area, 0.0), std::invalid_argument);
  EXPECT_THROW(normal_penalty(p, area, -1.0), std::invalid_argument);
  EXPECT_THROW(normal_penalty(p, std::nan(""), eps_n), std::invalid_argument);
  EXPECT_THROW(normal_penalty_energy(p, area, 0.0), std::invalid_argument);
  EXPECT_NO_THROW(normal_penalty(p, 0.0, eps_n));
}

}  // namespace
}  // namespace hypercontact
