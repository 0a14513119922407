// Normal penalty and Coulomb friction of all slave nodes against one obstacle, in one evaluation:
// each element is its node's normal penalty plus its friction (or the friction alone), the state
// arrays are the kernels', and the stored tangent is the derivative of the stored residual
// (central differences) in the open, stick and slip branches on a plane, a cylinder and the
// rounded edge and corner of a box, with multipliers and with smoothing.
#include <gtest/gtest.h>

#include <hypercontact/rigid_contact_friction.hpp>
#include <set>
#include <stdexcept>
#include <vector>

#include "contact_elements_fd.hpp"

namespace hypercontact {
namespace {

constexpr double eps_n = 400.0, eps_t = 300.0, mu = 0.4;

/// Slave nodes with their history, each coordinate its own dof.
struct FrictionScene {
  Obstacle obstacle;
  std::vector<double> x, area, xi_old, t_old, multipliers = {};
  double smoothing = 0.0;
  bool with_normal = true;
  std::vector<std::int32_t> dofs = test::identity_dofs(x.size());

  RigidFrictionEvaluation evaluate(std::span<const double> y) const {
    return evaluate_rigid_friction({{obstacle, y, area, dofs, eps_n, multipliers, smoothing},
                                    xi_old,
                                    t_old,
                                    eps_t,
                                    mu,
                                    with_normal});
  }
  double tangent_error() const {
    return test::dense_tangent_error([this](std::span<const double> y) { return evaluate(y); }, x);
  }
};

/// Four nodes on a tilted plane: open (above), stick (a small slip from ξ_old), slip (a large
/// one), stick with a traction from the last step.
FrictionScene plane_scene() {
  return {RigidPlane{{0, 0, 0.1}, Eigen::Vector3d(0.3, -0.2, 1).normalized()},
          {0.0, 0.0, 0.5, 0.1, 0.2, -0.05, -0.3, 0.1, 0.02, 0.4, -0.2, -0.1},
          {0.75, 0.5, 0.25, 0.4},
          {0.0, 0.0, 0.5, 0.1001, 0.2, -0.05, -0.1, 0.1, 0.02, 0.4, -0.2002, -0.1},
          {0, 0, 0, 0, 0, 0, 0, 0, 0, 0.3, 0.1, 0}};
}

/// Three nodes inside a cylinder (curved: the tangent plane turns with the node): stick, slip,
/// slip.
FrictionScene cylinder_scene() {
  return {RigidCylinder{{0, 0, 1}, Eigen::Vector3d(1, 0.3, 0).normalized(), 1.0},
          {0.1, 0.05, 0.03, -0.2, 0.4, 0.15, 0.3, -0.6, 0.3},
          {0.5, 0.25, 0.75},
          {0.1002, 0.05, 0.03, -0.2, 0.6, 0.15, 0.6, -0.6, 0.3},
          {0, 0, 0, 0.5, 0, 0, 0, 0, 0}};
}

/// Two nodes pressed into the rounded edge and the rounded corner of a box with r = 0.2 (the
/// normal turns with the node, as on the cylinder): stick (a small slip from ξ_old), slip.
FrictionScene rounded_box_scene() {
  return {RigidBox{{-1, -1, -1}, {1, 1, 1}, 0.2},
          {0.9, 0.1, 0.92, 0.9, 0.9, 0.92},
          {0.5, 0.25},
          {0.9, 0.1001, 0.92, 0.9, 0.6, 0.92},
          {0, 0, 0, 0, 0, 0}};
}

/// The same nodes on a box whose rounding is blended (continuous curvature).
FrictionScene blended_box_scene() {
  FrictionScene scene = rounded_box_scene();
  scene.obstacle = RigidBox{{-1, -1, -1}, {1, 1, 1}, 0.2, true};
  return scene;
}

std::set<StickSlip> states(const RigidFrictionEvaluation& e) {
  std::set<StickSlip> s;
  for (std::int8_t v : e.state) s.insert(static_cast<StickSlip>(v));
  return s;
}

TEST(RigidFrictionEvaluation, ElementsAreNormalPlusFrictionOfTheirNode) {
  const FrictionScene scene = plane_scene();
  const RigidFrictionEvaluation e = scene.evaluate(scene.x);
  FrictionScene friction_only = scene;
  friction_only.with_normal = false;
  const RigidFrictionEvaluation t = friction_only.evaluate(scene.x);
  EXPECT_EQ(states(e), (std::set<StickSlip>{StickSlip::Open, StickSlip::Stick, StickSlip::Slip}));
  ASSERT_EQ(e.elements.size(), 3u);
  ASSERT_EQ(t.elements.size(), 3u);
  Eigen::Vector3d normal_force = Eigen::Vector3d::Zero(), friction_force = normal_force;
  for (std::size_t i = 0, k = 0; i < 4; ++i) {
    // The old path: one projection for normal_penalty, one for coulomb_friction.
    const Eigen::Vector3d xi(&scene.x[3 * i]);
    const ObstacleProjection p = project(scene.obstacle, xi);
    const NodalContact n = normal_penalty(p, scene.area[i], eps_n);
    const FrictionResult f =
        coulomb_friction(p, xi, Eigen::Vector3d(&scene.xi_old[3 * i]),
                         Eigen::Vector3d(&scene.t_old[3 * i]), scene.area[i], eps_n, eps_t, mu);
    EXPECT_EQ(e.state[i], static_cast<std::int8_t>(f.state));
    EXPECT_EQ(e.gap[i], p.gap);
    EXPECT_EQ(e.dissipation[i], f.dissipation);
    EXPECT_EQ(Eigen::Vector3d(&e.traction[3 * i]), f.traction);
    EXPECT_EQ(Eigen::Vector3d(&e.slip_increment[3 * i]), f.slip_increment);
    if (!n.closed) continue;
    const std::size_t el = k++;
    EXPECT_EQ(e.elements.point[el], static_cast<std::int32_t>(i));
    const Eigen::Map<const Eigen::Vector3d> R(e.elements.element_residual(el).data());
    const Eigen::Map<const Eigen::Vector3d> R_t(t.elements.element_residual(el).data());
    EXPECT_LE((R - n.residual - f.residual).norm(), 1e-14 * R.norm());
    EXPECT_LE((R_t - f.residual).norm(), 1e-14 * f.residual.norm());
    EXPECT_LE(test::relative_error(e.elements.element_tangent(el), n.tangent + f.tangent), 1e-14);
    EXPECT_LE(test::relative_error(t.elements.element_tangent(el), f.tangent), 1e-14);
    normal_force -= n.residual;
    friction_force -= f.residual;
  }
  EXPECT_LE((e.force - normal_force).norm(), 1e-14 * normal_force.norm());
  EXPECT_LE((e.friction_force - friction_force).norm(), 1e-14 * friction_force.norm());
  EXPECT_LE((e.total_force - normal_force - friction_force).norm(), 1e-13 * normal_force.norm());
  EXPECT_EQ(t.force, e.force);  // the normal state is reported either way
}

TEST(RigidFrictionEvaluation, TangentIsTheDerivativeOfTheResidualInEveryBranch) {
  for (const FrictionScene& scene :
       {plane_scene(), cylinder_scene(), rounded_box_scene(), blended_box_scene()}) {
    const RigidFrictionEvaluation e = scene.evaluate(scene.x);
    EXPECT_TRUE(states(e).count(StickSlip::Stick) && states(e).count(StickSlip::Slip));
    EXPECT_LE(scene.tangent_error(), 1e-6);
    FrictionScene friction_only = scene;
    friction_only.with_normal = false;
    EXPECT_LE(friction_only.tangent_error(), 1e-6);
  }
  // Multipliers (p_N = ⟨λ − ε_N g⟩: node 0, above the plane by g ≈ 0.004 < λ/ε_N = 0.5,
  // sticks) and smoothing (p_N = ε_N P(g − λ/ε_N), every node in the band |g − λ/ε_N| < δ).
  FrictionScene augmented = plane_scene();
  augmented.multipliers = {200.0, 0.0, 50.0, 10.0};
  augmented.x[2] = augmented.xi_old[2] = 0.104;
  augmented.xi_old[0] = 0.0001;
  FrictionScene smoothed = augmented;
  smoothed.smoothing = 0.6;
  for (const FrictionScene& scene : {augmented, smoothed}) {
    const RigidFrictionEvaluation e = scene.evaluate(scene.x);
    EXPECT_GT(e.gap[0], 0);
    EXPECT_NE(e.state[0], static_cast<std::int8_t>(StickSlip::Open));
    EXPECT_EQ(e.elements.size(), 4u);
    EXPECT_LE(scene.tangent_error(), 1e-6);
  }
}

TEST(RigidFrictionEvaluation, MultipliersOnCurvedObstaclesHaveExactTangents) {
  // The augmented Lagrangian's multipliers on obstacles whose normal turns with the node:
  // stick and slip on the cylinder and on the circular and blended box roundings, with the
  // multiplier carrying part (or, open by the gap, all) of the pressure.
  for (FrictionScene scene : {cylinder_scene(), rounded_box_scene(), blended_box_scene()}) {
    scene.multipliers.assign(scene.area.size(), 0.0);
    for (std::size_t i = 0; i < scene.area.size(); ++i) scene.multipliers[i] = 20.0 + 15.0 * i;
    const RigidFrictionEvaluation e = scene.evaluate(scene.x);
    EXPECT_TRUE(states(e).count(StickSlip::Stick) && states(e).count(StickSlip::Slip));
    EXPECT_LE(scene.tangent_error(), 1e-6);
    FrictionScene smoothed = scene;
    smoothed.smoothing = 0.05;
    EXPECT_LE(smoothed.tangent_error(), 1e-6);
  }
}

TEST(RigidFrictionEvaluation, RejectsAHistoryOfTheWrongSize) {
  FrictionScene scene = plane_scene();
  scene.t_old.pop_back();
  EXPECT_THROW(scene.evaluate(scene.x), std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
