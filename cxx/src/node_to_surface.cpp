#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <hypercontact/node_to_surface.hpp>
#include <stdexcept>
#include <string>

#include "surface_kinematics.hpp"

namespace hypercontact {

namespace detail {

SurfaceKinematics surface_kinematics(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                                     const NodeCoordinates& master,
                                     const FacetProjection& projection, const char* who) {
  const std::string name(who);
  if (slave.cols() < 1) throw std::invalid_argument(name + ": at least one slave node is needed");
  if (weights.size() != slave.cols())
    throw std::invalid_argument(name + ": " + std::to_string(weights.size()) +
                                " slave weights for " + std::to_string(slave.cols()) +
                                " slave nodes");
  if (master.cols() != 3 && master.cols() != 4)
    throw std::invalid_argument(name + ": a master facet has 3 or 4 nodes, got " +
                                std::to_string(master.cols()));
  if (!slave.allFinite() || !weights.allFinite() || !master.allFinite())
    throw std::invalid_argument(name + ": slave coordinates, weights and master coordinates " +
                                "must be finite");
  if (!projection.xi.allFinite())
    throw std::invalid_argument(name + ": the projection's xi must be finite");
  SurfaceKinematics k;
  k.ns = static_cast<int>(slave.cols());
  k.nm = static_cast<int>(master.cols());
  k.dofs = 3 * (k.ns + k.nm);
  const int nm = k.nm;
  if (projection.feature != Feature::Face &&
      (projection.local_index < 0 || projection.local_index >= nm))
    throw std::invalid_argument(
        name + ": the projection's local index " + std::to_string(projection.local_index) +
        " is not an edge or vertex of a facet of " + std::to_string(nm) + " nodes");
  const Eigen::Vector2d& xi = projection.xi;
  k.normal = facet_normal(master, xi);  // throws on a degenerate or folded facet
  k.N = facet_shape_functions(nm, xi);
  k.dN = facet_shape_derivatives(nm, xi);
  k.d2N = facet_shape_mixed_derivatives(nm);
  k.x_s = slave * weights;
  k.r = k.x_s - master * k.N;
  k.a = master * k.dN;
  k.x12 = master * k.d2N;
  k.c = k.a.col(0).cross(k.a.col(1));
  k.gap = k.r.dot(k.normal);

  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  k.P = Eigen::MatrixXd::Zero(3, k.dofs);
  for (int i = 0; i < k.ns; ++i) k.P.block<3, 3>(0, 3 * i) = weights[i] * I;
  for (int a = 0; a < nm; ++a) k.P.block<3, 3>(0, 3 * (k.ns + a)) = -k.N[a] * I;
  for (int alpha = 0; alpha < 2; ++alpha) {
    k.P_xi[alpha] = Eigen::MatrixXd::Zero(3, k.dofs);
    for (int a = 0; a < nm; ++a) k.P_xi[alpha].block<3, 3>(0, 3 * (k.ns + a)) = -k.dN(a, alpha) * I;
  }
  switch (projection.feature) {
    case Feature::Face:
      k.T = Eigen::MatrixXd::Identity(2, 2);
      break;
    case Feature::Edge:
      k.T = facet_vertex_xi(nm, projection.local_index + 1) -
            facet_vertex_xi(nm, projection.local_index);
      break;
    case Feature::Vertex:
      k.T = Eigen::MatrixXd::Zero(2, 0);
      break;
  }
  return k;
}

ProjectionDerivatives projection_derivatives(const SurfaceKinematics& k, const char* who) {
  ProjectionDerivatives d;
  d.B.resize(k.dofs, 2);
  for (int alpha = 0; alpha < 2; ++alpha)
    d.B.col(alpha) = k.P_xi[alpha].transpose() * k.r - k.P.transpose() * k.a.col(alpha);
  d.dxi_dx = Eigen::MatrixXd::Zero(2, k.dofs);
  if (k.T.cols() == 0) return d;  // vertex: ξ* fixed

  const Eigen::Matrix2d metric = k.a.transpose() * k.a;
  Eigen::Matrix2d H = metric;
  H(0, 1) -= k.r.dot(k.x12);
  H(1, 0) = H(0, 1);
  const Eigen::MatrixXd Ht = k.T.transpose() * H * k.T;
  const Eigen::MatrixXd Mt = k.T.transpose() * metric * k.T;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Ht, Eigen::EigenvaluesOnly);
  const double smallest = eig.eigenvalues().minCoeff();
  if (!(smallest > 1e-10 * Mt.trace()))
    throw std::runtime_error(
        std::string(who) +
        ": the slave point is at a centre of curvature of the master facet (the Hessian of the "
        "distance in xi is not positive definite: smallest eigenvalue " +
        std::to_string(smallest) + "); the contact tangent does not exist there");
  d.dxi_dx = -k.T * Ht.llt().solve(k.T.transpose() * d.B.transpose());
  return d;
}

}  // namespace detail

