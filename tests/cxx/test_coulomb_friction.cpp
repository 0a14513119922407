// Coulomb friction: K_T = ∂r_T/∂x against central finite differences in every branch, the
// return map's cone, dissipation, a sliding sequence against its closed form, bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <hypercontact/coulomb_friction.hpp>
#include <hypercontact/obstacle.hpp>
#include <limits>
#include <random>
#include <stdexcept>

#include "finite_difference.hpp"

namespace hypercontact {
namespace {

using test::fd_jacobian;
using test::relative_error;

constexpr double area = 0.37;
constexpr double eps_n = 250.0;
constexpr double eps_t = 180.0;
constexpr double mu = 0.3;
const RigidPlane flat{{0, 0, 0}, {0, 0, 1}};
const RigidPlane tilted{{0.1, -0.2, 0.3}, Eigen::Vector3d(0.3, -0.2, 1.0).normalized()};

/// A curved obstacle (sphere of radius 1), to exercise the ∂n/∂x terms of the tangent.
ObstacleProjection project_to_sphere(const Eigen::Vector3d& x) {
  const Eigen::Vector3d d = x - Eigen::Vector3d(0.2, -0.1, -1.0);
  const double r = d.norm();
  const Eigen::Vector3d n = d / r;
  return {r - 1.0, n, (Eigen::Matrix3d::Identity() - n * n.transpose()) / r, Feature::Face};
}

/// Checks the branch taken and K_T against the FD Jacobian of r_T, projection x ↦ project_at(x).
template <typename Project>
void expect_exact_tangent_along(Project project_at, const Eigen::Vector3d& x,
                                const Eigen::Vector3d& xi_old, const Eigen::Vector3d& t_old,
                                StickSlip expected) {
  const auto residual = [&](const Eigen::Vector3d& y) {
    return coulomb_friction(project_at(y), y, xi_old, t_old, area, eps_n, eps_t, mu).residual;
  };
  const FrictionResult f =
      coulomb_friction(project_at(x), x, xi_old, t_old, area, eps_n, eps_t, mu);
  ASSERT_EQ(f.state, expected);
  EXPECT_LE(relative_error(fd_jacobian(residual, x), f.tangent), 1e-6);
}

void expect_exact_tangent(const RigidPlane& plane, const Eigen::Vector3d& x,
                          const Eigen::Vector3d& xi_old, const Eigen::Vector3d& t_old,
                          StickSlip expected) {
  expect_exact_tangent_along([&](const Eigen::Vector3d& y) { return project(plane, y); }, x, xi_old,
                             t_old, expected);
}

/// Unit tangent of `plane` at angle θ in its tangent plane.
Eigen::Vector3d tangent_direction(const RigidPlane& plane, double theta) {
  const Eigen::Vector3d a = plane.normal.unitOrthogonal();
  return std::cos(theta) * a + std::sin(theta) * plane.normal.cross(a);
}

TEST(CoulombFriction, StickOnFlatPlane) {
  const Eigen::Vector3d x(0.1, 0.2, -0.02);  // p_N = 5, μ p_N = 1.5
  const Eigen::Vector3d xi_old = x - Eigen::Vector3d(0.002, -0.001, 0.01);
  const FrictionResult f =
      coulomb_friction(project(flat, x), x, xi_old, {0, 0, 0}, area, eps_n, eps_t, mu);
  EXPECT_EQ(f.state, StickSlip::Stick);
  EXPECT_LE(relative_error(f.traction, Eigen::Vector3d(eps_t * 0.002, -eps_t * 0.001, 0)), 1e-12);
  EXPECT_EQ(f.residual, area * f.traction);
  EXPECT_EQ(f.slip_increment, Eigen::Vector3d::Zero());
  EXPECT_EQ(f.dissipation, 0.0);
  const Eigen::Matrix3d expected = area * eps_t * Eigen::Vector3d(1, 1, 0).asDiagonal();
  EXPECT_LE(relative_error(f.tangent, expected), 1e-15);
  expect_exact_tangent(flat, x, xi_old, {0, 0, 0}, StickSlip::Stick);
}

TEST(CoulombFriction, SlipSeveralDirectionsWithAndWithoutHistory) {
  for (const RigidPlane& plane : {flat, tilted}) {
    const Eigen::Vector3d x =
        plane.point + 0.3 * tangent_direction(plane, 0.4) - 0.02 * plane.normal;
    for (double theta : {0.0, 1.1, 2.5, 4.0, 5.5}) {
      const Eigen::Vector3d xi_old = x - 0.02 * tangent_direction(plane, theta);  // |t_trial| 3.6
      const Eigen::Vector3d t_old_tangential = 0.9 * tangent_direction(plane, theta + 2.0);
      for (const Eigen::Vector3d& t_old : {Eigen::Vector3d::Zero().eval(), t_old_tangential,
                                           (t_old_tangential + 0.4 * plane.normal).eval()}) {
        const FrictionResult f =
            coulomb_friction(project(plane, x), x, xi_old, t_old, area, eps_n, eps_t, mu);
        EXPECT_NEAR(f.traction.norm(), mu * eps_n * 0.02, 1e-12);
        EXPECT_NEAR(f.traction.dot(plane.normal), 0.0, 1e-12);
        expect_exact_tangent(plane, x, xi_old, t_old, StickSlip::Slip);
      }
    }
  }
}

TEST(CoulombFriction, StickOnTiltedPlaneWithHistory) {
  const Eigen::Vector3d x =
      tilted.point + 0.5 * tangent_direction(tilted, 0.2) - 0.03 * tilted.normal;
  const Eigen::Vector3d xi_old = x - 0.001 * tangent_direction(tilted, 0.7);
  const Eigen::Vector3d t_old = 0.5 * tangent_direction(tilted, 2.0) + 0.2 * tilted.normal;
  expect_exact_tangent(tilted, x, xi_old, t_old, StickSlip::Stick);
}

TEST(CoulombFriction, NearStickSlipTransitionBothSides) {
  const Eigen::Vector3d x =
      tilted.point + 0.2 * tangent_direction(tilted, 2.2) - 0.02 * tilted.normal;
  const Eigen::Vector3d t_old = 0.4 * tangent_direction(tilted, 1.0);
  const Eigen::Vector3d e = tangent_direction(tilted, 0.3);
  const double radius = mu * eps_n * 0.02;
  // Choose s ≥ 0 with |t_old + ε_T s e| = radius (1 ± 1e-3): Φ = ±1.5e-3, far above ε_T h.
  for (const auto& [factor, expected] :
       {std::pair{1 - 1e-3, StickSlip::Stick}, std::pair{1 + 1e-3, StickSlip::Slip}}) {
    const double b = t_old.dot(e), c = t_old.squaredNorm() - std::pow(factor * radius, 2);
    const double s = (-b + std::sqrt(b * b - c)) / eps_t;
    const Eigen::Vector3d xi_old = x - s * e;
    const FrictionResult f =
        coulomb_friction(project(tilted, x), x, xi_old, t_old, area, eps_n, eps_t, mu);
    EXPECT_NEAR(f.traction.norm(), std::min(factor, 1.0) * radius, 1e-12);
    expect_exact_tangent(tilted, x, xi_old, t_old, expected);
  }
}

TEST(CoulombFriction, CurvedObstacleStickAndSlip) {
  const Eigen::Vector3d x(0.4, 0.2, -0.1);
  ASSERT_LT(project_to_sphere(x).gap, -0.02);
  const Eigen::Vector3d t_old(0.3, -0.2, 0.5);  // has a normal component: projected
  expect_exact_tangent_along(project_to_sphere, x, x - Eigen::Vector3d(1e-3, 2e-3, 0), t_old,
                             StickSlip::Stick);
  expect_exact_tangent_along(project_to_sphere, x, x - Eigen::Vector3d(0.03, -0.02, 0.01), t_old,
                             StickSlip::Slip);
}

TEST(CoulombFriction, OpenIsZero) {
  const RigidBox box{{-1, -1, 0}, {1, 1, 0.4}};
  for (const ObstacleProjection& p :
       {project(tilted, tilted.point + 0.01 * tilted.normal), project(box, {1.05, 0.3, -0.02}),
        project(box, {1.03, -1.04, -0.02})}) {
    const Eigen::Vector3d x(0.3, 0.1, 0.2);
    const FrictionResult f =
        coulomb_friction(p, x, x - Eigen::Vector3d(0.1, 0, 0), {1, 2, 3}, area, eps_n, eps_t, mu);
    EXPECT_EQ(f.state, StickSlip::Open);
    EXPECT_EQ(f.residual, Eigen::Vector3d::Zero());
    EXPECT_EQ(f.tangent, Eigen::Matrix3d::Zero());
    EXPECT_EQ(f.traction, Eigen::Vector3d::Zero());
    EXPECT_EQ(f.slip_increment, Eigen::Vector3d::Zero());
    EXPECT_EQ(f.dissipation, 0.0);
  }
}

TEST(CoulombFriction, FrictionlessIsZero) {
  const Eigen::Vector3d x(0.1, 0.2, -0.02);
  for (const Eigen::Vector3d& xi_old : {x, (x - Eigen::Vector3d(0.01, 0, 0)).eval()}) {
    const FrictionResult f =
        coulomb_friction(project(flat, x), x, xi_old, {0, 0, 0}, area, eps_n, eps_t, 0.0);
    EXPECT_EQ(f.state, StickSlip::Slip);
    EXPECT_EQ(f.residual, Eigen::Vector3d::Zero());
    EXPECT_EQ(f.tangent, Eigen::Matrix3d::Zero());
    EXPECT_EQ(f.dissipation, 0.0);
    EXPECT_LE((f.slip_increment - (x - xi_old)).norm(), 1e-15);
  }
  const Eigen::Vector3d up(0.1, 0.2, 0.02);
  EXPECT_EQ(coulomb_friction(project(flat, up), up, x, {}, area, eps_n, eps_t, 0.0).state,
            StickSlip::Open);
}

TEST(CoulombReturnMap, ConeAndDirectionOverRandomStates) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int stick = 0, slip = 0;
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector3d t_trial(3 * u(rng), 3 * u(rng), 3 * u(rng));
    const double p_n = 5 * (1 + u(rng)), coefficient = 0.5 * (1 + u(rng));
    const double radius = coefficient * p_n;
    const auto [t, state] = return_map(t_trial, p_n, coefficient);
    EXPECT_LE(t.norm(), radius * (1 + 1e-12));
    if (state == StickSlip::Stick) {
      ++stick;
      EXPECT_LE(t_trial.norm(), radius);
      EXPECT_EQ(t, t_trial);
    } else {
      ++slip;
      ASSERT_EQ(state, StickSlip::Slip);
      EXPECT_GT(t_trial.norm(), radius);
      EXPECT_NEAR(t.norm(), radius, 1e-12 * std::max(1.0, radius));
      EXPECT_LE(t.cross(t_trial).norm(), 1e-12 * t.norm() * t_trial.norm());
      EXPECT_GE(t.dot(t_trial), 0.0);
    }
  }
  EXPECT_GT(stick, 500);
  EXPECT_GT(slip, 500);
}

