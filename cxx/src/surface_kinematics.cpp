#include "surface_kinematics.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <stdexcept>
#include <string>

namespace hypercontact::detail {

namespace {
[[noreturn]] void invalid(const char* who, const std::string& what) {
  throw std::invalid_argument(std::string(who) + ": " + what);
}
}  // namespace

template <int NM>
SurfaceKinematics<NM> surface_kinematics(const SlaveNodes& slave, const SlaveWeights& weights,
                                         const FacetNodes<NM>& master,
                                         const FacetProjection& projection, const char* who) {
  if (slave.cols() < 1) invalid(who, "at least one slave node is needed");
  if (weights.size() != slave.cols())
    invalid(who, std::to_string(weights.size()) + " slave weights for " +
                     std::to_string(slave.cols()) + " slave nodes");
  if (!slave.allFinite() || !weights.allFinite() || !master.allFinite())
    invalid(who, "slave coordinates, weights and master coordinates must be finite");
  if (!projection.xi.allFinite()) invalid(who, "the projection's xi must be finite");
  SurfaceKinematics<NM> k;
  k.ns = static_cast<int>(slave.cols());
  k.dofs = 3 * (k.ns + NM);
  if (projection.feature != Feature::Face &&
      (projection.local_index < 0 || projection.local_index >= NM))
    invalid(who, "the projection's local index " + std::to_string(projection.local_index) +
                     " is not an edge or vertex of a facet of " + std::to_string(NM) + " nodes");
  const Eigen::Vector2d& xi = projection.xi;
  k.normal = facet_normal<NM>(master, xi);  // throws on a degenerate or folded facet
  k.N = facet_shape_functions<NM>(xi);
  k.dN = facet_shape_derivatives<NM>(xi);
  k.d2N = facet_shape_second_derivatives<NM>(xi);
  k.x_s = slave * weights;
  k.r = k.x_s - master * k.N;
  k.a = master * k.dN;
  k.xdd = master * k.d2N;
  k.c = k.a.col(0).cross(k.a.col(1));
  k.gap = k.r.dot(k.normal);

  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  k.P.setZero(3, k.dofs);
  for (int i = 0; i < k.ns; ++i) k.P.template block<3, 3>(0, 3 * i) = weights[i] * I;
  for (int a = 0; a < NM; ++a) k.P.template block<3, 3>(0, 3 * (k.ns + a)) = -k.N[a] * I;
  for (int alpha = 0; alpha < 2; ++alpha) {
    k.P_xi[alpha].setZero(3, k.dofs);
    for (int a = 0; a < NM; ++a)
      k.P_xi[alpha].template block<3, 3>(0, 3 * (k.ns + a)) = -k.dN(a, alpha) * I;
  }
  switch (projection.feature) {
    case Feature::Face:
      k.T = Eigen::Matrix2d::Identity();
      break;
    case Feature::Edge:
      k.T = facet_vertex_xi<NM>(projection.local_index + 1) -
            facet_vertex_xi<NM>(projection.local_index);
      break;
    case Feature::Vertex:
      k.T.resize(2, 0);
      break;
  }
  return k;
}

template <int NM>
ProjectionDerivatives<NM> projection_derivatives(const SurfaceKinematics<NM>& k, const char* who) {
  ProjectionDerivatives<NM> d;
  d.B.resize(k.dofs, 2);
  for (int alpha = 0; alpha < 2; ++alpha)
    d.B.col(alpha) = k.P_xi[alpha].transpose() * k.r - k.P.transpose() * k.a.col(alpha);
  d.dxi_dx.setZero(2, k.dofs);
  if (k.T.cols() == 0) return d;  // vertex: ξ* fixed

  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 2, 2>;
  const Eigen::Matrix2d metric = k.a.transpose() * k.a;
  const Eigen::Matrix2d H = distance_hessian(k.a, k.r, k.xdd);
  const Small Ht = k.T.transpose() * H * k.T;
  const Small Mt = k.T.transpose() * metric * k.T;
  const Eigen::SelfAdjointEigenSolver<Small> eig(Ht, Eigen::EigenvaluesOnly);
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

int facet_node_count(const NodeCoordinates& master, const char* who) {
  const auto n = master.cols();
  if (n != 3 && n != 4 && n != 6 && n != 9)
    invalid(who, "a master facet has 3, 4, 6 or 9 nodes, got " + std::to_string(n));
  return static_cast<int>(master.cols());
}

SlaveNodes bounded_slave(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                         const char* who) {
  if (slave.cols() < 1 || slave.cols() > max_slave_nodes)
    invalid(who, "a slave point has 1 to " + std::to_string(max_slave_nodes) + " nodes, got " +
                     std::to_string(slave.cols()));
  if (weights.size() != slave.cols() || !slave.allFinite() || !weights.allFinite())
    invalid(who, "slave coordinates and weights must be finite and as many");
  return slave;
}

template SurfaceKinematics<3> surface_kinematics<3>(const SlaveNodes&, const SlaveWeights&,
                                                    const FacetNodes<3>&, const FacetProjection&,
                                                    const char*);
template SurfaceKinematics<4> surface_kinematics<4>(const SlaveNodes&, const SlaveWeights&,
                                                    const FacetNodes<4>&, const FacetProjection&,
                                                    const char*);
template SurfaceKinematics<6> surface_kinematics<6>(const SlaveNodes&, const SlaveWeights&,
                                                    const FacetNodes<6>&, const FacetProjection&,
                                                    const char*);
template SurfaceKinematics<9> surface_kinematics<9>(const SlaveNodes&, const SlaveWeights&,
                                                    const FacetNodes<9>&, const FacetProjection&,
                                                    const char*);
template ProjectionDerivatives<3> projection_derivatives<3>(const SurfaceKinematics<3>&,
                                                            const char*);
template ProjectionDerivatives<4> projection_derivatives<4>(const SurfaceKinematics<4>&,
                                                            const char*);
template ProjectionDerivatives<6> projection_derivatives<6>(const SurfaceKinematics<6>&,
                                                            const char*);
template ProjectionDerivatives<9> projection_derivatives<9>(const SurfaceKinematics<9>&,
                                                            const char*);

}  // namespace hypercontact::detail
