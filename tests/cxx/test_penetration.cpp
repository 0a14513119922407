// Smoothed normal law (penetration.hpp): P, P', Q and normal_pressure against their closed forms
// and central finite differences, continuity at g = ±δ; the rigid-obstacle kernels with
// smoothing δ > 0 (normal_penalty on plane, box face/edge/corner, cylinder; evaluate_rigid_contact
// with multipliers; coulomb_friction in stick and slip, flat and curved) against central finite
// differences in every region of the law; δ = 0 bit-identical to the call without the argument;
// invalid smoothing rejected.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <hypercontact/coulomb_friction.hpp>
#include <hypercontact/normal_penalty.hpp>
#include <hypercontact/obstacle.hpp>
#include <hypercontact/penetration.hpp>
#include <hypercontact/rigid_contact.hpp>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "finite_difference.hpp"

namespace hypercontact {
namespace {

using test::fd_gradient;
using test::fd_jacobian;
using test::relative_error;

constexpr double area = 0.37;
constexpr double eps_n = 250.0;
constexpr double eps_t = 180.0;
constexpr double mu = 0.3;
/// Band half-width of the geometric tests: every FD point below is ≥ 10⁴ steps from g = ±δ.
constexpr double delta = 0.05;

/// The tests' own smoothed bracket (closed form of the header), and its energy.
double expected_P(double g, double d) {
  if (g <= -d) return -g;
  if (g >= d) return 0.0;
  return (d - g) * (d - g) / (4 * d);
}
double expected_slope(double g, double d) {
  if (g <= -d) return -1.0;
  if (g >= d) return 0.0;
  return -(d - g) / (2 * d);
}
double macaulay(double g) { return std::max(0.0, -g); }

// --- The law itself ------------------------------------------------------------------------------

TEST(Penetration, ContinuousAtTheBandEdges) {
  for (double d : {1e-3, 0.05, 0.7}) {
    SCOPED_TRACE("delta = " + std::to_string(d));
    for (double edge : {-d, d}) {
      const double below = std::nextafter(edge, -1.0), above = std::nextafter(edge, 1.0);
      const Penetration a = penetration(below, d), b = penetration(above, d),
                        at = penetration(edge, d);
      EXPECT_NEAR(a.value, b.value, 1e-12);
      EXPECT_NEAR(a.slope, b.slope, 1e-12);
      EXPECT_NEAR(at.value, a.value, 1e-12);
      EXPECT_NEAR(at.slope, b.slope, 1e-12);
      EXPECT_NEAR(penetration_energy(below, d), penetration_energy(above, d), 1e-12);
      // One-sided slopes of P from outside and inside the band agree with P' there.
      const double h = 1e-7 * d;
      EXPECT_NEAR((penetration(edge, d).value - penetration(edge - h, d).value) / h, at.slope,
                  1e-6);
      EXPECT_NEAR((penetration(edge + h, d).value - penetration(edge, d).value) / h, at.slope,
                  1e-6);
    }
    EXPECT_EQ(penetration(d, d).value, 0.0);
    EXPECT_EQ(penetration(d, d).slope, 0.0);
    EXPECT_EQ(penetration(-d, d).value, d);
    EXPECT_EQ(penetration(-d, d).slope, -1.0);
  }
}

TEST(Penetration, SlopeAndEnergyAgainstFiniteDifferences) {
  const double h = 1e-6;
  for (double g : {-0.3, -0.08, -0.03, -0.01, 0.0, 0.02, 0.04, 0.07, 0.3}) {
    SCOPED_TRACE("g = " + std::to_string(g));
    const Penetration p = penetration(g, delta);
    EXPECT_NEAR((penetration(g + h, delta).value - penetration(g - h, delta).value) / (2 * h),
                p.slope, 1e-8);
    // Q' = −P.
    EXPECT_NEAR(
        (penetration_energy(g + h, delta) - penetration_energy(g - h, delta)) / (2 * h), -p.value,
        1e-8);
    EXPECT_NEAR(p.value, expected_P(g, delta), 1e-15);
    EXPECT_NEAR(p.slope, expected_slope(g, delta), 1e-15);
    EXPECT_GE(p.slope, -1.0);
    EXPECT_LE(p.slope, 0.0);
    EXPECT_GE(penetration_energy(g, delta), 0.0);
  }
  // Closed forms of Q in the three regions.
  EXPECT_NEAR(penetration_energy(-0.3, delta), 0.5 * 0.09 + delta * delta / 6, 1e-15);
  EXPECT_NEAR(penetration_energy(0.01, delta), std::pow(delta - 0.01, 3) / (12 * delta), 1e-15);
  EXPECT_EQ(penetration_energy(0.3, delta), 0.0);
}

TEST(Penetration, MacaulayOutsideTheBandAboveItInside) {
  for (double g : {-2.0, -0.3, -0.05000001, 0.05, 0.0500001, 0.4, 7.0}) {
    EXPECT_EQ(penetration(g, delta).value, macaulay(g)) << "g = " << g;
    EXPECT_EQ(penetration(g, delta).slope, g < 0 ? -1.0 : 0.0) << "g = " << g;
  }
  double largest = -1, at = 1;
  for (int i = -999; i <= 999; ++i) {
    const double g = delta * i / 1000.0;
    const double excess = penetration(g, delta).value - macaulay(g);
    EXPECT_GE(excess, 0.0) << "g = " << g;
    EXPECT_LE(excess, delta / 4 * (1 + 1e-15)) << "g = " << g;
    if (excess > largest) largest = excess, at = g;
  }
  EXPECT_EQ(at, 0.0);
  EXPECT_DOUBLE_EQ(penetration(0.0, delta).value, delta / 4);
  EXPECT_DOUBLE_EQ(penetration(0.0, delta).slope, -0.5);
}

TEST(Penetration, ZeroSmoothingIsTheMacaulayBracketClosedAtZero) {
  for (double g : {-1.0, -1e-300, 0.0, 1e-300, 0.5}) {
    const Penetration p = penetration(g, 0.0);
    EXPECT_EQ(p.value, macaulay(g)) << "g = " << g;
    EXPECT_EQ(p.slope, g <= 0 ? -1.0 : 0.0) << "g = " << g;
    EXPECT_EQ(penetration_active(g, 0.0), g <= 0) << "g = " << g;
    EXPECT_EQ(penetration_energy(g, 0.0), 0.5 * macaulay(g) * macaulay(g)) << "g = " << g;
  }
  EXPECT_TRUE(penetration_active(0.0, 0.0));
  EXPECT_TRUE(penetration_active(0.0499, delta));
  EXPECT_FALSE(penetration_active(delta, delta));
}

TEST(Penetration, NormalPressureWithAMultiplier) {
  const double lambda = 3.0;  // λ/ε_N = 0.012
  for (double g : {-0.2, -0.01, 0.0, 0.005, 0.0119, 0.0121, 0.05}) {
    SCOPED_TRACE("g = " + std::to_string(g));
    // δ = 0: ⟨λ − ε_N g⟩ exactly.
    const NormalPressure p0 = normal_pressure(g, eps_n, lambda, 0.0);
    EXPECT_EQ(p0.value, std::max(0.0, lambda - eps_n * g));
    EXPECT_EQ(p0.active, lambda - eps_n * g > 0);
    EXPECT_EQ(p0.slope, p0.active ? -eps_n : 0.0);
    // δ > 0: ε_N P(g − λ/ε_N).
    const NormalPressure p = normal_pressure(g, eps_n, lambda, delta);
    const double s = g - lambda / eps_n;
    EXPECT_EQ(p.value, eps_n * penetration(s, delta).value);
    EXPECT_EQ(p.slope, eps_n * penetration(s, delta).slope);
    EXPECT_NEAR(p.value, eps_n * expected_P(s, delta), 1e-12);
    EXPECT_TRUE(p.active);  // g < λ/ε_N + δ = 0.062 for every g here
  }
  // Active up to g < λ/ε_N + δ, inactive from there on.
  const double edge = lambda / eps_n + delta;
  EXPECT_TRUE(normal_pressure(edge - 1e-9, eps_n, lambda, delta).active);
  EXPECT_GT(normal_pressure(edge - 1e-4, eps_n, lambda, delta).value, 0.0);
  for (double g : {edge + 1e-9, edge + 0.01, 1.0}) {
    const NormalPressure p = normal_pressure(g, eps_n, lambda, delta);
    EXPECT_FALSE(p.active) << "g = " << g;
    EXPECT_EQ(p.value, 0.0);
    EXPECT_EQ(p.slope, 0.0);
  }
  // λ = 0, δ = 0: the penalty, closed at g = 0.
  EXPECT_TRUE(normal_pressure(0.0, eps_n, 0.0, 0.0).active);
  EXPECT_EQ(normal_pressure(0.0, eps_n, 0.0, 0.0).slope, -eps_n);
  EXPECT_FALSE(normal_pressure(1e-12, eps_n, 0.0, 0.0).active);
  // dp/dg by FD, δ > 0.
  const double h = 1e-7;
  for (double g : {-0.1, 0.0, 0.03, 0.055}) {
    const double fd = (normal_pressure(g + h, eps_n, lambda, delta).value -
                       normal_pressure(g - h, eps_n, lambda, delta).value) /
                      (2 * h);
    EXPECT_NEAR(fd, normal_pressure(g, eps_n, lambda, delta).slope, 1e-6 * eps_n) << "g = " << g;
  }
}

TEST(Penetration, InvalidSmoothingThrows) {
  const ObstacleProjection p = project(RigidPlane{{0, 0, 0}, {0, 0, 1}}, {0, 0, -0.1});
  const Eigen::Vector3d x(0, 0, -0.1);
  const std::vector<double> xs{0, 0, -0.1}, a{area}, lam{1.0};
  for (double bad : {-1e-3, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    SCOPED_TRACE("smoothing = " + std::to_string(bad));
    EXPECT_THROW(normal_penalty(p, area, eps_n, bad), std::invalid_argument);
    EXPECT_THROW(normal_penalty_energy(p, area, eps_n, bad), std::invalid_argument);
    EXPECT_THROW(coulomb_friction(p, x, x, {0, 0, 0}, area, eps_n, eps_t, mu, bad),
                 std::invalid_argument);
    EXPECT_THROW(evaluate_rigid_contact(RigidPlane{{0, 0, 0}, {0, 0, 1}}, xs, a, eps_n, {}, bad),
                 std::invalid_argument);
    EXPECT_THROW(evaluate_rigid_contact(RigidPlane{{0, 0, 0}, {0, 0, 1}}, xs, a, eps_n, lam, bad),
                 std::invalid_argument);
  }
  // Invalid smoothing is rejected also where the contact is open.
  const ObstacleProjection open = project(RigidPlane{{0, 0, 0}, {0, 0, 1}}, {0, 0, 0.5});
  EXPECT_THROW(normal_penalty(open, area, eps_n, -1.0), std::invalid_argument);
  EXPECT_THROW(coulomb_friction(open, x, x, {0, 0, 0}, area, eps_n, eps_t, mu, std::nan("")),
               std::invalid_argument);
  EXPECT_NO_THROW(normal_penalty(p, area, eps_n, 0.0));
  EXPECT_NO_THROW(normal_penalty(p, area, eps_n, delta));
}

// --- normal_penalty with δ > 0 -------------------------------------------------------------------

/// Gaps of the four regions of the law: below the band, in it (closed, open), above it.
constexpr double g_closed = -0.08, g_band_closed = -0.02, g_band_open = 0.03, g_inactive = 0.07;

/// Active: p_N = ε_N P(g); r against FD of W, K against FD of r; x ↦ project_at(x).
template <typename Project>
void expect_smoothed_derivatives_along(Project project_at, const Eigen::Vector3d& x,
                                       double expected_gap) {
  const ObstacleProjection p = project_at(x);
  ASSERT_NEAR(p.gap, expected_gap, 1e-12);
  const auto energy = [&](const Eigen::Vector3d& y) {
    return normal_penalty_energy(project_at(y), area, eps_n, delta);
  };
  const auto residual = [&](const Eigen::Vector3d& y) {
    return normal_penalty(project_at(y), area, eps_n, delta).residual;
  };
  const NodalContact c = normal_penalty(p, area, eps_n, delta);
  ASSERT_TRUE(c.closed);
  EXPECT_NEAR(c.pressure, eps_n * expected_P(p.gap, delta), 1e-12 * eps_n);
  EXPECT_GT(c.pressure, 0.0);
  // The force pushes the node out along n: r = −A ε_N P n.
  EXPECT_LE((c.residual + area * c.pressure * p.normal).norm(), 1e-12 * area * c.pressure);
  EXPECT_LE(relative_error(fd_gradient(energy, x), c.residual), 1e-6);
  EXPECT_LE(relative_error(fd_jacobian(residual, x), c.tangent), 1e-6);
}

template <typename Project>
void expect_smoothed_inactive_along(Project project_at, const Eigen::Vector3d& x) {
  const ObstacleProjection p = project_at(x);
  ASSERT_GE(p.gap, delta);
  const NodalContact c = normal_penalty(p, area, eps_n, delta);
  EXPECT_FALSE(c.closed);
  EXPECT_EQ(c.residual, Eigen::Vector3d::Zero());
  EXPECT_EQ(c.tangent, Eigen::Matrix3d::Zero());
  EXPECT_EQ(c.pressure, 0.0);
  EXPECT_EQ(normal_penalty_energy(p, area, eps_n, delta), 0.0);
}

template <typename O>
auto projector(const O& obstacle) {
  return [obstacle](const Eigen::Vector3d& y) { return project(Obstacle{obstacle}, y); };
}

const RigidPlane tilted{{0.1, -0.2, 0.3}, Eigen::Vector3d(0.3, -0.2, 1.0).normalized()};
const RigidBox box{{-1, -1, 0}, {1, 1, 0.4}};
const RigidCylinder cylinder{{0.2, -0.1, -1.0}, Eigen::Vector3d(0.2, 1.0, 0.1).normalized(), 0.8};

/// A point of gap g off the cylinder: radially out from the axis point at parameter t.
Eigen::Vector3d cylinder_point(double t, double angle, double g) {
  const Eigen::Vector3d a = cylinder.axis, u = a.unitOrthogonal(), v = a.cross(u);
  return cylinder.point + t * a + (cylinder.radius + g) * (std::cos(angle) * u + std::sin(angle) * v);
}

TEST(SmoothedNormalPenalty, TiltedPlaneEveryRegion) {
  const Eigen::Vector3d base = tilted.point + Eigen::Vector3d(0.5, 0.4, 0.2) -
                               Eigen::Vector3d(0.5, 0.4, 0.2).dot(tilted.normal) * tilted.normal;
  for (double g : {g_closed, g_band_closed, g_band_open}) {
    SCOPED_TRACE("g = " + std::to_string(g));
    expect_smoothed_derivatives_along(projector(tilted), base + g * tilted.normal, g);
  }
  expect_smoothed_inactive_along(projector(tilted), base + g_inactive * tilted.normal);
  // Closed forms: below the band the plain penalty plus the constant δ²/6 in the energy.
  const ObstacleProjection p = project(tilted, base + g_closed * tilted.normal);
  EXPECT_NEAR(normal_penalty_energy(p, area, eps_n, delta),
              area * eps_n * (0.5 * g_closed * g_closed + delta * delta / 6), 1e-12);
  const NodalContact c = normal_penalty(p, area, eps_n, delta);
  EXPECT_LE(relative_error(c.residual, normal_penalty(p, area, eps_n).residual), 1e-12);
  EXPECT_LE(relative_error(c.tangent, normal_penalty(p, area, eps_n).tangent), 1e-12);
  // In the band the stiffness is A ε_N (−P') n ⊗ n with −P' = (δ − g)/(2δ) < 1.
  const ObstacleProjection q = project(tilted, base + g_band_open * tilted.normal);
  const Eigen::Matrix3d expected = area * eps_n * (delta - g_band_open) / (2 * delta) *
                                   tilted.normal * tilted.normal.transpose();
  EXPECT_LE(relative_error(normal_penalty(q, area, eps_n, delta).tangent, expected), 1e-12);
}

TEST(SmoothedNormalPenalty, BoxFacesInside) {
  // Bottom face closest (0.02 / 0.08 deep); +x side wall closest (0.02 deep).
  for (const auto& [x, gap, normal] :
       {std::tuple{Eigen::Vector3d(0.9, 0.2, 0.02), g_band_closed, Eigen::Vector3d(0, 0, -1)},
        std::tuple{Eigen::Vector3d(0.5, 0.2, 0.08), g_closed, Eigen::Vector3d(0, 0, -1)},
        std::tuple{Eigen::Vector3d(0.98, 0.1, 0.2), g_band_closed, Eigen::Vector3d(1, 0, 0)}}) {
    SCOPED_TRACE("g = " + std::to_string(gap));
    const ObstacleProjection p = project(box, x);
    EXPECT_EQ(p.feature, Feature::Face);
    EXPECT_EQ(p.normal, normal);
    expect_smoothed_derivatives_along(projector(box), x, gap);
  }
}

TEST(SmoothedNormalPenalty, BoxOutsideFaceEdgeCornerInTheBand) {
  // Open geometrically (0 < g < δ) but active: on an edge and at a corner the ∂n/∂x = (…)/g
  // term is multiplied by P(g) > 0.
  const double g = g_band_open;  // 0.03
  for (const auto& [x, feature] :
       {std::pair{Eigen::Vector3d(0.5, 0.5, -g), Feature::Face},
        std::pair{Eigen::Vector3d(1.018, 0.3, -0.024), Feature::Edge},
        std::pair{Eigen::Vector3d(1.01, -1.02, -0.02), Feature::Vertex}}) {
    SCOPED_TRACE("feature " + std::to_string(static_cast<int>(feature)));
    const ObstacleProjection p = project(box, x);
    EXPECT_EQ(p.feature, feature);
    expect_smoothed_derivatives_along(projector(box), x, g);
    if (feature != Feature::Face) EXPECT_GT(p.dnormal_dx.norm(), 1.0);
  }
  // Further out (g = 0.07 > δ): inactive.
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.5, 0.5, -0.07), Eigen::Vector3d(1.042, 0.3, -0.056),
                                   Eigen::Vector3d(1.02, -1.04, -0.05)})
    expect_smoothed_inactive_along(projector(box), x);
}