TEST(CoulombFriction, DissipationOverRandomStates) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int slips = 0;
  for (int i = 0; i < 5000; ++i) {
    const RigidPlane plane{{u(rng), u(rng), u(rng)},
                           Eigen::Vector3d(u(rng), u(rng), 2 + u(rng)).normalized()};
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - plane.normal * plane.normal.transpose();
    const double gap = 0.05 * u(rng) - 0.04;  // about one state in ten open
    const Eigen::Vector3d x =
        plane.point + P * Eigen::Vector3d(u(rng), u(rng), u(rng)) + gap * plane.normal;
    const Eigen::Vector3d xi_old = x + 0.05 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const Eigen::Vector3d t_old(u(rng), u(rng), u(rng));
    const double coefficient = 0.5 * (1 + u(rng)), a = 1 + u(rng);
    const ObstacleProjection p = project(plane, x);
    const FrictionResult f = coulomb_friction(p, x, xi_old, t_old, a, eps_n, eps_t, coefficient);
    const double p_n = std::max(0.0, -eps_n * p.gap);
    const Eigen::Vector3d t_trial = P * (t_old + eps_t * (x - xi_old));
    EXPECT_GE(f.dissipation, 0.0);
    EXPECT_LE(f.traction.norm(), coefficient * p_n * (1 + 1e-12));
    EXPECT_NEAR(f.dissipation, a * f.traction.dot(f.slip_increment), 1e-12);
    switch (f.state) {
      case StickSlip::Open:
        EXPECT_EQ(f.dissipation, 0.0);
        break;
      case StickSlip::Stick:
        EXPECT_EQ(f.dissipation, 0.0);
        EXPECT_LE((f.traction - t_trial).norm(), 1e-12 * t_trial.norm());
        break;
      case StickSlip::Slip:
        ++slips;
        // Elastic plus slip: t_trial = t + ε_T Δs; D = A t·Δs = μ p_N |Δs| A.
        EXPECT_LE((f.traction + eps_t * f.slip_increment - t_trial).norm(), 1e-12 * t_trial.norm());
        EXPECT_NEAR(f.dissipation, coefficient * p_n * f.slip_increment.norm() * a, 1e-12);
        break;
    }
  }
  EXPECT_GT(slips, 500);
}

