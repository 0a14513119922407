#include <array>
#include <hypercontact/rigid_box.hpp>

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
    return project_from_outside(d, rho, clamped, r);
  }
  return project_from_inside(inner, x);
}

}  // namespace hypercontact