TEST(SmoothedNormalPenalty, CylinderEveryRegion) {
  for (double g : {g_closed, g_band_closed, g_band_open}) {
    SCOPED_TRACE("g = " + std::to_string(g));
    expect_smoothed_derivatives_along(projector(cylinder), cylinder_point(0.3, 1.2, g), g);
  }
  expect_smoothed_inactive_along(projector(cylinder), cylinder_point(0.3, 1.2, g_inactive));
}

TEST(SmoothedNormalPenalty, AugmentedMultiplierThroughRigidContact) {
  // p_N = ε_N P(g − λ/ε_N), W = A ε_N Q(g − λ/ε_N) with λ fixed; here λ/ε_N = 0.04, so active up
  // to g < 0.09.
  const Obstacle obstacle = box;
  const double lambda = 10.0, shift = lambda / eps_n;
  const std::vector<double> lam{lambda}, a{area};
  const auto node = [&](const Eigen::Vector3d& y) {
    const std::vector<double> v(y.data(), y.data() + 3);
    return evaluate_rigid_contact(obstacle, v, a, eps_n, lam, delta)[0];
  };
  const auto energy = [&](const Eigen::Vector3d& y) {
    return area * eps_n * penetration_energy(node(y).projection.gap - shift, delta);
  };
  const auto residual = [&](const Eigen::Vector3d& y) {
    return Eigen::Vector3d(node(y).contact.residual);
  };
  // Shifted gaps g − λ/ε_N: −0.08 (face, inside), −0.02 (face, outside), +0.03 (edge), +0.03
  // (corner), −0.02 (edge).
  for (const auto& [x, shifted] :
       {std::pair{Eigen::Vector3d(0.5, 0.2, 0.04), -0.08},
        std::pair{Eigen::Vector3d(0.5, 0.2, -0.02), -0.02},
        std::pair{Eigen::Vector3d(1.042, 0.3, -0.056), 0.03},
        std::pair{Eigen::Vector3d(1.02, -1.03, -0.06), 0.03},
        std::pair{Eigen::Vector3d(1.012, 0.3, -0.016), -0.02}}) {
    SCOPED_TRACE("shifted gap " + std::to_string(shifted));
    const RigidContactNode n = node(x);
    ASSERT_NEAR(n.projection.gap - shift, shifted, 1e-12);
    ASSERT_TRUE(n.contact.closed);
    EXPECT_NEAR(n.contact.pressure, eps_n * expected_P(shifted, delta), 1e-12 * eps_n);
    EXPECT_LE(relative_error(fd_gradient(energy, x), n.contact.residual), 1e-6);
    EXPECT_LE(relative_error(fd_jacobian(residual, x), n.contact.tangent), 1e-6);
  }
  // g − λ/ε_N = 0.06 > δ: inactive.
  const RigidContactNode far = node(Eigen::Vector3d(0.5, 0.2, -0.1));
  EXPECT_FALSE(far.contact.closed);
  EXPECT_EQ(far.contact.residual, Eigen::Vector3d::Zero());
  EXPECT_EQ(far.contact.tangent, Eigen::Matrix3d::Zero());
  // Without multipliers, evaluate_rigid_contact is normal_penalty with δ.
  const std::vector<double> v{0.9, 0.2, 0.02};
  const RigidContactNode plain = evaluate_rigid_contact(obstacle, v, a, eps_n, {}, delta)[0];
  const NodalContact direct = normal_penalty(project(obstacle, {0.9, 0.2, 0.02}), area, eps_n, delta);
  EXPECT_EQ(plain.contact.residual, direct.residual);
  EXPECT_EQ(plain.contact.tangent, direct.tangent);
}

