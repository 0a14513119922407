// Deformable–deformable normal contact (PETSc-free): a slave surface against a master surface,
// each slave point paired by the narrow phase with its closest master facet and, if closed,
// evaluated with the node-to-surface (or Gauss-point-to-surface) penalty element.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <hypercontact/contact_elements.hpp>
#include <hypercontact/narrow_phase.hpp>
#include <span>
#include <vector>

namespace hypercontact {

/// Per slave point and total output of one evaluation.
struct SurfaceContactState {
  std::vector<std::int32_t> facet;    ///< master facet of the closest point (−1: none)
  std::vector<std::int32_t> feature;  ///< 0 face, 1 edge, 2 vertex, −1 none
  std::vector<std::int32_t> status;   ///< PairingStatus
  std::vector<double> xi;             ///< ξ* on the facet, 2 per point
  std::vector<double> gap;            ///< signed gap g (> 0 open; 0 when not paired)
  std::vector<double> pressure;       ///< p_N = ε_N ⟨−g⟩ (augmented: ⟨λ_N − ε_N ĝ⟩)
  std::vector<double> normal;         ///< unit normal used for the sign of g, 3 per point
  Eigen::Vector3d force;    ///< force of the master on the slave body, −Σ r (slave part)
  std::int32_t num_closed;  ///< points with g ≤ 0 (augmented: with p_N > 0)
};

/// Geometry and numbering of one slave surface against one master surface.
///
/// x: nn × 3 current coordinates of the contact nodes (all nodes of both surfaces);
/// point_nodes, point_weights: np × k (1 ≤ k ≤ max_slave_nodes = 9) — slave point p is
///   x_p = Σ_i M_pi x_{node_pi} over the entries with node ≥ 0 (nodal integration: one node with
///   M = 1; Gauss points: the nodes of the slave facet, 3, 4, 6 or 9);
/// point_area: np — the point's weight w_p (nodal area or det J × Gauss weight, reference);
/// facets: nf master facets of nodes_per_facet nodes each (3, 6: triangles, 4, 9:
///   quadrilaterals), corners counter-clockwise seen from outside the master (narrow_phase.hpp);
/// edge_neighbour: nf × corners (3 or 4) — the master facet across edge k (corner k → k+1) of
///   facet f, −1 on the master surface's boundary;
/// offsets (np + 1), candidates: the broad phase's candidate facets of each point (CSR);
/// dofs: nn × 3 global PETSc indices, −1 for a constrained dof (skipped: Dirichlet rows and
///   columns stay exact).
struct SurfaceContactInput {
  std::span<const double> x;
  std::span<const std::int32_t> point_nodes;
  std::span<const double> point_weights;
  std::span<const double> point_area;
  FacetConnectivity facets;
  std::span<const std::int32_t> edge_neighbour;
  std::span<const std::int32_t> offsets;
  std::span<const std::int32_t> candidates;
  std::span<const std::int32_t> dofs;
  double eps_n;
  /// Augmented Lagrangian: λ_N ≥ 0 per slave point (np entries), or empty (all zero: penalty).
  /// A point with λ_N > 0 is active where ⟨λ_N − ε_N ĝ⟩ > 0 (node_to_surface), gaps up to
  /// λ_N/ε_N included; a point with λ_N = 0 is evaluated exactly as without multipliers.
  std::span<const double> multipliers = {};
  /// Smoothing δ ≥ 0 of the normal law (penetration.hpp, node_to_surface): 0 is the Macaulay
  /// bracket; δ > 0 makes points with g < λ_N/ε_N + δ active.
  double smoothing = 0.0;
  /// A smooth master (smooth_master.hpp; linear facets only): every slave point is projected
  /// along the master's averaged nodal normals, on the facet where that projection lands (walked
  /// to from the closest facet across edges, among the candidates), and its force acts along the
  /// interpolated normal; its element's columns add the nodal normals' stencils. A point whose
  /// projection leaves the candidates, crosses the rim, does not converge or meets a crease keeps
  /// the faceted element (feature 0, 1, 2; the smooth element reports feature 3), unless it lies
  /// beside the closest facet's edge or vertex (|g| < |r|/2): then it is open (docs/method.md
  /// §3.6).
  bool smooth_master = false;
};

/// The state and, for every closed point, its element: rows = columns = the dofs of
/// [the point's slave nodes, the facet's nodes] (3 each), R and K of node_to_surface, global
/// numbering (rows of master nodes may belong to another rank). With a smooth master the rows
/// are the same and the columns add the stencil's nodes (smooth_node_to_surface).
struct SurfaceContactEvaluation : SurfaceContactState {
  ContactElements elements;
};

/// Evaluates every slave point once: its pairing by the narrow phase (NarrowPhase::pair: closest
/// candidate facet, gap and its sign, the rim, the touch tolerance) and, if it is Paired and
/// closed (g ≤ touch; with λ_N > 0 or δ > 0: p_N > 0, see node_to_surface), the residual and
/// tangent of node_to_surface (energy ½ w ε_N g² with all curvature terms) against that facet.
/// Throws std::invalid_argument on inconsistent sizes or indices out of range, and as
/// node_to_surface.
SurfaceContactEvaluation evaluate_surface_contact(const SurfaceContactInput& in);

}  // namespace hypercontact
