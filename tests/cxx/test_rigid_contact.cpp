// Evaluation of all slave nodes against one obstacle, and its input checks.
#include <gtest/gtest.h>

#include <cmath>
#include <hypercontact/rigid_contact.hpp>
#include <stdexcept>
#include <vector>

namespace hypercontact {
namespace {

const Obstacle plane = RigidPlane{{0, 0, 0}, {0, 0, 1}};

TEST(RigidContact, EvaluatesEveryNode) {
  const std::vector<double> x = {0, 0, -0.1, 1, 0, 0.2};
  const std::vector<double> area = {0.5, 0.25};
  const std::vector<RigidContactNode> nodes = evaluate_rigid_contact(plane, x, area, 100.0);
  ASSERT_EQ(nodes.size(), 2u);
  EXPECT_NEAR(nodes[0].projection.gap, -0.1, 1e-15);
  EXPECT_TRUE(nodes[0].contact.closed);
  EXPECT_NEAR(nodes[0].contact.residual.z(), 0.5 * 100.0 * -0.1, 1e-13);
  EXPECT_NEAR(nodes[1].projection.gap, 0.2, 1e-15);
  EXPECT_FALSE(nodes[1].contact.closed);
}

TEST(RigidContact, NonFiniteCoordinateNamesTheNode) {
  const std::vector<double> x = {0, 0, -0.1, 1, std::nan(""), 0.2};
  try {
    evaluate_rigid_contact(plane, x, std::vector<double>{0.5, 0.5}, 100.0);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("node 1"), std::string::npos) << e.what();
  }
  const std::vector<double> y = {0, 0, INFINITY};
  EXPECT_THROW(evaluate_rigid_contact(plane, y, std::vector<double>{0.5}, 100.0),
               std::runtime_error);
}

TEST(RigidContact, RejectsBadInput) {
  const std::vector<double> x = {0, 0, -0.1};
  EXPECT_THROW(evaluate_rigid_contact(plane, x, std::vector<double>{-0.5}, 100.0),
               std::invalid_argument);
  EXPECT_THROW(evaluate_rigid_contact(plane, x, std::vector<double>{0.5}, 0.0),
               std::invalid_argument);
  EXPECT_THROW(evaluate_rigid_contact(plane, x, std::vector<double>{0.5, 0.5}, 100.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