TEST(SmoothedNormalPenalty, ZeroSmoothingIsBitIdentical) {
  std::vector<ObstacleProjection> projections;
  for (double g : {-0.08, -0.02, 0.0, 0.03})
    projections.push_back(project(cylinder, cylinder_point(0.3, 1.2, g)));
  projections.push_back(project(box, {1.018, 0.3, -0.024}));
  projections.push_back(project(box, {0.9, 0.2, 0.02}));
  for (const ObstacleProjection& p : projections) {
    const NodalContact a = normal_penalty(p, area, eps_n), b = normal_penalty(p, area, eps_n, 0.0);
    EXPECT_EQ(a.residual, b.residual);
    EXPECT_EQ(a.tangent, b.tangent);
    EXPECT_EQ(a.pressure, b.pressure);
    EXPECT_EQ(a.closed, b.closed);
    EXPECT_EQ(normal_penalty_energy(p, area, eps_n), normal_penalty_energy(p, area, eps_n, 0.0));
  }
  const Obstacle obstacle = box;
  const std::vector<double> x{0.9, 0.2, 0.02, 1.012, 0.3, -0.016, 0.5, 0.2, -0.1}, a{0.3, 0.2, 0.1},
      lam{10.0, 10.0, 10.0};
  for (const std::vector<double>& l : {std::vector<double>{}, lam}) {
    const auto r0 = evaluate_rigid_contact(obstacle, x, a, eps_n, l);
    const auto r1 = evaluate_rigid_contact(obstacle, x, a, eps_n, l, 0.0);
    ASSERT_EQ(r0.size(), r1.size());
    for (std::size_t i = 0; i < r0.size(); ++i) {
      EXPECT_EQ(r0[i].contact.residual, r1[i].contact.residual);
      EXPECT_EQ(r0[i].contact.tangent, r1[i].contact.tangent);
      EXPECT_EQ(r0[i].contact.closed, r1[i].contact.closed);
    }
  }
}