namespace {

void check_parameters(double w, double eps_n, const char* who) {
  if (!(std::isfinite(w) && w >= 0))
    throw std::invalid_argument(std::string(who) + ": w must be finite and >= 0, got " +
                                std::to_string(w));
  if (!(std::isfinite(eps_n) && eps_n > 0))
    throw std::invalid_argument(std::string(who) + ": eps_n must be finite and > 0, got " +
                                std::to_string(eps_n));
}

int rank(Feature f) { return f == Feature::Face ? 0 : f == Feature::Edge ? 1 : 2; }

void check_smoothing(double smoothing, const char* who) {
  if (!(std::isfinite(smoothing) && smoothing >= 0))
    throw std::invalid_argument(std::string(who) + ": smoothing must be finite and >= 0, got " +
                                std::to_string(smoothing));
}

void check_multiplier(double lambda, const char* who) {
  if (!(std::isfinite(lambda) && lambda >= 0))
    throw std::invalid_argument(std::string(who) + ": the multiplier must be finite and >= 0, got " +
                                std::to_string(lambda));
}

/// ĝ: g on the face; off it s |r| with s = −1 if g ≤ 0, else +1 (φ* = ½ ĝ²). `along` is the unit
/// vector e with ∇ĝ = Pᵀ e: n on the face, s r/|r| off it (n if r = 0 there: a subgradient).
struct SignedDistance {
  double value;
  Eigen::Vector3d along;
  double distance;  ///< |r| (0 on the face: not used there)
};

SignedDistance signed_distance(const detail::SurfaceKinematics& k) {
  if (k.T.cols() == 2) return {k.gap, k.normal, 0.0};
  const double d = k.r.norm();
  const double s = k.gap <= 0 ? -1.0 : 1.0;
  if (!(d > 0)) return {0.0, k.normal, 0.0};
  return {s * d, (s / d) * k.r, d};
}

struct SignedDistanceDerivatives {
  Eigen::VectorXd gradient;  ///< ∇ĝ = Pᵀ e
  Eigen::MatrixXd hessian;   ///< ∇²ĝ, symmetric
};

/// ∇ĝ and ∇²ĝ at x (derivatives over all 3 (ns + nm) coordinates).
/// Face (ĝ = g, r = g n, φ* = ½ g², so g ∇²g = ∇²φ* − ∇g ∇gᵀ): with A = Pᵀ a (dofs × 2),
/// C_α = P_,αᵀ n, M = aᵀa, κ = [0 n·x_,12; n·x_,12 0], H = M − g κ, B = g C − A and
/// ∇²φ* = PᵀP − B H⁻¹ Bᵀ, PᵀP − Pᵀ n nᵀ P = A M⁻¹ Aᵀ and M⁻¹ − H⁻¹ = −g M⁻¹ κ H⁻¹ give, with no
/// division by g,  ∇²g = −A M⁻¹ κ H⁻¹ Aᵀ + C H⁻¹ Aᵀ + A H⁻¹ Cᵀ − g C H⁻¹ Cᵀ.
/// Edge, vertex (ĝ = s |r| = s √(2 φ*)): ∇²ĝ = s (∇²φ* − Pᵀ r̂ r̂ᵀ P)/|r|, r̂ = r/|r|, with
/// ∇²φ* = PᵀP + B dξ*/dx (node_to_surface's penalty tangent over w ε_N); 0 if r = 0.
SignedDistanceDerivatives signed_distance_derivatives(const detail::SurfaceKinematics& k,
                                                      const detail::ProjectionDerivatives& d,
                                                      const SignedDistance& sd) {
  SignedDistanceDerivatives out;
  out.gradient = k.P.transpose() * sd.along;
  if (k.T.cols() == 2) {
    const Eigen::Vector3d& n = k.normal;
    const Eigen::MatrixXd A = k.P.transpose() * k.a;
    Eigen::MatrixXd C(k.dofs, 2);
    for (int alpha = 0; alpha < 2; ++alpha) C.col(alpha) = k.P_xi[alpha].transpose() * n;
    const Eigen::Matrix2d M = k.a.transpose() * k.a;
    Eigen::Matrix2d kappa = Eigen::Matrix2d::Zero();
    kappa(0, 1) = kappa(1, 0) = n.dot(k.x12);
    const Eigen::Matrix2d H = M - k.gap * kappa;
    const Eigen::Matrix2d Hinv = H.inverse(), Minv = M.inverse();
    const Eigen::MatrixXd hess = -A * (Minv * kappa * Hinv) * A.transpose() +
                                 C * Hinv * A.transpose() + A * Hinv * C.transpose() -
                                 k.gap * C * Hinv * C.transpose();
    out.hessian = 0.5 * (hess + hess.transpose());
    return out;
  }
  if (!(sd.distance > 0)) {
    out.hessian = Eigen::MatrixXd::Zero(k.dofs, k.dofs);
    return out;
  }
  const Eigen::Vector3d r_hat = k.r / sd.distance;
  const Eigen::VectorXd Pr = k.P.transpose() * r_hat;
  const double s = sd.value < 0 ? -1.0 : 1.0;
  const Eigen::MatrixXd hess =
      (s / sd.distance) * (k.P.transpose() * k.P + d.B * d.dxi_dx - Pr * Pr.transpose());
  out.hessian = 0.5 * (hess + hess.transpose());
  return out;
}

}  // namespace