TEST(CoulombFriction, SlidingSequenceMatchesClosedForm) {
  // Fixed penetration δ, tangential displacement u_k = k Δu: stick while ε_T u_k < μ p_N, then
  // slide with |t| = μ p_N; total dissipation = μ p_N A (u_total − μ p_N/ε_T).
  const double depth = 0.02, du = 1e-3, p_n = eps_n * depth, radius = mu * p_n;
  const int steps = 50;
  const Eigen::Vector3d e = tangent_direction(tilted, 0.8);
  const Eigen::Vector3d x0 = tilted.point - depth * tilted.normal;
  Eigen::Vector3d xi_old = x0, t_old = Eigen::Vector3d::Zero();
  double dissipation = 0, slip = 0;
  for (int k = 1; k <= steps; ++k) {
    const Eigen::Vector3d x = x0 + k * du * e;
    const FrictionResult f =
        coulomb_friction(project(tilted, x), x, xi_old, t_old, area, eps_n, eps_t, mu);
    if (eps_t * k * du < radius) {
      EXPECT_EQ(f.state, StickSlip::Stick) << "step " << k;
      EXPECT_NEAR(f.traction.norm(), eps_t * k * du, 1e-12);
    } else {
      EXPECT_EQ(f.state, StickSlip::Slip) << "step " << k;
      EXPECT_NEAR(f.traction.norm(), radius, 1e-12 * radius);
    }
    EXPECT_GE(f.traction.dot(e), 0.0);  // −r_T opposes the motion
    dissipation += f.dissipation;
    slip += f.slip_increment.norm();
    xi_old = x;
    t_old = f.traction;
  }
  const double total_slip = steps * du - radius / eps_t;
  EXPECT_NEAR(slip, total_slip, 1e-12 * total_slip);
  EXPECT_NEAR(dissipation, radius * area * total_slip, 1e-12 * radius * area * total_slip);
}

