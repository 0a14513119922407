// Private to the kernels: kinematics of a slave point against a master facet at its projection,
// shared by node_to_surface.cpp and surface_friction.cpp.
#pragma once

#include <Eigen/Core>
#include <array>
#include <hypercontact/facet_projection.hpp>

namespace hypercontact::detail {

/// x = [x_1 … x_ns (slave), x_1 … x_nm (master)] stacked, dofs = 3 (ns + nm) entries;
/// r = x_s − x_M(ξ*) = P x, P = [M_1 I … M_ns I, −N_1 I … −N_nm I] at ξ*.
struct SurfaceKinematics {
  int ns = 0, nm = 0, dofs = 0;
  Eigen::VectorXd N;                            ///< N_a(ξ*)
  Eigen::Matrix<double, Eigen::Dynamic, 2> dN;  ///< ∂N_a/∂ξ_α at ξ*
  Eigen::VectorXd d2N;                          ///< ∂²N_a/∂ξ1∂ξ2
  Eigen::MatrixXd P;                            ///< 3 × dofs
  std::array<Eigen::MatrixXd, 2> P_xi;          ///< ∂P/∂ξ_α = [0, −∂N_a/∂ξ_α I]
  Eigen::Vector3d x_s, r;
  Eigen::Matrix<double, 3, 2> a;  ///< a_α at ξ*
  Eigen::Vector3d x12;            ///< x_,12 (x_,11 = x_,22 = 0)
  Eigen::Vector3d c;              ///< a_1 × a_2
  Eigen::Vector3d normal;         ///< c / |c|
  double gap = 0;                 ///< r · n
  Eigen::MatrixXd T;              ///< 2 × k: ξ = ξ* + T η on the feature (k = 2, 1, 0)
};

/// Validates the inputs (who names the caller in messages) and evaluates the kinematics.
/// Throws std::invalid_argument on bad sizes, non-finite input, an inconsistent projection or a
/// degenerate facet.
SurfaceKinematics surface_kinematics(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                                     const NodeCoordinates& master,
                                     const FacetProjection& projection, const char* who);

/// dξ*/dx = −T (Tᵀ H T)⁻¹ Tᵀ Bᵀ (2 × dofs) and B (dofs × 2), with H = a_α·a_β − r·x_,αβ and
/// B_α = P_,αᵀ r − Pᵀ a_α. Throws std::runtime_error when Tᵀ H T is not positive definite
/// (the slave point at a centre of curvature of the facet).
struct ProjectionDerivatives {
  Eigen::MatrixXd B;
  Eigen::MatrixXd dxi_dx;
};
ProjectionDerivatives projection_derivatives(const SurfaceKinematics& k, const char* who);

}  // namespace hypercontact::detail