// --- coulomb_friction with δ > 0 -----------------------------------------------------------------

/// State and pressure, and K_T against the FD Jacobian of r_T with the history fixed.
template <typename Project>
FrictionResult expect_smoothed_friction_along(Project project_at, const Eigen::Vector3d& x,
                                              const Eigen::Vector3d& xi_old,
                                              const Eigen::Vector3d& t_old, StickSlip expected) {
  const auto residual = [&](const Eigen::Vector3d& y) {
    return coulomb_friction(project_at(y), y, xi_old, t_old, area, eps_n, eps_t, mu, delta)
        .residual;
  };
  const ObstacleProjection p = project_at(x);
  const FrictionResult f = coulomb_friction(p, x, xi_old, t_old, area, eps_n, eps_t, mu, delta);
  EXPECT_EQ(f.state, expected);
  const double p_n = eps_n * expected_P(p.gap, delta);
  EXPECT_LE(f.traction.norm(), mu * p_n * (1 + 1e-12));
  if (expected == StickSlip::Slip) EXPECT_NEAR(f.traction.norm(), mu * p_n, 1e-12 * mu * p_n);
  EXPECT_NEAR(f.dissipation, area * f.traction.dot(f.slip_increment), 1e-12);
  EXPECT_LE(relative_error(fd_jacobian(residual, x), f.tangent), 1e-6);
  return f;
}

