// Evaluation of all slave nodes against one obstacle, and its input checks; the evaluation with
// element contributions: each element is its node's normal penalty on the node's dofs, and the
// stored tangent is the derivative of the stored residual (central differences) on a plane, the
// face, edge and vertex of a box, a cylinder, with multipliers and with smoothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <hypercontact/rigid_contact.hpp>
#include <stdexcept>
#include <vector>

#include "contact_elements_fd.hpp"

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
    const RigidContactNode n =
        evaluate_rigid_contact(box, v, std::vector<double>{area}, eps, lam)[0];
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
    const RigidContactNode n =
        evaluate_rigid_contact(box, v, std::vector<double>{area}, eps, lam)[0];
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
  EXPECT_FALSE(
      evaluate_rigid_contact(box, far, std::vector<double>{area}, eps, lam)[0].contact.closed);
  EXPECT_THROW(
      evaluate_rigid_contact(box, far, std::vector<double>{area}, eps, std::vector<double>{-1.0}),
      std::invalid_argument);
  EXPECT_THROW(
      evaluate_rigid_contact(box, far, std::vector<double>{area}, eps, std::vector<double>{1, 2}),
      std::invalid_argument);
}

// --- The evaluation with element contributions ------------------------------------------------

/// Slave nodes against an obstacle, each coordinate its own dof.
struct RigidScene {
  Obstacle obstacle;
  std::vector<double> x, area, multipliers;
  double eps_n = 50.0, smoothing = 0.0;
  std::vector<std::int32_t> dofs = test::identity_dofs(x.size());

  RigidContactInput input(std::span<const double> y) const {
    return {obstacle, y, area, dofs, eps_n, multipliers, smoothing};
  }
  RigidContactEvaluation evaluate(std::span<const double> y) const {
    return evaluate_rigid_contact(input(y));
  }
  double tangent_error() const {
    return test::dense_tangent_error([this](std::span<const double> y) { return evaluate(y); }, x);
  }
};

const Obstacle unit_box = RigidBox{{-1, -1, -1}, {1, 1, 1}};

/// Box nodes, λ = 2 (λ/ε_N = 0.04) except node 4: inside under the top face (Face), outside by an
/// edge and by a vertex within λ/ε_N (Edge, Vertex: closed by λ), far above (open), and a
/// penalty node inside (λ = 0).
RigidScene box_scene() {
  return {unit_box,
          {0.2, 0.1, 0.97, 1.02, 0.3, 1.01, 1.01, 1.02, 1.01, 0.2, 0.1, 1.5, 0.1, -0.3, 0.9},
          {0.3, 0.2, 0.4, 0.5, 0.25},
          {2.0, 2.0, 2.0, 2.0, 0.0}};
}

TEST(RigidContactEvaluation, ElementsAreTheNodesPenaltyOnTheirDofs) {
  RigidScene scene = box_scene();
  scene.dofs[4] = -1;  // node 1's y is constrained: kept in the element, skipped by assembly
  const RigidContactEvaluation e = scene.evaluate(scene.x);
  const std::vector<Feature> features{Feature::Face, Feature::Edge, Feature::Vertex, Feature::Face,
                                      Feature::Face};
  ASSERT_EQ(e.elements.size(), 4u);
  EXPECT_EQ(e.elements.point, (std::vector<std::int32_t>{0, 1, 2, 4}));
  EXPECT_EQ(e.elements.numbering, DofNumbering::Local);
  EXPECT_EQ(e.num_closed, 4);
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (std::size_t i = 0, k = 0; i < 5; ++i) {
    // The old path: the projection, the gap shifted by λ/ε_N, normal_penalty.
    const Eigen::Vector3d xi(&scene.x[3 * i]);
    const ObstacleProjection p = project(unit_box, xi);
    EXPECT_EQ(p.feature, features[i]) << "node " << i;
    ObstacleProjection shifted = p;
    shifted.gap -= scene.multipliers[i] / scene.eps_n;
    const NodalContact c = normal_penalty(shifted, scene.area[i], scene.eps_n);
    EXPECT_EQ(e.gap[i], p.gap);
    EXPECT_EQ(e.pressure[i], c.pressure);
    if (!c.closed) continue;
    const std::size_t el = k++;
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(e.elements.rows(el)[j], scene.dofs[3 * i + j]);
      EXPECT_EQ(e.elements.columns(el)[j], scene.dofs[3 * i + j]);
      EXPECT_NEAR(e.elements.element_residual(el)[j], c.residual[j], 1e-14 * c.residual.norm());
    }
    EXPECT_LE(test::relative_error(e.elements.element_tangent(el), c.tangent), 1e-14);
    force -= c.residual;
  }
  EXPECT_LE((e.force - force).norm(), 1e-14 * force.norm());
}

