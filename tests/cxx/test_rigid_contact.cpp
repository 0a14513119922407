// Evaluation of all slave nodes against one obstacle, and its input checks.
#include <gtest/gtest.h>

#include <algorithm>
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

TEST(RigidContact, AugmentedLagrangianShiftsTheGap) {
  // With a multiplier λ the pressure is ⟨λ − ε g⟩ and the residual/tangent are the gradient and
  // Hessian of the augmented energy A/(2ε) ⟨λ − ε g⟩² (λ fixed), here on a curved obstacle.
  const Obstacle box = RigidBox{{-1, -1, -1}, {1, 1, 1}};
  const double area = 0.3, eps = 50.0, lambda = 2.0;
  const std::vector<double> lam = {lambda};
  auto energy = [&](const Eigen::Vector3d& y) {
    const std::vector<double> v(y.data(), y.data() + 3);
    const RigidContactNode n = evaluate_rigid_contact(box, v, std::vector<double>{area}, eps, lam)[0];
    const double p = std::max(0.0, lambda - eps * n.projection.gap);
    return area / (2 * eps) * p * p;
  };
  auto residual = [&](const Eigen::Vector3d& y) {
    const std::vector<double> v(y.data(), y.data() + 3);
    return Eigen::Vector3d(
        evaluate_rigid_contact(box, v, std::vector<double>{area}, eps, lam)[0].contact.residual);
  };
  // Outside near an edge, within λ/ε = 0.04 of the box: closed only because of λ.
  for (const Eigen::Vector3d x : {Eigen::Vector3d(1.02, 0.3, 1.01), Eigen::Vector3d(0.2, 0.1, 1.03),
                                  Eigen::Vector3d(0.2, 0.1, 0.97)}) {
    const std::vector<double> v(x.data(), x.data() + 3);
    const RigidContactNode n = evaluate_rigid_contact(box, v, std::vector<double>{area}, eps, lam)[0];
    ASSERT_TRUE(n.contact.closed);
    EXPECT_NEAR(n.contact.pressure, lambda - eps * n.projection.gap, 1e-12);
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(j);
      EXPECT_NEAR((energy(x + e) - energy(x - e)) / (2 * h), n.contact.residual[j],
                  1e-6 * n.contact.residual.norm());
      const Eigen::Vector3d column = (residual(x + e) - residual(x - e)) / (2 * h);
      EXPECT_LT((column - n.contact.tangent.col(j)).norm(), 1e-6 * n.contact.tangent.norm());
    }
  }
  // Beyond λ/ε: open.
  const std::vector<double> far = {0.2, 0.1, 1.05};
  EXPECT_FALSE(evaluate_rigid_contact(box, far, std::vector<double>{area}, eps, lam)[0].contact.closed);
  EXPECT_THROW(evaluate_rigid_contact(box, far, std::vector<double>{area}, eps, std::vector<double>{-1.0}),
               std::invalid_argument);
  EXPECT_THROW(evaluate_rigid_contact(box, far, std::vector<double>{area}, eps, std::vector<double>{1, 2}),
               std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
