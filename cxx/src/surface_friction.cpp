#include <Eigen/Geometry>
#include <cmath>
#include <hypercontact/surface_friction.hpp>
#include <stdexcept>
#include <string>

#include "surface_kinematics.hpp"

namespace hypercontact {

namespace {

constexpr const char* who = "surface_friction";

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(std::string(who) + ": " + what);
}

void check_parameters(double w, double eps_n, double eps_t, double mu) {
  require(std::isfinite(w) && w >= 0, "w must be finite and >= 0, got " + std::to_string(w));
  require(std::isfinite(eps_n) && eps_n > 0,
          "eps_n must be finite and > 0, got " + std::to_string(eps_n));
  require(std::isfinite(eps_t) && eps_t > 0,
          "eps_t must be finite and > 0, got " + std::to_string(eps_t));
  require(std::isfinite(mu) && mu >= 0, "mu must be finite and >= 0, got " + std::to_string(mu));
}

void check_history(const NodeCoordinates& old_master, const Eigen::Vector2d& xi_old,
                   const Eigen::Vector3d& t_old) {
  require(old_master.cols() == 3 || old_master.cols() == 4,
          "the old facet has 3 or 4 nodes, got " + std::to_string(old_master.cols()));
  require(old_master.allFinite() && xi_old.allFinite() && t_old.allFinite(),
          "old facet coordinates, xi_old and t_old must be finite");
}

/// [v]× with [v]× u = v × u.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

SurfaceFriction surface_friction(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                                 const NodeCoordinates& master, const FacetProjection& projection,
                                 const NodeCoordinates& old_master, const Eigen::Vector2d& xi_old,
                                 const Eigen::Vector3d& t_old, double w, double eps_n, double eps_t,
                                 double mu, double lambda, double smoothing) {
  check_parameters(w, eps_n, eps_t, mu);
  require(std::isfinite(smoothing) && smoothing >= 0,
          "smoothing must be finite and >= 0, got " + std::to_string(smoothing));
  require(std::isfinite(lambda) && lambda >= 0,
          "the multiplier must be finite and >= 0, got " + std::to_string(lambda));
  check_history(old_master, xi_old, t_old);
  const detail::SurfaceKinematics k =
      detail::surface_kinematics(slave, weights, master, projection, who);
  const int no = static_cast<int>(old_master.cols());
  const int dofs = k.dofs, total = k.dofs + 3 * no;
  SurfaceFriction f{Eigen::VectorXd::Zero(total),
                    Eigen::MatrixXd::Zero(total, total),
                    Eigen::Vector3d::Zero(),
                    Eigen::Vector3d::Zero(),
                    0.0,
                    StickSlip::Open,
                    k.gap,
                    0.0,
                    k.normal,
                    projection.xi,
                    projection.feature,
                    projection.local_index};
  // Augmented (λ_N > 0): p_N = λ_N − ε_N g, open unless p_N > 0; smoothed: p_N = ε_N P(g − λ_N/ε_N).
  const NormalPressure np = normal_pressure(k.gap, eps_n, lambda, smoothing);
  if (!np.active) return f;

  const Eigen::Vector3d& n = k.normal;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d P_T = I - n * n.transpose();
  const double p_n = np.value;
  const Eigen::VectorXd N_old = facet_shape_functions(no, xi_old);
  const Eigen::Vector3d x_old = old_master * N_old;
  const Eigen::Vector3d v = t_old + eps_t * (k.x_s - x_old);
  const Eigen::Vector3d t_trial = P_T * v;
  const auto [t, state] = return_map(t_trial, p_n, mu);
  f.traction = t;
  f.state = state;
  f.pressure = p_n;
  f.slip_increment = (t_trial - t) / eps_t;  // zero in stick
  f.dissipation = mu * p_n * f.slip_increment.norm() * w;
  f.residual.head(dofs) = w * k.P.transpose() * t;
  if (mu == 0) return f;  // t ≡ 0: R = 0, K = 0

  // Derivatives w.r.t. y = [slave, current facet, old facet] (total columns).
  const detail::ProjectionDerivatives d = detail::projection_derivatives(k, who);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(2, total);  // dξ*/dy
  D.leftCols(dofs) = d.dxi_dx;
  Eigen::MatrixXd P_full = Eigen::MatrixXd::Zero(3, total);
  P_full.leftCols(dofs) = k.P;
  const Eigen::MatrixXd dr = P_full - k.a * D;
  std::array<Eigen::MatrixXd, 2> da;
  for (int alpha = 0; alpha < 2; ++alpha) {
    da[alpha] = k.x12 * D.row(1 - alpha);  // x_,11 = x_,22 = 0
    for (int a = 0; a < k.nm; ++a) da[alpha].middleCols<3>(3 * (k.ns + a)) += k.dN(a, alpha) * I;
  }
  const Eigen::MatrixXd dc = -cross_matrix(k.a.col(1)) * da[0] + cross_matrix(k.a.col(0)) * da[1];
  const Eigen::MatrixXd dn = (P_T / k.c.norm()) * dc;
  const Eigen::RowVectorXd dg = n.transpose() * dr + k.r.transpose() * dn;
  const Eigen::RowVectorXd dp = np.slope * dg;
  Eigen::MatrixXd dv = Eigen::MatrixXd::Zero(3, total);
  for (int i = 0; i < k.ns; ++i) dv.middleCols<3>(3 * i) = eps_t * weights[i] * I;
  for (int b = 0; b < no; ++b) dv.middleCols<3>(dofs + 3 * b) = -eps_t * N_old[b] * I;
  const Eigen::MatrixXd dt_trial = P_T * dv - n * (v.transpose() * dn) - n.dot(v) * dn;

  Eigen::MatrixXd dt;
  switch (state) {
    case StickSlip::Stick:
      dt = dt_trial;
      break;
    case StickSlip::Slip: {  // μ > 0 and Φ > 0 : |t_trial| > μ p_N ≥ 0, m is defined
      const double norm = t_trial.norm();
      const Eigen::Vector3d m = t_trial / norm;
      dt = mu * m * dp + (mu * p_n / norm) * (I - m * m.transpose()) * dt_trial;
      break;
    }
    case StickSlip::Open:
      throw std::logic_error("surface_friction: return_map never returns Open");
  }
  f.tangent.topRows(dofs) = w * (k.P.transpose() * dt);
  for (int alpha = 0; alpha < 2; ++alpha)
    f.tangent.topRows(dofs) += w * (k.P_xi[alpha].transpose() * t) * D.row(alpha);
  return f;
}

SurfaceFriction surface_friction(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                                 const NodeCoordinates& master, const NodeCoordinates& old_master,
                                 const Eigen::Vector2d& xi_old, const Eigen::Vector3d& t_old,
                                 double w, double eps_n, double eps_t, double mu, double lambda,
                                 double smoothing) {
  check_parameters(w, eps_n, eps_t, mu);
  require(weights.size() == slave.cols() && slave.allFinite() && weights.allFinite(),
          "slave coordinates and weights must be finite and as many");
  return surface_friction(slave, weights, master, project_to_facet(master, slave * weights),
                          old_master, xi_old, t_old, w, eps_n, eps_t, mu, lambda, smoothing);
}

}  // namespace hypercontact