SurfaceContact node_to_surface(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                               const NodeCoordinates& master, const FacetProjection& projection,
                               double w, double eps_n, double touch, double lambda,
                               double smoothing) {
  constexpr const char* who = "node_to_surface";
  check_smoothing(smoothing, who);
  check_parameters(w, eps_n, who);
  check_multiplier(lambda, who);
  const detail::SurfaceKinematics k =
      detail::surface_kinematics(slave, weights, master, projection, who);
  SurfaceContact result{Eigen::VectorXd::Zero(k.dofs),
                        Eigen::MatrixXd::Zero(k.dofs, k.dofs),
                        k.gap,
                        0.0,
                        k.normal,
                        projection.xi,
                        projection.feature,
                        projection.local_index,
                        false};
  if (!(touch >= 0))
    throw std::invalid_argument(std::string(who) + ": touch must be >= 0");
  if (lambda > 0 || smoothing > 0) {  // augmented Lagrangian and/or smoothed penalty
    const SignedDistance sd = signed_distance(k);
    const NormalPressure np = normal_pressure(sd.value, eps_n, lambda, smoothing);
    if (!np.active) return result;  // open
    const double p = np.value;
    const detail::ProjectionDerivatives d = detail::projection_derivatives(k, who);
    const SignedDistanceDerivatives dd = signed_distance_derivatives(k, d, sd);
    result.residual = -w * p * dd.gradient;
    const Eigen::MatrixXd K =
        -w * np.slope * dd.gradient * dd.gradient.transpose() - w * p * dd.hessian;
    result.tangent = 0.5 * (K + K.transpose());
    result.pressure = p;
    result.closed = true;
    return result;
  }
  if (k.gap > touch) return result;
  const detail::ProjectionDerivatives d = detail::projection_derivatives(k, who);
  const double scale = w * eps_n;
  result.residual = scale * k.P.transpose() * k.r;
  // K = w ε_N [PᵀP − B T (TᵀHT)⁻¹ Tᵀ Bᵀ] = w ε_N [PᵀP + B dξ*/dx], symmetrised against rounding.
  const Eigen::MatrixXd K = scale * (k.P.transpose() * k.P + d.B * d.dxi_dx);
  result.tangent = 0.5 * (K + K.transpose());
  result.pressure = eps_n * std::max(0.0, -k.gap);
  result.closed = true;
  return result;
}

SurfaceContact node_to_surface(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                               const NodeCoordinates& master, double w, double eps_n,
                               double lambda, double smoothing) {
  check_parameters(w, eps_n, "node_to_surface");
  if (weights.size() != slave.cols() || !slave.allFinite() || !weights.allFinite())
    throw std::invalid_argument(
        "node_to_surface: slave coordinates and weights must be finite and as many");
  return node_to_surface(slave, weights, master, project_to_facet(master, slave * weights), w,
                         eps_n, 0.0, lambda, smoothing);
}