TEST(SmoothedCoulombFriction, FlatPlaneStickAndSlipEveryRegion) {
  const RigidPlane flat{{0, 0, 0}, {0, 0, 1}};
  const Eigen::Vector3d e = Eigen::Vector3d(0.6, -0.8, 0);
  for (double g : {g_closed, g_band_closed, g_band_open}) {
    SCOPED_TRACE("g = " + std::to_string(g));
    const Eigen::Vector3d x(0.1, 0.2, g);
    const double radius = mu * eps_n * expected_P(g, delta);  // 6, 1.84, 0.15
    // Stick: |t_trial| = 0.3 radius; slip: 3 radius (plus a normal offset of ξ_old, dropped).
    const Eigen::Vector3d stick_old = x - 0.3 * radius / eps_t * e + Eigen::Vector3d(0, 0, 0.01);
    const Eigen::Vector3d slip_old = x - 3 * radius / eps_t * e + Eigen::Vector3d(0, 0, 0.01);
    const FrictionResult stick =
        expect_smoothed_friction_along(projector(flat), x, stick_old, {0, 0, 0}, StickSlip::Stick);
    EXPECT_LE((stick.traction - 0.3 * radius * e).norm(), 1e-10 * radius);
    const FrictionResult slip = expect_smoothed_friction_along(
        projector(flat), x, slip_old, Eigen::Vector3d(0.1 * radius, 0.05 * radius, 0.3),
        StickSlip::Slip);
    // In slip the tangent carries μ m ⊗ ∂p_N/∂x, ∂p_N/∂x = ε_N P'(g) n: column z.
    EXPECT_LE((slip.tangent.col(2) - area * mu * eps_n * expected_slope(g, delta) *
                                         slip.traction.normalized())
                  .norm(),
              1e-10 * slip.tangent.norm());
  }
  // Above the band: open.
  const Eigen::Vector3d up(0.1, 0.2, g_inactive);
  const FrictionResult open = coulomb_friction(project(flat, up), up, up - Eigen::Vector3d(0.1, 0, 0),
                                               {1, 2, 3}, area, eps_n, eps_t, mu, delta);
  EXPECT_EQ(open.state, StickSlip::Open);
  EXPECT_EQ(open.residual, Eigen::Vector3d::Zero());
  EXPECT_EQ(open.tangent, Eigen::Matrix3d::Zero());
  EXPECT_EQ(open.traction, Eigen::Vector3d::Zero());
}

