#include <algorithm>
#include <array>
#include <cmath>
#include <hypercontact/rigid_box.hpp>
#include <limits>

namespace hypercontact {

namespace {

Feature feature_from_clamped(int num_clamped) {
  switch (num_clamped) {
    case 1:
      return Feature::Face;
    case 2:
      return Feature::Edge;
    default:
      return Feature::Vertex;
  }
}

/// d = x − c, rho = |d| > 0, clamped = D's diagonal (1 where x_i was clamped), r the radius.
ObstacleProjection project_from_outside(const Eigen::Vector3d& d, double rho,
                                        const Eigen::Vector3d& clamped, double r) {
  const Eigen::Vector3d n = d / rho;
  const Eigen::Matrix3d dn = (Eigen::Matrix3d(clamped.asDiagonal()) - n * n.transpose()) / rho;
  return {rho - r, n, dn, feature_from_clamped(static_cast<int>(clamped.sum()))};
}

/// Nearest face plane of a point inside or on the surface of the inner box [lo, hi] (the box's
/// [lo + r, hi − r]).
ObstacleProjection project_from_inside(const RigidBox& box, const Eigen::Vector3d& x) {
  // Face order (−z, +z, −x, +x, −y, +y) decides ties: the first minimum wins.
  constexpr std::array<int, 6> axis{2, 2, 0, 0, 1, 1};
  constexpr std::array<double, 6> sign{-1, 1, -1, 1, -1, 1};
  std::size_t best = 0;
  double best_distance = 0;
  for (std::size_t f = 0; f < 6; ++f) {
    const int a = axis[f];
    const double distance = sign[f] < 0 ? x[a] - box.lo[a] : box.hi[a] - x[a];
    if (f == 0 || distance < best_distance) {
      best = f;
      best_distance = distance;
    }
  }
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[axis[best]] = sign[best];
  // 0.0 − δ keeps a point exactly on the surface at g = +0 (and − r keeps it there with r = 0).
  return {0.0 - best_distance - box.radius, n, Eigen::Matrix3d::Zero(), Feature::Face};
}

/// y(λ) ∈ [0, e]: the root of y + 4λy³ = e for λ ≥ 0, e ≥ 0 (increasing and convex in y, so
/// Newton from y = e descends monotonically onto it).
double quartic_root(double e, double lambda) {
  double y = e;
  for (int it = 0; it < 200 && y > 0; ++it) {
    const double step = (y + 4 * lambda * y * y * y - e) / (1 + 12 * lambda * y * y);
    y -= step;
    if (!(step > 1e-16 * e)) break;
  }
  return std::max(y, 0.0);
}

/// The closest point y of the surface Σ yᵢ⁴ = a⁴ to e ≥ 0 with ρ₄ = (Σ eᵢ⁴)^¼ > a (computed
/// by the caller without over- or underflow), and its multiplier λ (yᵢ + 4λyᵢ³ = eᵢ). φ(λ) = Σ
/// yᵢ(λ)⁴ − a⁴ decreases from φ(0) > 0: Newton on λ, kept inside a bracket that every step narrows,
/// bisecting when Newton leaves it.
Eigen::Vector3d quartic_closest_point(const Eigen::Vector3d& e, double rho4, double a,
                                      double& lambda) {
  const double a4 = a * a * a * a;
  const Eigen::Vector3d radial = e * (a / rho4);
  lambda = (rho4 - a) / (4 * radial.array().pow(3).matrix().norm());  // a first guess
  double lo = 0, hi = std::numeric_limits<double>::infinity();
  Eigen::Vector3d y = e;
  for (int it = 0; it < 200; ++it) {
    for (int i = 0; i < 3; ++i) y[i] = quartic_root(e[i], lambda);
    const double phi = y.array().pow(4).sum() - a4;
    (phi > 0 ? lo : hi) = lambda;
    double dphi = 0;  // Σ 4yᵢ³ dyᵢ/dλ, dyᵢ/dλ = −4yᵢ³/(1 + 12λyᵢ²)
    for (int i = 0; i < 3; ++i) dphi -= 16 * std::pow(y[i], 6) / (1 + 12 * lambda * y[i] * y[i]);
    double next = dphi < 0 ? lambda - phi / dphi : lo;
    if (!(next > lo && next < hi))
      next = std::isfinite(hi) ? 0.5 * (lo + hi) : 2 * std::max(lo, lambda) + 1e-300;
    if (phi == 0 || !(std::abs(next - lambda) > 1e-15 * lambda)) break;
    lambda = next;
  }
  return y;
}

/// The blended rounding (project_to_box) for a point outside B with two or three clamped
/// coordinates: d = x − c, clamped = D's diagonal, r the radius.
ObstacleProjection project_blended(const Eigen::Vector3d& d, const Eigen::Vector3d& clamped,
                                   double r) {
  const double a = 0.5 * r;  // S's superellipse radius, and the offset
  const Eigen::Vector3d e = d.cwiseAbs();
  const Eigen::Vector3d s =
      (d.array() < 0).select(-Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones());
  const double emax = e.maxCoeff();
  const Eigen::Vector3d unit = e / emax;  // scaled: no over- or underflow in the fourth powers
  const double rho4 = emax * std::sqrt(std::sqrt(unit.array().pow(4).sum()));
  const Feature feature = feature_from_clamped(static_cast<int>(clamped.sum()));
  if (rho4 <= a) {  // deeper than r/2 into the rounding: the level set of ρ₄
    const Eigen::Vector3d cube = unit.array().pow(3);
    const Eigen::Vector3d nhat = cube / cube.norm();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - nhat * nhat.transpose();
    const Eigen::Matrix3d dn_de =
        P * Eigen::Matrix3d((3 * unit.array().square()).matrix().asDiagonal()) * P /
        (cube.norm() * emax);
    return {rho4 - r, s.cwiseProduct(nhat), s.asDiagonal() * dn_de * s.asDiagonal(), feature};
  }
  double lambda = 0;
  const Eigen::Vector3d y = quartic_closest_point(e, rho4, a, lambda);
  const Eigen::Vector3d b = 4 * y.array().pow(3);  // ∇(Σyᵢ⁴)
  const Eigen::Vector3d nhat = b / b.norm();
  // ∂y/∂e = A⁻¹ − A⁻¹b bᵀA⁻¹/(bᵀA⁻¹b), A = diag(1 + 12λyᵢ²): differentiating yᵢ + 4λyᵢ³ = eᵢ
  // and bᵀ dy = 0
  const Eigen::Vector3d Ainv_b = b.array() / (1 + 12 * lambda * y.array().square());
  Eigen::Matrix3d dy_de =
      Eigen::Matrix3d((1 / (1 + 12 * lambda * y.array().square())).matrix().asDiagonal());
  dy_de -= Ainv_b * Ainv_b.transpose() / b.dot(Ainv_b);
  const Eigen::Matrix3d dn_dy = (Eigen::Matrix3d::Identity() - nhat * nhat.transpose()) *
                                Eigen::Matrix3d((12 * y.array().square()).matrix().asDiagonal()) /
                                b.norm();
  const Eigen::Matrix3d dn_de = dn_dy * dy_de;
  return {(e - y).norm() - a, s.cwiseProduct(nhat), s.asDiagonal() * dn_de * s.asDiagonal(),
          feature};
}

}  // namespace

ObstacleProjection project_to_box(const RigidBox& box, const Eigen::Vector3d& x) {
  const double r = box.radius;
  // B = [lo + r, hi − r]; where 2r is the side (to round-off) B is flat: lo + r and hi − r meet
  // at the middle, never cross
  const Eigen::Array3d mid = 0.5 * (box.lo.array() + box.hi.array());
  const RigidBox inner{(box.lo.array() + r).min(mid).matrix(),
                       (box.hi.array() - r).max(mid).matrix(), r};
  const Eigen::Vector3d c = x.cwiseMax(inner.lo).cwiseMin(inner.hi);
  const Eigen::Vector3d d = x - c;
  const double rho = d.norm();
  if (rho > 0) {  // also false when |d|² underflows: such a point is treated as on B's surface
    const Eigen::Vector3d clamped = (x.array() != c.array()).cast<double>();
    if (box.blended && r > 0 && clamped.sum() > 1) return project_blended(d, clamped, r);
    return project_from_outside(d, rho, clamped, r);
  }
  return project_from_inside(inner, x);
}

}  // namespace hypercontact
