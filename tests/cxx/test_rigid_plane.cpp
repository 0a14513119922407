// Rigid plane: signed distance and its derivatives.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <hypercontact/rigid_plane.hpp>

#include "finite_difference.hpp"

namespace hypercontact {
namespace {

TEST(RigidPlane, SignedDistanceAndNormal) {
  const RigidPlane plane{{0.1, -0.2, 0.3}, Eigen::Vector3d(0.3, -0.2, 1.0).normalized()};
  const Eigen::Vector3d tangential = Eigen::Vector3d(1, 2, 0).cross(plane.normal);
  for (double g : {-0.2, 0.0, 0.7}) {
    const ObstacleProjection p =
        project_to_plane(plane, plane.point + tangential + g * plane.normal);
    EXPECT_NEAR(p.gap, g, 1e-14);
    EXPECT_EQ(p.normal, plane.normal);
    EXPECT_EQ(p.dnormal_dx, Eigen::Matrix3d::Zero());
    EXPECT_EQ(p.feature, Feature::Face);
  }
}

TEST(RigidPlane, GapGradientIsNormal) {
  const RigidPlane plane{{0.1, -0.2, 0.3}, Eigen::Vector3d(0.3, -0.2, 1.0).normalized()};
  const Eigen::Vector3d x(0.4, 0.5, -0.6);
  const auto gap = [&](const Eigen::Vector3d& y) { return project_to_plane(plane, y).gap; };
  EXPECT_LE(test::relative_error(test::fd_gradient(gap, x), plane.normal), 1e-6);
}

}  // namespace
}  // namespace hypercontact