TEST(SmoothedCoulombFriction, TiltedPlaneAndCylinderStickAndSlipEveryRegion) {
  const Eigen::Vector3d t_old(0.03, -0.02, 0.05);  // has a normal component: projected
  for (double g : {g_closed, g_band_closed, g_band_open}) {
    SCOPED_TRACE("g = " + std::to_string(g));
    const double radius = mu * eps_n * expected_P(g, delta);
    const Eigen::Vector3d xc = cylinder_point(0.3, 1.2, g);
    const Eigen::Vector3d n = project(cylinder, xc).normal;
    const Eigen::Vector3d e = n.cross(cylinder.axis).normalized();  // around the cylinder
    const Eigen::Vector3d d = (0.5 * e + cylinder.axis).normalized();
    expect_smoothed_friction_along(projector(cylinder), xc, xc - 0.2 * radius / eps_t * d, t_old,
                                   StickSlip::Stick);
    expect_smoothed_friction_along(projector(cylinder), xc, xc - 4 * radius / eps_t * d, t_old,
                                   StickSlip::Slip);
    const Eigen::Vector3d base = tilted.point + Eigen::Vector3d(0.5, 0.4, 0.2) -
                                 Eigen::Vector3d(0.5, 0.4, 0.2).dot(tilted.normal) * tilted.normal;
    const Eigen::Vector3d xp = base + g * tilted.normal;
    const Eigen::Vector3d ep = tilted.normal.unitOrthogonal();
    expect_smoothed_friction_along(projector(tilted), xp, xp - 0.2 * radius / eps_t * ep, t_old,
                                   StickSlip::Stick);
    expect_smoothed_friction_along(projector(tilted), xp, xp - 4 * radius / eps_t * ep, t_old,
                                   StickSlip::Slip);
  }
  const Eigen::Vector3d xc = cylinder_point(0.3, 1.2, g_inactive);
  EXPECT_EQ(coulomb_friction(project(cylinder, xc), xc, xc, t_old, area, eps_n, eps_t, mu, delta)
                .state,
            StickSlip::Open);
}

