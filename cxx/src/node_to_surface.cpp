#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <hypercontact/node_to_surface.hpp>
#include <stdexcept>
#include <string>

#include "surface_kinematics.hpp"

namespace hypercontact {

namespace {

void check_parameters(double w, double eps_n, const char* who) {
  if (!(std::isfinite(w) && w >= 0))
    throw std::invalid_argument(std::string(who) + ": w must be finite and >= 0, got " +
                                std::to_string(w));
  if (!(std::isfinite(eps_n) && eps_n > 0))
    throw std::invalid_argument(std::string(who) + ": eps_n must be finite and > 0, got " +
                                std::to_string(eps_n));
}

void check_smoothing(double smoothing, const char* who) {
  if (!(std::isfinite(smoothing) && smoothing >= 0))
    throw std::invalid_argument(std::string(who) + ": smoothing must be finite and >= 0, got " +
                                std::to_string(smoothing));
}

void check_multiplier(double lambda, const char* who) {
  if (!(std::isfinite(lambda) && lambda >= 0))
    throw std::invalid_argument(std::string(who) +
                                ": the multiplier must be finite and >= 0, got " +
                                std::to_string(lambda));
}

/// ĝ: g on the face; off it s |r| with s = −1 if g ≤ 0, else +1 (φ* = ½ ĝ²). `along` is the unit
/// vector e with ∇ĝ = Pᵀ e: n on the face, s r/|r| off it (n if r = 0 there: a subgradient).
struct SignedDistance {
  double value;
  Eigen::Vector3d along;
  double distance;  ///< |r| (0 on the face: not used there)
};

template <int NM>
SignedDistance signed_distance(const detail::SurfaceKinematics<NM>& k) {
  if (k.T.cols() == 2) return {k.gap, k.normal, 0.0};
  const double d = k.r.norm();
  const double s = k.gap <= 0 ? -1.0 : 1.0;
  if (!(d > 0)) return {0.0, k.normal, 0.0};
  return {s * d, (s / d) * k.r, d};
}

template <int NM>
struct SignedDistanceDerivatives {
  static constexpr int max_dofs = detail::SurfaceKinematics<NM>::max_dofs;
  BoundedVector<max_dofs> gradient;  ///< ∇ĝ = Pᵀ e
  BoundedMatrix<max_dofs> hessian;   ///< ∇²ĝ, symmetric
};

/// ∇ĝ and ∇²ĝ at x (derivatives over all 3 (ns + nm) coordinates).
/// Face (ĝ = g, r = g n, φ* = ½ g², so g ∇²g = ∇²φ* − ∇g ∇gᵀ): with A = Pᵀ a (dofs × 2),
/// C_α = P_,αᵀ n, M = aᵀa, κ_αβ = n·x_,αβ, H = M − g κ, B = g C − A and
/// ∇²φ* = PᵀP − B H⁻¹ Bᵀ, PᵀP − Pᵀ n nᵀ P = A M⁻¹ Aᵀ and M⁻¹ − H⁻¹ = −g M⁻¹ κ H⁻¹ give, with no
/// division by g (κ_αβ = n·x_,αβ),  ∇²g = −A M⁻¹ κ H⁻¹ Aᵀ + C H⁻¹ Aᵀ + A H⁻¹ Cᵀ − g C H⁻¹ Cᵀ.
/// Edge, vertex (ĝ = s |r| = s √(2 φ*)): ∇²ĝ = s (∇²φ* − Pᵀ r̂ r̂ᵀ P)/|r|, r̂ = r/|r|, with
/// ∇²φ* = PᵀP + B dξ*/dx (node_to_surface's penalty tangent over w ε_N); 0 if r = 0.
template <int NM>
SignedDistanceDerivatives<NM> signed_distance_derivatives(
    const detail::SurfaceKinematics<NM>& k, const detail::ProjectionDerivatives<NM>& d,
    const SignedDistance& sd) {
  constexpr int max_dofs = detail::SurfaceKinematics<NM>::max_dofs;
  using DofsBy2 = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::ColMajor, max_dofs, 2>;
  using DofMatrix = BoundedMatrix<max_dofs>;
  SignedDistanceDerivatives<NM> out;
  out.gradient = k.P.transpose() * sd.along;
  if (k.T.cols() == 2) {
    const Eigen::Vector3d& n = k.normal;
    const DofsBy2 A = k.P.transpose() * k.a;
    DofsBy2 C(k.dofs, 2);
    for (int alpha = 0; alpha < 2; ++alpha) C.col(alpha) = k.P_xi[alpha].transpose() * n;
    const Eigen::Matrix2d M = k.a.transpose() * k.a;
    Eigen::Matrix2d kappa;  // n·x_,αβ (bilinear: only the mixed term)
    kappa << n.dot(k.xdd.col(0)), n.dot(k.xdd.col(2)), n.dot(k.xdd.col(2)), n.dot(k.xdd.col(1));
    const Eigen::Matrix2d H = M - k.gap * kappa;
    const Eigen::Matrix2d Hinv = H.inverse(), Minv = M.inverse();
    const DofMatrix hess = -A * (Minv * kappa * Hinv) * A.transpose() + C * Hinv * A.transpose() +
                           A * Hinv * C.transpose() - k.gap * C * Hinv * C.transpose();
    out.hessian = 0.5 * (hess + hess.transpose());
    return out;
  }
  if (!(sd.distance > 0)) {
    out.hessian.setZero(k.dofs, k.dofs);
    return out;
  }
  const Eigen::Vector3d r_hat = k.r / sd.distance;
  const BoundedVector<max_dofs> Pr = k.P.transpose() * r_hat;
  const double s = sd.value < 0 ? -1.0 : 1.0;
  const DofMatrix hess =
      (s / sd.distance) * (k.P.transpose() * k.P + d.B * d.dxi_dx - Pr * Pr.transpose());
  out.hessian = 0.5 * (hess + hess.transpose());
  return out;
}

/// W of node_to_surface_energy at the kinematics k.
template <int NM>
double energy(const detail::SurfaceKinematics<NM>& k, double w, double eps_n, double touch,
              double lambda, double smoothing, const char* who) {
  if (!(touch >= 0)) throw std::invalid_argument(std::string(who) + ": touch must be >= 0");
  if (smoothing > 0)
    return w * eps_n * penetration_energy(signed_distance(k).value - lambda / eps_n, smoothing);
  if (lambda > 0) {
    const double p = std::max(0.0, lambda - eps_n * signed_distance(k).value);
    return 0.5 * w * p * p / eps_n;
  }
  if (k.gap > touch) return 0.0;
  return 0.5 * w * eps_n * k.r.squaredNorm();
}

}  // namespace

template <int NM>
requires FacetNodeCount<NM> SurfaceContact node_to_surface(const SlaveNodes& slave,
                                                           const SlaveWeights& weights,
                                                           const FacetNodes<NM>& master,
                                                           const FacetProjection& projection,
                                                           double w, double eps_n, double touch,
                                                           double lambda, double smoothing) {
  constexpr const char* who = "node_to_surface";
  check_smoothing(smoothing, who);
  check_parameters(w, eps_n, who);
  check_multiplier(lambda, who);
  const detail::SurfaceKinematics<NM> k =
      detail::surface_kinematics<NM>(slave, weights, master, projection, who);
  SurfaceContact result{ElementVector::Zero(k.dofs),
                        ElementMatrix::Zero(k.dofs, k.dofs),
                        k.gap,
                        0.0,
                        k.normal,
                        projection.xi,
                        projection.feature,
                        projection.local_index,
                        false};
  if (!(touch >= 0)) throw std::invalid_argument(std::string(who) + ": touch must be >= 0");
  if (lambda > 0 || smoothing > 0) {  // augmented Lagrangian and/or smoothed penalty
    const SignedDistance sd = signed_distance(k);
    const NormalPressure np = normal_pressure(sd.value, eps_n, lambda, smoothing);
    if (!np.active) return result;  // open
    const double p = np.value;
    const detail::ProjectionDerivatives<NM> d = detail::projection_derivatives<NM>(k, who);
    const SignedDistanceDerivatives<NM> dd = signed_distance_derivatives<NM>(k, d, sd);
    result.residual = -w * p * dd.gradient;
    const BoundedMatrix<detail::SurfaceKinematics<NM>::max_dofs> K =
        -w * np.slope * dd.gradient * dd.gradient.transpose() - w * p * dd.hessian;
    result.tangent = 0.5 * (K + K.transpose());
    result.pressure = p;
    result.closed = true;
    return result;
  }
  if (k.gap > touch) return result;
  const detail::ProjectionDerivatives<NM> d = detail::projection_derivatives<NM>(k, who);
  const double scale = w * eps_n;
  result.residual = scale * k.P.transpose() * k.r;
  // K = w ε_N [PᵀP − B T (TᵀHT)⁻¹ Tᵀ Bᵀ] = w ε_N [PᵀP + B dξ*/dx], symmetrised against rounding.
  const BoundedMatrix<detail::SurfaceKinematics<NM>::max_dofs> K =
      scale * (k.P.transpose() * k.P + d.B * d.dxi_dx);
  result.tangent = 0.5 * (K + K.transpose());
  result.pressure = eps_n * std::max(0.0, -k.gap);
  result.closed = true;
  return result;
}

template SurfaceContact node_to_surface<3>(const SlaveNodes&, const SlaveWeights&,
                                           const FacetNodes<3>&, const FacetProjection&, double,
                                           double, double, double, double);
template SurfaceContact node_to_surface<4>(const SlaveNodes&, const SlaveWeights&,
                                           const FacetNodes<4>&, const FacetProjection&, double,
                                           double, double, double, double);
template SurfaceContact node_to_surface<6>(const SlaveNodes&, const SlaveWeights&,
                                           const FacetNodes<6>&, const FacetProjection&, double,
                                           double, double, double, double);
template SurfaceContact node_to_surface<9>(const SlaveNodes&, const SlaveWeights&,
                                           const FacetNodes<9>&, const FacetProjection&, double,
                                           double, double, double, double);

SurfaceContact node_to_surface(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                               const NodeCoordinates& master, const FacetProjection& projection,
                               double w, double eps_n, double touch, double lambda,
                               double smoothing) {
  constexpr const char* who = "node_to_surface";
  const SlaveNodes s = detail::bounded_slave(slave, weights, who);
  const SlaveWeights M = weights;
  switch (detail::facet_node_count(master, who)) {
    case 3:
      return node_to_surface<3>(s, M, FacetNodes<3>(master), projection, w, eps_n, touch, lambda,
                                smoothing);
    case 4:
      return node_to_surface<4>(s, M, FacetNodes<4>(master), projection, w, eps_n, touch, lambda,
                                smoothing);
    case 6:
      return node_to_surface<6>(s, M, FacetNodes<6>(master), projection, w, eps_n, touch, lambda,
                                smoothing);
    default:
      return node_to_surface<9>(s, M, FacetNodes<9>(master), projection, w, eps_n, touch, lambda,
                                smoothing);
  }
}

SurfaceContact node_to_surface(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                               const NodeCoordinates& master, double w, double eps_n, double lambda,
                               double smoothing) {
  check_parameters(w, eps_n, "node_to_surface");
  detail::bounded_slave(slave, weights, "node_to_surface");
  return node_to_surface(slave, weights, master, project_to_facet(master, slave * weights), w,
                         eps_n, 0.0, lambda, smoothing);
}

double node_to_surface_energy(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                              const NodeCoordinates& master, double w, double eps_n, double touch,
                              double lambda, double smoothing) {
  constexpr const char* who = "node_to_surface_energy";
  check_smoothing(smoothing, who);
  check_parameters(w, eps_n, who);
  check_multiplier(lambda, who);
  const SlaveNodes s = detail::bounded_slave(slave, weights, who);
  const FacetProjection p = project_to_facet(master, slave * weights);
  switch (detail::facet_node_count(master, who)) {
    case 3:
      return energy<3>(detail::surface_kinematics<3>(s, weights, master, p, who), w, eps_n, touch,
                       lambda, smoothing, who);
    case 4:
      return energy<4>(detail::surface_kinematics<4>(s, weights, master, p, who), w, eps_n, touch,
                       lambda, smoothing, who);
    case 6:
      return energy<6>(detail::surface_kinematics<6>(s, weights, master, p, who), w, eps_n, touch,
                       lambda, smoothing, who);
    default:
      return energy<9>(detail::surface_kinematics<9>(s, weights, master, p, who), w, eps_n, touch,
                       lambda, smoothing, who);
  }
}

}  // namespace hypercontact
