#include <cmath>
#include <hypercontact/coulomb_friction.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {
/// Throws std::invalid_argument unless ok; the message is built only then.
template <typename Message>
void require(bool ok, Message what) {
  if (!ok) throw std::invalid_argument("coulomb_friction: " + std::string(what()));
}

void check_parameters(double area, double eps_n, double eps_t, double mu) {
  require(std::isfinite(area) && area >= 0,
          [&] { return "area must be finite and >= 0, got " + std::to_string(area); });
  require(std::isfinite(eps_n) && eps_n > 0,
          [&] { return "eps_n must be finite and > 0, got " + std::to_string(eps_n); });
  require(std::isfinite(eps_t) && eps_t > 0,
          [&] { return "eps_t must be finite and > 0, got " + std::to_string(eps_t); });
  require(std::isfinite(mu) && mu >= 0,
          [&] { return "mu must be finite and >= 0, got " + std::to_string(mu); });
}
}  // namespace

ReturnMapResult return_map(const Eigen::Vector3d& t_trial, double p_n, double mu) {
  require(t_trial.allFinite(), [&] { return "t_trial must be finite"; });
  require(std::isfinite(p_n) && p_n >= 0,
          [&] { return "p_n must be finite and >= 0, got " + std::to_string(p_n); });
  require(std::isfinite(mu) && mu >= 0,
          [&] { return "mu must be finite and >= 0, got " + std::to_string(mu); });
  if (mu == 0) return {Eigen::Vector3d::Zero(), StickSlip::Slip};
  const double norm = t_trial.norm();
  if (norm - mu * p_n <= 0) return {t_trial, StickSlip::Stick};
  return {(mu * p_n / norm) * t_trial, StickSlip::Slip};
}

FrictionResult coulomb_friction(const ObstacleProjection& p, const Eigen::Vector3d& x,
                                const Eigen::Vector3d& xi_old, const Eigen::Vector3d& t_old,
                                double area, double eps_n, double eps_t, double mu,
                                double smoothing) {
  check_parameters(area, eps_n, eps_t, mu);
  require(std::isfinite(smoothing) && smoothing >= 0,
          [&] { return "smoothing must be finite and >= 0, got " + std::to_string(smoothing); });
  require(std::isfinite(p.gap) && p.normal.allFinite() && p.dnormal_dx.allFinite(),
          [&] { return "projection must be finite"; });
  require(x.allFinite() && xi_old.allFinite() && t_old.allFinite(),
          [&] { return "x, xi_old and t_old must be finite"; });
  if (!penetration_active(p.gap, smoothing))
    return {Eigen::Vector3d::Zero(),
            Eigen::Matrix3d::Zero(),
            Eigen::Vector3d::Zero(),
            Eigen::Vector3d::Zero(),
            0.0,
            StickSlip::Open};

  const Eigen::Vector3d& n = p.normal;
  const Eigen::Matrix3d& dn = p.dnormal_dx;
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
  const Penetration pen = penetration(p.gap, smoothing);
  const double p_n = eps_n * pen.value;
  const Eigen::Vector3d w = t_old + eps_t * (x - xi_old);
  const Eigen::Vector3d t_trial = P * w;
  // T = ∂t_trial/∂x, including the turning of the tangent plane with n on curved obstacles.
  const Eigen::Matrix3d T = eps_t * P - n.dot(w) * dn - n * (dn.transpose() * w).transpose();

  const auto [t, state] = return_map(t_trial, p_n, mu);
  const Eigen::Vector3d slip = (t_trial - t) / eps_t;  // zero in stick; along m in slip
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
  switch (state) {
    case StickSlip::Stick:
      K = area * T;
      break;
    case StickSlip::Slip:
      if (mu > 0) {  // Φ > 0 with μ > 0 implies |t_trial| > μ p_N ≥ 0: m is defined.
        const double norm = t_trial.norm();
        const Eigen::Vector3d m = t_trial / norm;
        const Eigen::Vector3d dp_n = (eps_n * pen.slope) * n;
        K = area * mu *
            (m * dp_n.transpose() +
             (p_n / norm) * (Eigen::Matrix3d::Identity() - m * m.transpose()) * T);
      }
      break;
    case StickSlip::Open:
      throw std::logic_error("coulomb_friction: return_map never returns Open");
  }
  return {area * t, K, t, slip, mu * p_n * slip.norm() * area, state};
}

}  // namespace hypercontact