TEST(RigidContactEvaluation, TangentIsTheDerivativeOfTheResidualInEveryBranch) {
  const RigidScene plane_scene{RigidPlane{{0, 0, 0.1}, Eigen::Vector3d(0.3, -0.2, 1).normalized()},
                               {0.1, 0.2, -0.05, -0.3, 0.1, 0.02, 0.0, 0.0, 0.5},
                               {0.5, 0.25, 0.75}};
  const RigidScene cylinder_scene{
      RigidCylinder{{0, 0, 1}, Eigen::Vector3d(1, 0.3, 0).normalized(), 1.0},
      {0.1, 0.05, 0.03, -0.2, 0.4, 0.15, 0.3, -0.6, 0.3},
      {0.5, 0.25, 0.75}};
  RigidScene smoothed = box_scene();
  smoothed.smoothing = 0.05;  // node 3 (g = 0.5 − 0.04) stays open, the others in or below the band
  for (const RigidScene* scene : {&plane_scene, &cylinder_scene}) {
    const RigidContactEvaluation e = scene->evaluate(scene->x);
    ASSERT_GE(e.elements.size(), 2u);
    EXPECT_LE(scene->tangent_error(), 1e-6);
  }
  const RigidScene box = box_scene();
  EXPECT_EQ(box.evaluate(box.x).elements.size(), 4u);  // face, edge, vertex and the penalty node
  EXPECT_LE(box.tangent_error(), 1e-6);
  EXPECT_EQ(smoothed.evaluate(smoothed.x).elements.size(), 4u);
  EXPECT_LE(smoothed.tangent_error(), 1e-6);
  // A box with rounded edges (r = 0.2): nodes pressed into a rounded edge and a rounded corner,
  // where the normal turns with the node, and under the flat top.
  const RigidScene rounded{RigidBox{{-1, -1, -1}, {1, 1, 1}, 0.2},
                           {0.9, 0.1, 0.92, 0.9, 0.9, 0.92, 0.2, 0.1, 0.97},
                           {0.3, 0.2, 0.4}};
  const RigidContactEvaluation r = rounded.evaluate(rounded.x);
  ASSERT_EQ(r.elements.size(), 3u);
  std::vector<Feature> features;
  for (std::size_t i = 0; i < 3; ++i) {
    const ObstacleProjection p = project(rounded.obstacle, Eigen::Vector3d(&rounded.x[3 * i]));
    EXPECT_LT(p.gap, 0);
    features.push_back(p.feature);
  }
  EXPECT_EQ(features, (std::vector<Feature>{Feature::Edge, Feature::Vertex, Feature::Face}));
  EXPECT_LE(rounded.tangent_error(), 1e-6);
  // The blended rounding (its curvature continuous): the same nodes, pressed less than r/2
  // into the rounded edge and corner.
  RigidScene blended = rounded;
  blended.obstacle = RigidBox{{-1, -1, -1}, {1, 1, 1}, 0.2, true};
  ASSERT_EQ(blended.evaluate(blended.x).elements.size(), 3u);
  for (std::size_t i = 0; i < 2; ++i) {
    const ObstacleProjection p = project(blended.obstacle, Eigen::Vector3d(&blended.x[3 * i]));
    EXPECT_LT(p.gap, 0);
    EXPECT_GT(p.gap, -0.1);
    EXPECT_FALSE(p.dnormal_dx.isZero(0));
  }
  EXPECT_LE(blended.tangent_error(), 1e-6);
}

TEST(RigidContactEvaluation, RejectsDofsOfTheWrongSize) {
  RigidScene scene = box_scene();
  scene.dofs.pop_back();
  EXPECT_THROW(scene.evaluate(scene.x), std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
