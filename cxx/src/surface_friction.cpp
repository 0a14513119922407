#include <Eigen/Geometry>
#include <cmath>
#include <hypercontact/surface_friction.hpp>
#include <span>
#include <stdexcept>
#include <string>

#include "surface_kinematics.hpp"

namespace hypercontact {

namespace {

constexpr const char* who = "surface_friction";

[[noreturn]] void invalid(const std::string& what) {
  throw std::invalid_argument(std::string(who) + ": " + what);
}

void check_parameters(double w, double eps_n, double eps_t, double mu) {
  if (!(std::isfinite(w) && w >= 0)) invalid("w must be finite and >= 0, got " + std::to_string(w));
  if (!(std::isfinite(eps_n) && eps_n > 0))
    invalid("eps_n must be finite and > 0, got " + std::to_string(eps_n));
  if (!(std::isfinite(eps_t) && eps_t > 0))
    invalid("eps_t must be finite and > 0, got " + std::to_string(eps_t));
  if (!(std::isfinite(mu) && mu >= 0))
    invalid("mu must be finite and >= 0, got " + std::to_string(mu));
}

void check_law(double lambda, double smoothing) {
  if (!(std::isfinite(smoothing) && smoothing >= 0))
    invalid("smoothing must be finite and >= 0, got " + std::to_string(smoothing));
  if (!(std::isfinite(lambda) && lambda >= 0))
    invalid("the multiplier must be finite and >= 0, got " + std::to_string(lambda));
}

/// [v]× with [v]× u = v × u.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// 3 × total and 1 × total blocks of derivatives w.r.t. y = [slave, current facet, old facet].
using Rows3 = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, max_friction_dofs>;
using Rows2 = Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::ColMajor, 2, max_friction_dofs>;
using Row = Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, max_friction_dofs>;

/// The return map's state at a closed point (surface_friction's notation).
struct TrialState {
  Eigen::Matrix3d P_T;      ///< I − n ⊗ n
  Eigen::Vector3d v;        ///< t_old + ε_T (x_s − x_old)
  Eigen::Vector3d t_trial;  ///< P_T v
  Eigen::Vector3d t;        ///< the returned traction
  StickSlip state;
  NormalPressure pressure;
};

/// dt/dy (3 × total) of the returned traction, and dξ*/dy (2 × total).
template <int NM>
Rows3 traction_derivative(const detail::SurfaceKinematics<NM>& k, const Rows2& D,
                          const SlaveWeights& weights, std::span<const double> N_old,
                          const TrialState& s, double eps_t, double mu) {
  const int dofs = k.dofs, total = static_cast<int>(D.cols());
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d& n = k.normal;
  Rows3 P_full = Rows3::Zero(3, total);
  P_full.leftCols(dofs) = k.P;
  const Rows3 dr = P_full - k.a * D;
  std::array<Rows3, 2> da;
  for (int alpha = 0; alpha < 2; ++alpha) {
    // da_α = x_,αβ dξ^β + Σ_a ∂N_a/∂ξ_α dx_a (bilinear and linear facets: x_,11 = x_,22 = 0)
    if constexpr (facet_is_quadratic<NM>)
      da[alpha] = k.xdd.col(alpha) * D.row(alpha) + k.xdd.col(2) * D.row(1 - alpha);
    else
      da[alpha] = k.xdd.col(2) * D.row(1 - alpha);
    for (int a = 0; a < NM; ++a)
      da[alpha].template middleCols<3>(3 * (k.ns + a)) += k.dN(a, alpha) * I;
  }
  const Rows3 dc = -cross_matrix(k.a.col(1)) * da[0] + cross_matrix(k.a.col(0)) * da[1];
  const Rows3 dn = (s.P_T / k.c.norm()) * dc;
  const Row dg = n.transpose() * dr + k.r.transpose() * dn;
  const Row dp = s.pressure.slope * dg;
  Rows3 dv = Rows3::Zero(3, total);
  for (int i = 0; i < k.ns; ++i) dv.template middleCols<3>(3 * i) = eps_t * weights[i] * I;
  for (std::size_t b = 0; b < N_old.size(); ++b)
    dv.template middleCols<3>(dofs + 3 * static_cast<int>(b)) = -eps_t * N_old[b] * I;
  const Rows3 dt_trial = s.P_T * dv - n * (s.v.transpose() * dn) - n.dot(s.v) * dn;
  switch (s.state) {
    case StickSlip::Stick:
      return dt_trial;
    case StickSlip::Slip: {  // μ > 0 and Φ > 0 : |t_trial| > μ p_N ≥ 0, m is defined
      const double norm = s.t_trial.norm();
      const Eigen::Vector3d m = s.t_trial / norm;
      return mu * m * dp + (mu * s.pressure.value / norm) * (I - m * m.transpose()) * dt_trial;
    }
    case StickSlip::Open:
      break;
  }
  throw std::logic_error("surface_friction: return_map never returns Open");
}

}  // namespace

template <int NM, int NO>
requires FacetNodeCount<NM> && FacetNodeCount<NO> SurfaceFriction
surface_friction(const SlaveNodes& slave, const SlaveWeights& weights, const FacetNodes<NM>& master,
                 const FacetProjection& projection, const FacetNodes<NO>& old_master,
                 const Eigen::Vector2d& xi_old, const Eigen::Vector3d& t_old, double w,
                 double eps_n, double eps_t, double mu, double lambda, double smoothing) {
  check_parameters(w, eps_n, eps_t, mu);
  check_law(lambda, smoothing);
  if (!(old_master.allFinite() && xi_old.allFinite() && t_old.allFinite()))
    invalid("old facet coordinates, xi_old and t_old must be finite");
  const detail::SurfaceKinematics<NM> k =
      detail::surface_kinematics<NM>(slave, weights, master, projection, who);
  const int dofs = k.dofs, total = k.dofs + 3 * NO;
  SurfaceFriction f{FrictionVector::Zero(total),
                    FrictionMatrix::Zero(total, total),
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
  // Augmented (λ_N > 0): p_N = λ_N − ε_N g, open unless p_N > 0; smoothed: p_N = ε_N P(g −
  // λ_N/ε_N).
  TrialState s;
  s.pressure = normal_pressure(k.gap, eps_n, lambda, smoothing);
  if (!s.pressure.active) return f;

  const Eigen::Vector3d& n = k.normal;
  s.P_T = Eigen::Matrix3d::Identity() - n * n.transpose();
  const Eigen::Matrix<double, NO, 1> N_old = facet_shape_functions<NO>(xi_old);
  const Eigen::Vector3d x_old = old_master * N_old;
  s.v = t_old + eps_t * (k.x_s - x_old);
  s.t_trial = s.P_T * s.v;
  const ReturnMapResult returned = return_map(s.t_trial, s.pressure.value, mu);
  s.t = returned.traction;
  s.state = returned.state;
  f.traction = s.t;
  f.state = s.state;
  f.pressure = s.pressure.value;
  f.slip_increment = (s.t_trial - s.t) / eps_t;  // zero in stick
  f.dissipation = mu * s.pressure.value * f.slip_increment.norm() * w;
  f.residual.head(dofs) = w * k.P.transpose() * s.t;
  if (mu == 0) return f;  // t ≡ 0: R = 0, K = 0

  // dR = w ([Pᵀ; 0] dt + [P_,αᵀ t; 0] dξ*^α), with y = [slave, current facet, old facet].
  const detail::ProjectionDerivatives<NM> d = detail::projection_derivatives<NM>(k, who);
  Rows2 D = Rows2::Zero(2, total);  // dξ*/dy
  D.leftCols(dofs) = d.dxi_dx;
  const Rows3 dt = traction_derivative<NM>(k, D, weights, {N_old.data(), NO}, s, eps_t, mu);
  f.tangent.topRows(dofs) = w * (k.P.transpose() * dt);
  for (int alpha = 0; alpha < 2; ++alpha)
    f.tangent.topRows(dofs) += w * (k.P_xi[alpha].transpose() * s.t) * D.row(alpha);
  return f;
}

#define HYPERCONTACT_SURFACE_FRICTION(NM, NO)                                                \
  template SurfaceFriction surface_friction<NM, NO>(                                         \
      const SlaveNodes&, const SlaveWeights&, const FacetNodes<NM>&, const FacetProjection&, \
      const FacetNodes<NO>&, const Eigen::Vector2d&, const Eigen::Vector3d&, double, double, \
      double, double, double, double);
HYPERCONTACT_SURFACE_FRICTION(3, 3)
HYPERCONTACT_SURFACE_FRICTION(3, 4)
HYPERCONTACT_SURFACE_FRICTION(4, 3)
HYPERCONTACT_SURFACE_FRICTION(4, 4)
HYPERCONTACT_SURFACE_FRICTION(6, 6)
HYPERCONTACT_SURFACE_FRICTION(9, 9)
#undef HYPERCONTACT_SURFACE_FRICTION

namespace {
template <int NM>
SurfaceFriction with_old_facet(const SlaveNodes& s, const SlaveWeights& M,
                               const FacetNodes<NM>& master, const FacetProjection& projection,
                               const NodeCoordinates& old_master, const Eigen::Vector2d& xi_old,
                               const Eigen::Vector3d& t_old, double w, double eps_n, double eps_t,
                               double mu, double lambda, double smoothing) {
  const int no = detail::facet_node_count(old_master, "surface_friction (old facet)");
  if constexpr (facet_is_quadratic<NM>) {  // a surface of curved facets: the old facet is alike
    if (no != NM)
      invalid("the old facet has " + std::to_string(no) + " nodes and the current one " +
              std::to_string(NM) + ": both must be facets of one surface");
    return surface_friction<NM, NM>(s, M, master, projection, FacetNodes<NM>(old_master), xi_old,
                                    t_old, w, eps_n, eps_t, mu, lambda, smoothing);
  } else {
    if (no == 3)
      return surface_friction<NM, 3>(s, M, master, projection, FacetNodes<3>(old_master), xi_old,
                                     t_old, w, eps_n, eps_t, mu, lambda, smoothing);
    if (no == 4)
      return surface_friction<NM, 4>(s, M, master, projection, FacetNodes<4>(old_master), xi_old,
                                     t_old, w, eps_n, eps_t, mu, lambda, smoothing);
    invalid("the old facet has " + std::to_string(no) + " nodes and the current one " +
            std::to_string(NM) + ": both must be facets of one surface");
  }
}
}  // namespace

SurfaceFriction surface_friction(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                                 const NodeCoordinates& master, const FacetProjection& projection,
                                 const NodeCoordinates& old_master, const Eigen::Vector2d& xi_old,
                                 const Eigen::Vector3d& t_old, double w, double eps_n, double eps_t,
                                 double mu, double lambda, double smoothing) {
  check_parameters(w, eps_n, eps_t, mu);
  const SlaveNodes s = detail::bounded_slave(slave, weights, who);
  const SlaveWeights M = weights;
  switch (detail::facet_node_count(master, who)) {
    case 3:
      return with_old_facet<3>(s, M, FacetNodes<3>(master), projection, old_master, xi_old, t_old,
                               w, eps_n, eps_t, mu, lambda, smoothing);
    case 4:
      return with_old_facet<4>(s, M, FacetNodes<4>(master), projection, old_master, xi_old, t_old,
                               w, eps_n, eps_t, mu, lambda, smoothing);
    case 6:
      return with_old_facet<6>(s, M, FacetNodes<6>(master), projection, old_master, xi_old, t_old,
                               w, eps_n, eps_t, mu, lambda, smoothing);
    default:
      return with_old_facet<9>(s, M, FacetNodes<9>(master), projection, old_master, xi_old, t_old,
                               w, eps_n, eps_t, mu, lambda, smoothing);
  }
}

SurfaceFriction surface_friction(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                                 const NodeCoordinates& master, const NodeCoordinates& old_master,
                                 const Eigen::Vector2d& xi_old, const Eigen::Vector3d& t_old,
                                 double w, double eps_n, double eps_t, double mu, double lambda,
                                 double smoothing) {
  check_parameters(w, eps_n, eps_t, mu);
  detail::bounded_slave(slave, weights, who);
  return surface_friction(slave, weights, master, project_to_facet(master, slave * weights),
                          old_master, xi_old, t_old, w, eps_n, eps_t, mu, lambda, smoothing);
}

}  // namespace hypercontact
