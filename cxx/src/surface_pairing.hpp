// Internal: the narrow phase of deformable–deformable contact shared by the frictionless and the
// frictional evaluation: input checks, the master surface's rim nodes, and the pairing of one
// slave point (closest candidate facet, the rim continued by kOverhang, OffSurface
// classification, the touch tolerance).
#pragma once

#include <hypercontact/surface_contact.hpp>
#include <hypercontact/facet_projection.hpp>
#include <hypercontact/node_to_surface.hpp>
#include <vector>

namespace hypercontact::detail {

/// Throws std::invalid_argument (prefixed with `who`) on inconsistent sizes or indices.
void check_surface_input(const SurfaceContactInput& in, const char* who);

/// Per contact node: 1 if it ends an edge of the master surface without a neighbour.
std::vector<char> master_boundary_nodes(const SurfaceContactInput& in);

/// One slave point and how it was paired.
struct SlavePointPairing {
  NodeCoordinates slave;             ///< 3 × ns current coordinates of its nodes
  Eigen::VectorXd weights;           ///< ns weights M_i
  std::vector<std::int32_t> nodes;   ///< its ns contact nodes
  std::int32_t facet = -1;           ///< closest master facet
  FacetProjection projection;        ///< onto that facet (continued over the rim: a face point)
  PairingStatus status = PairingStatus::NoCandidate;
  double gap = 0.0;                  ///< signed gap (Paired), distance (OffSurface)
  double touch = 0.0;                ///< closed if gap ≤ touch (meshes built in touch)
};

/// Pairs slave point p (NoCandidate if it has no candidate facet) and records facet, feature,
/// status, ξ, gap and normal in s.
SlavePointPairing pair_slave_point(const SurfaceContactInput& in, const std::vector<char>& boundary_node,
                                   std::size_t p, SurfaceContactState& s);

/// Pairs slave point p and, if it is paired and closed, evaluates its normal element
/// (node_to_surface against `master`, the closest facet's nodes) and records it in s (num_closed,
/// pressure). Returns false, leaving master and e unset, if the point is not closed.
bool closed_normal_element(const SurfaceContactInput& in, const std::vector<char>& boundary_node,
                           std::size_t p, SurfaceContactState& s, SlavePointPairing& pr,
                           NodeCoordinates& master, SurfaceContact& e);

/// The dofs (3 per node) of `nodes`, then of the nodes of master facet `facet`, into out.
void element_dofs(const SurfaceContactInput& in, std::span<const std::int32_t> nodes,
                  std::int32_t facet, std::span<std::int32_t> out);

/// s with every per-point array sized for np points and the totals zero.
void init_state(SurfaceContactState& s, std::size_t np);

}  // namespace hypercontact::detail