TEST(CoulombFriction, RejectsBadInput) {
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d x(0.1, 0.2, -0.02), xi = x, t = Eigen::Vector3d::Zero();
  const ObstacleProjection p = project(flat, x);
  const auto call = [&](double a, double en, double et, double m) {
    return coulomb_friction(p, x, xi, t, a, en, et, m);
  };
  EXPECT_THROW(call(-1e-3, eps_n, eps_t, mu), std::invalid_argument);
  EXPECT_THROW(call(inf, eps_n, eps_t, mu), std::invalid_argument);
  EXPECT_THROW(call(area, 0.0, eps_t, mu), std::invalid_argument);
  EXPECT_THROW(call(area, eps_n, 0.0, mu), std::invalid_argument);
  EXPECT_THROW(call(area, eps_n, -1.0, mu), std::invalid_argument);
  EXPECT_THROW(call(area, eps_n, eps_t, -0.1), std::invalid_argument);
  EXPECT_THROW(call(area, eps_n, eps_t, nan), std::invalid_argument);
  const Eigen::Vector3d bad(0, nan, 0);
  EXPECT_THROW(coulomb_friction(p, bad, xi, t, area, eps_n, eps_t, mu), std::invalid_argument);
  EXPECT_THROW(coulomb_friction(p, x, bad, t, area, eps_n, eps_t, mu), std::invalid_argument);
  EXPECT_THROW(coulomb_friction(p, x, xi, bad, area, eps_n, eps_t, mu), std::invalid_argument);
  ObstacleProjection q = p;
  q.gap = nan;
  EXPECT_THROW(coulomb_friction(q, x, xi, t, area, eps_n, eps_t, mu), std::invalid_argument);
  EXPECT_THROW(return_map(bad, 1.0, mu), std::invalid_argument);
  EXPECT_THROW(return_map(t, -1.0, mu), std::invalid_argument);
  EXPECT_THROW(return_map(t, 1.0, -mu), std::invalid_argument);
  EXPECT_NO_THROW(call(0.0, eps_n, eps_t, mu));
}

}  // namespace
}  // namespace hypercontact
