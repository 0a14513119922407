// project(obstacle, x) on the Obstacle variant: each alternative goes to its own projection
// (plane: g = (x − p)·n; box: the distance to a face from inside, to an edge from outside;
// cylinder: ρ − R).
#include <gtest/gtest.h>

#include <cmath>
#include <hypercontact/obstacle.hpp>

namespace hypercontact {
namespace {

TEST(Obstacle, ProjectDispatchesOnTheAlternative) {
  const Eigen::Vector3d x(0.3, 0.4, 0.25);
  const Obstacle plane = RigidPlane{{0, 0, 0.1}, {0, 0, 1}};
  const Obstacle box = RigidBox{{-1, -1, -1}, {0.2, 1, 1}};
  const Obstacle cylinder = RigidCylinder{{0, 0, 0}, {1, 0, 0}, 0.2};
  EXPECT_NEAR(project(plane, x).gap, 0.15, 1e-15);
  const ObstacleProjection b = project(box, x);  // outside the face x = 0.2 only
  EXPECT_NEAR(b.gap, 0.1, 1e-15);
  EXPECT_EQ(b.feature, Feature::Face);
  EXPECT_EQ(b.normal, Eigen::Vector3d(1, 0, 0));
  const ObstacleProjection c = project(cylinder, x);
  EXPECT_NEAR(c.gap, std::hypot(0.4, 0.25) - 0.2, 1e-15);
  EXPECT_NEAR(c.normal.x(), 0.0, 1e-15);
  EXPECT_NE(c.dnormal_dx, Eigen::Matrix3d::Zero());  // curved
}

}  // namespace
}  // namespace hypercontact