double node_to_surface_energy(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                              const NodeCoordinates& master, double w, double eps_n,
                              double touch, double lambda, double smoothing) {
  constexpr const char* who = "node_to_surface_energy";
  check_smoothing(smoothing, who);
  check_parameters(w, eps_n, who);
  check_multiplier(lambda, who);
  if (weights.size() != slave.cols() || !slave.allFinite() || !weights.allFinite())
    throw std::invalid_argument(std::string(who) +
                                ": slave coordinates and weights must be finite and as many");
  const FacetProjection p = project_to_facet(master, slave * weights);
  const detail::SurfaceKinematics k = detail::surface_kinematics(slave, weights, master, p, who);
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

NodeCoordinates gather_facet(std::int32_t facet, std::span<const std::int32_t> facets,
                             int nodes_per_facet, std::span<const double> coords) {
  if (nodes_per_facet != 3 && nodes_per_facet != 4)
    throw std::invalid_argument("gather_facet: nodes_per_facet must be 3 or 4, got " +
                                std::to_string(nodes_per_facet));
  const std::size_t npf = static_cast<std::size_t>(nodes_per_facet);
  const std::size_t num_facets = facets.size() / npf, num_nodes = coords.size() / 3;
  if (facet < 0 || static_cast<std::size_t>(facet) >= num_facets)
    throw std::out_of_range("gather_facet: facet " + std::to_string(facet) + " out of range [0, " +
                            std::to_string(num_facets) + ")");
  NodeCoordinates x(3, nodes_per_facet);
  for (std::size_t a = 0; a < npf; ++a) {
    const std::int32_t node = facets[npf * static_cast<std::size_t>(facet) + a];
    if (node < 0 || static_cast<std::size_t>(node) >= num_nodes)
      throw std::out_of_range("gather_facet: facet " + std::to_string(facet) + " has node " +
                              std::to_string(node) + " out of range [0, " +
                              std::to_string(num_nodes) + ")");
    for (int i = 0; i < 3; ++i) x(i, static_cast<Eigen::Index>(a)) = coords[3 * node + i];
  }
  return x;
}

ClosestFacet closest_facet(const Eigen::Vector3d& x_s, std::span<const std::int32_t> candidates,
                           std::span<const std::int32_t> facets, int nodes_per_facet,
                           std::span<const double> coords) {
  if (candidates.empty()) throw std::invalid_argument("closest_facet: no candidate facets");
  if (nodes_per_facet != 3 && nodes_per_facet != 4)
    throw std::invalid_argument("closest_facet: nodes_per_facet must be 3 or 4, got " +
                                std::to_string(nodes_per_facet));
  if (facets.size() % static_cast<std::size_t>(nodes_per_facet) != 0 || coords.size() % 3 != 0)
    throw std::invalid_argument("closest_facet: facets must be num_facets x " +
                                std::to_string(nodes_per_facet) +
                                " and coords num_nodes x 3 (row-major)");
  if (!x_s.allFinite()) throw std::invalid_argument("closest_facet: x_s must be finite");
  bool have = false;
  ClosestFacet best{};
  double best_length = 0;
  for (const std::int32_t facet : candidates) {
    const NodeCoordinates x = gather_facet(facet, facets, nodes_per_facet, coords);
    FacetProjection p;
    try {
      p = project_to_facet(x, x_s);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("closest_facet: candidate facet " + std::to_string(facet) + ": " +
                                  e.what());
    }
    double length = 0;
    for (int a = 0; a < nodes_per_facet; ++a)
      length = std::max(length, (x.col((a + 1) % nodes_per_facet) - x.col(a)).norm());
    bool better = !have;
    if (have) {
      const double tol =
          1e-12 * (std::max(length, best_length) + std::max(p.distance, best.projection.distance));
      if (p.distance < best.projection.distance - tol) {
        better = true;
      } else if (p.distance <= best.projection.distance + tol) {
        const int r = rank(p.feature), r_best = rank(best.projection.feature);
        better = r < r_best || (r == r_best && facet < best.facet);
      }
    }
    if (better) {
      best = {facet, p};
      best_length = length;
      have = true;
    }
  }
  return best;
}

}  // namespace hypercontact
