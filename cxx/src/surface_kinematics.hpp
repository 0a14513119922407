// Private to the kernels: kinematics of a slave point against a master facet of NM nodes at its
// projection, shared by node_to_surface.cpp and surface_friction.cpp; bounded Eigen types
// (surface_element_types.hpp), nothing on the heap.
#pragma once

#include <Eigen/Core>
#include <array>
#include <hypercontact/facet_projection.hpp>
#include <hypercontact/surface_element_types.hpp>

namespace hypercontact::detail {

/// x = [x_1 … x_ns (slave), x_1 … x_nm (master)] stacked, dofs = 3 (ns + nm) entries;
/// r = x_s − x_M(ξ*) = P x, P = [M_1 I … M_ns I, −N_1 I … −N_nm I] at ξ*.
template <int NM>
struct SurfaceKinematics {
  static constexpr int nm = NM;
  static constexpr int max_dofs = 3 * (max_slave_nodes + NM);
  using Rows3 = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, max_dofs>;
  int ns = 0, dofs = 0;
  Eigen::Matrix<double, NM, 1> N;    ///< N_a(ξ*)
  Eigen::Matrix<double, NM, 2> dN;   ///< ∂N_a/∂ξ_α at ξ*
  Eigen::Matrix<double, NM, 3> d2N;  ///< ∂²N_a/∂ξ1², ∂²N_a/∂ξ2², ∂²N_a/∂ξ1∂ξ2
  Rows3 P;                           ///< 3 × dofs
  std::array<Rows3, 2> P_xi;         ///< ∂P/∂ξ_α = [0, −∂N_a/∂ξ_α I]
  Eigen::Vector3d x_s, r;
  Eigen::Matrix<double, 3, 2> a;  ///< a_α at ξ*
  Eigen::Matrix3d xdd;            ///< [x_,11 x_,22 x_,12] (bilinear: only x_,12 ≠ 0)
  Eigen::Vector3d c;              ///< a_1 × a_2
  Eigen::Vector3d normal;         ///< c / |c|
  double gap = 0;                 ///< r · n
  /// 2 × k: ξ = ξ* + T η on the feature (k = 2 face, 1 edge, 0 vertex)
  Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::ColMajor, 2, 2> T;
};

/// Validates the inputs (who names the caller in messages) and evaluates the kinematics.
/// Throws std::invalid_argument on bad sizes, non-finite input, an inconsistent projection or a
/// degenerate facet.
template <int NM>
SurfaceKinematics<NM> surface_kinematics(const SlaveNodes& slave, const SlaveWeights& weights,
                                         const FacetNodes<NM>& master,
                                         const FacetProjection& projection, const char* who);

/// dξ*/dx = −T (Tᵀ H T)⁻¹ Tᵀ Bᵀ (2 × dofs) and B (dofs × 2), with H = a_α·a_β − r·x_,αβ and
/// B_α = P_,αᵀ r − Pᵀ a_α. Throws std::runtime_error when Tᵀ H T is not positive definite
/// (the slave point at a centre of curvature of the facet).
template <int NM>
struct ProjectionDerivatives {
  static constexpr int max_dofs = SurfaceKinematics<NM>::max_dofs;
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::ColMajor, max_dofs, 2> B;
  Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::ColMajor, 2, max_dofs> dxi_dx;
};
template <int NM>
ProjectionDerivatives<NM> projection_derivatives(const SurfaceKinematics<NM>& k, const char* who);

/// master.cols() if it is 3, 4, 6 or 9, else std::invalid_argument.
int facet_node_count(const NodeCoordinates& master, const char* who);

/// The slave nodes and weights of a run-time caller (3 × ns, ns ≤ max_slave_nodes), checked.
SlaveNodes bounded_slave(const NodeCoordinates& slave, const Eigen::VectorXd& weights,
                         const char* who);

extern template SurfaceKinematics<3> surface_kinematics<3>(const SlaveNodes&, const SlaveWeights&,
                                                           const FacetNodes<3>&,
                                                           const FacetProjection&, const char*);
extern template SurfaceKinematics<4> surface_kinematics<4>(const SlaveNodes&, const SlaveWeights&,
                                                           const FacetNodes<4>&,
                                                           const FacetProjection&, const char*);
extern template SurfaceKinematics<6> surface_kinematics<6>(const SlaveNodes&, const SlaveWeights&,
                                                           const FacetNodes<6>&,
                                                           const FacetProjection&, const char*);
extern template SurfaceKinematics<9> surface_kinematics<9>(const SlaveNodes&, const SlaveWeights&,
                                                           const FacetNodes<9>&,
                                                           const FacetProjection&, const char*);
extern template ProjectionDerivatives<3> projection_derivatives<3>(const SurfaceKinematics<3>&,
                                                                   const char*);
extern template ProjectionDerivatives<4> projection_derivatives<4>(const SurfaceKinematics<4>&,
                                                                   const char*);
extern template ProjectionDerivatives<6> projection_derivatives<6>(const SurfaceKinematics<6>&,
                                                                   const char*);
extern template ProjectionDerivatives<9> projection_derivatives<9>(const SurfaceKinematics<9>&,
                                                                   const char*);

}  // namespace hypercontact::detail