TEST(SmoothedCoulombFriction, ZeroSmoothingIsBitIdentical) {
  const Eigen::Vector3d t_old(0.3, -0.2, 0.5);
  for (double g : {-0.08, -0.02, 0.0, 0.03}) {
    const Eigen::Vector3d x = cylinder_point(0.3, 1.2, g);
    const ObstacleProjection p = project(cylinder, x);
    for (const Eigen::Vector3d& xi_old :
         {(x - Eigen::Vector3d(1e-3, 2e-3, 0)).eval(), (x - Eigen::Vector3d(0.03, -0.02, 0.01)).eval()}) {
      const FrictionResult a = coulomb_friction(p, x, xi_old, t_old, area, eps_n, eps_t, mu);
      const FrictionResult b = coulomb_friction(p, x, xi_old, t_old, area, eps_n, eps_t, mu, 0.0);
      EXPECT_EQ(a.state, b.state);
      EXPECT_EQ(a.residual, b.residual);
      EXPECT_EQ(a.tangent, b.tangent);
      EXPECT_EQ(a.traction, b.traction);
      EXPECT_EQ(a.slip_increment, b.slip_increment);
      EXPECT_EQ(a.dissipation, b.dissipation);
    }
  }
}

}  // namespace
}  // namespace hypercontact
