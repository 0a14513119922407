// A smooth master surface (docs/method.md §3.6): a deformable master (3- and 4-node facets, and
// the curved 6- and 9-node facets of quadratic elements) carries a C0 field of averaged nodal
// normals, and a slave point is projected onto it along that field instead of by the closest
// point. Its pressure acts along the interpolated normal. Gap, normal and force are then
// continuous where a slave point crosses an edge or a vertex of the master, where the faceted
// closest-point element turns its force by the angle between the facets at once (the Newton
// stall of a point bouncing between two facets). The tangent is the exact derivative of that
// force; it is not symmetric and it couples the point with the nodes whose positions make the
// facet's nodal normals (the neighbour stencil).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <hypercontact/coulomb_friction.hpp>
#include <hypercontact/facet_shape.hpp>
#include <hypercontact/narrow_phase.hpp>
#include <hypercontact/surface_element_types.hpp>
#include <span>
#include <vector>

namespace hypercontact {

/// The facets at every node of a master surface: node a is corner corner[i] of facet facet[i]
/// for i in offsets[a] … offsets[a + 1].
struct NodeFacets {
  std::vector<std::int32_t> offsets;
  std::vector<std::int32_t> facet;
  std::vector<std::int8_t> corner;

  /// Throws std::invalid_argument unless the facets have 3, 4, 6 or 9 nodes and every node
  /// index is below num_nodes.
  NodeFacets(const FacetConnectivity& facets, std::size_t num_nodes);
};

/// The unit nodal normal at a node a of the master surface, m_a = m̃/|m̃| with m̃ the sum over
/// the facets at a of one vector per facet:
///   linear facets: (x_next − x_a) × (x_prev − x_a) (next and prev: the facet's corners after and
///     before a, counter-clockwise seen from outside; on a triangle 2 × its area times its normal,
///     on a quadrilateral the corner's parallelogram);
///   quadratic facets (6, 9 nodes; a may be a corner, an edge node or the centre):
///     a_1 × a_2 = ∂x_M/∂ξ_1 × ∂x_M/∂ξ_2 at the node's ξ, over all the facet's nodes;
/// and its derivative ∂m_a/∂x with respect to the nodes it depends on.
struct NodalNormal {
  Eigen::Vector3d m;
  std::vector<std::int32_t> nodes;  ///< a first, then the facets' nodes m̃ depends on
  Eigen::Matrix<double, 3, Eigen::Dynamic> jacobian;  ///< 3 × 3 nodes.size(): ∂m/∂x_{nodes[j]}
};

/// m_a alone (x: num_nodes × 3, row-major). Throws std::invalid_argument if the node has no
/// facet or its normals cancel (|m̃| = 0).
Eigen::Vector3d nodal_normal_value(std::int32_t node, const NodeFacets& at,
                                   const FacetConnectivity& facets, std::span<const double> x);
/// m_a and ∂m_a/∂x. Throws as nodal_normal_value.
NodalNormal nodal_normal(std::int32_t node, const NodeFacets& at, const FacetConnectivity& facets,
                         std::span<const double> x);

/// Whether node a is a crease: the vector of one of its facets in m̃ (nodal_normal) more than
/// 45° (cos < 0.7) from m, its unit nodal normal — a folded hinge, a corner of the
/// body, where the averaged normal represents no facet and the normal field turns over a facet
/// (or cancels). The smooth evaluation keeps the faceted element on facets with such a node.
bool is_crease(std::int32_t node, const Eigen::Vector3d& m, const NodeFacets& at,
               const FacetConnectivity& facets, std::span<const double> x);

/// The projection of x_s onto a facet along its normal field: ξ and t with
///   x_s = x_M(ξ) + t m(ξ),  x_M(ξ) = Σ N_a(ξ) x_a,  m(ξ) = Σ N_a(ξ) m_a
/// (m_a the facet's nodal normals; m(ξ) is not a unit vector: the signed distance along the
/// unit normal n = m/|m| is ĝ = t |m(ξ)|). Newton on the three unknowns (ξ1, ξ2, t) from ξ0,
/// with ξ free (the caller decides whether ξ lies on the facet).
struct NormalFieldProjection {
  Eigen::Vector2d xi;
  double t = 0.0;
  double gap = 0.0;        ///< ĝ = t |m(ξ)|
  Eigen::Vector3d normal;  ///< n = m(ξ)/|m(ξ)|
  int iterations = 0;
  bool converged = false;  ///< |Δ(ξ, t)| fell to rounding within 50 iterations, J regular
};

template <int NM>
requires FacetNodeCount<NM> NormalFieldProjection project_along_normals(const Eigen::Vector3d& x_s,
                                                                        const FacetNodes<NM>& X,
                                                                        const FacetNodes<NM>& M,
                                                                        const Eigen::Vector2d& xi0);

/// How far ξ lies outside the reference facet (≤ 0: on it) and across which edge: quadrilateral
/// max(|ξ1|, |ξ2|) − 1, triangle max(−ξ2, ξ1 + ξ2 − 1, −ξ1) (edges 0, 1, 2 in that order).
struct Overhang {
  double amount;
  int edge;
};
template <int NM>
requires FacetNodeCount<NM> Overhang overhang(const Eigen::Vector2d& xi);

/// The contact element of a slave point x_s = Σ M_i x_i against a facet of the smooth master,
/// at the projection along the normal field (ξ, t), with the pressure p_N = normal_pressure(ĝ, ε_N,
/// λ_N, δ) (penetration.hpp):
///   residual R_i = −w p_N M_i n (slave node i),  R_a = w p_N N_a(ξ) n (facet node a)
///   (force and moment balance: Σ N_a = 1 and x_s − x_M(ξ) ∥ n);
///   tangent K = ∂R/∂x over the columns: the slave nodes, the facet's nodes and the nodes of its
///   nodal normals' stencils, by the implicit function (ξ, t)(x_s, x_a, m_a) and ∂m_a/∂x.
///
/// With friction (`friction` not null; docs/method.md §3.6): the return map of surface_friction
/// with the smoothed normal n at the normal-field point ξ:
///   x_old = Σ N_b(ξ_old) x_b (the old facet's CURRENT nodes), v = t_old + ε_T (x_s − x_old),
///   t_trial = (I − n n) v,  (t, state) = return_map(t_trial, p_N, μ),
///   R_i += w M_i t,  R_a −= w N_a(ξ) t;
/// the tangent adds ∂/∂x of that (with dn, dp_N, dξ of the normal-field projection, and the old
/// facet's nodes as columns). No history (old_nodes empty): old point = current point, t_old = 0,
/// so t_trial = 0: no friction force and no friction tangent (state Stick; Slip at μ = 0, as
/// return_map reports a frictionless point).
struct SmoothFrictionHistory {
  std::span<const std::int32_t> old_nodes;  ///< the old facet's nodes (NM of them), or empty
  Eigen::Vector2d xi_old = Eigen::Vector2d::Zero();
  Eigen::Vector3d t_old = Eigen::Vector3d::Zero();
  double eps_t = 0.0;
  double mu = 0.0;
};

struct SmoothContact {
  Eigen::VectorXd residual;           ///< 3 (ns + NM): slave nodes, then facet nodes
  Eigen::MatrixXd tangent;            ///< residual.size() × 3 columns.size()
  std::vector<std::int32_t> columns;  ///< nodes: the ns slave nodes, the facet's, the stencil's
  double gap = 0.0;
  double pressure = 0.0;
  Eigen::Vector3d normal;
  Eigen::Vector2d xi;
  bool closed = false;
  // friction (zero without)
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();
  Eigen::Vector3d slip_increment = Eigen::Vector3d::Zero();
  double dissipation = 0.0;
  StickSlip state = StickSlip::Open;
};

/// `slave_nodes` (ns node indices into x), `slave` their coordinates and `weights` M_i; `facet` the
/// facet's index in `facets`; `projection` = project_along_normals at the current x; w ≥ 0 the
/// point's weight; closed for ĝ ≤ touch at λ_N = δ = 0. Throws std::invalid_argument on sizes,
/// std::runtime_error if the projection's Jacobian is singular.
template <int NM>
requires FacetNodeCount<NM> SmoothContact smooth_node_to_surface(
    std::span<const std::int32_t> slave_nodes, const SlaveNodes& slave, const SlaveWeights& weights,
    std::int32_t facet, const NodeFacets& at, const FacetConnectivity& facets,
    std::span<const double> x, const NormalFieldProjection& projection, double w, double eps_n,
    double touch = 0.0, double lambda = 0.0, double smoothing = 0.0,
    const SmoothFrictionHistory* friction = nullptr);

}  // namespace hypercontact
