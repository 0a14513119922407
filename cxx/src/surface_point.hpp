// Internal: one slave point of a surface evaluation, shared by the frictionless and the frictional
// family (surface_contact.cpp, surface_contact_friction.cpp): the input checks, the point's
// nodes, its pairing by the narrow phase recorded in the state, its normal element if closed,
// and the dofs of its element.
#pragma once

#include <array>
#include <hypercontact/narrow_phase.hpp>
#include <hypercontact/node_to_surface.hpp>
#include <hypercontact/surface_contact.hpp>
#include <span>

namespace hypercontact::detail {

/// Throws std::invalid_argument (prefixed with `who`) on inconsistent sizes or indices of the
/// slave points, dofs, candidates and multipliers (the master's are NarrowPhase's).
void check_surface_input(const SurfaceContactInput& in, const char* who);

/// Entries of point_nodes (and point_weights) per slave point: 1 to max_slave_nodes.
std::size_t nodes_per_point(const SurfaceContactInput& in);

/// s with every per-point array sized for np points and the totals zero.
void init_state(SurfaceContactState& s, std::size_t np);

/// A slave point x_s = Σ M_i x_i: its nodes (the entries ≥ 0 of its row of point_nodes), their
/// current coordinates and weights.
struct SlavePoint {
  std::array<std::int32_t, max_slave_nodes> node_storage{};
  int num_nodes = 0;
  SlaveNodes x;
  SlaveWeights weights;

  std::span<const std::int32_t> nodes() const {
    return {node_storage.data(), static_cast<std::size_t>(num_nodes)};
  }
  Eigen::Vector3d position() const { return x * weights; }
};

/// Slave point p of the input.
SlavePoint slave_point(const SurfaceContactInput& in, std::size_t p);

/// Records the pairing of point p (facet, feature, ξ, normal, gap, status) in s.
void record_pairing(const PointPairing& pr, std::size_t p, SurfaceContactState& s);

/// A paired and closed slave point with its normal element against a facet of NM nodes.
template <int NM>
struct ClosedPoint {
  SlavePoint slave;
  PointPairing pairing;
  FacetNodes<NM> master;  ///< the closest facet's nodes
  SurfaceContact element;
};

/// Pairs slave point p (NoCandidate without candidates) and records facet, feature, status, ξ,
/// gap and normal in s; if it is paired and closed, evaluates its normal element (node_to_surface)
/// into out and records it in s (num_closed, pressure). Returns whether it is closed.
template <int NM>
bool closed_normal_element(const SurfaceContactInput& in, const NarrowPhase& narrow, std::size_t p,
                           SurfaceContactState& s, ClosedPoint<NM>& out);

/// The dofs (3 per node) of `nodes`, then of the nodes of master facet `facet`, into out.
void element_dofs(const SurfaceContactInput& in, std::span<const std::int32_t> nodes,
                  std::int32_t facet, std::span<std::int32_t> out);

extern template bool closed_normal_element<3>(const SurfaceContactInput&, const NarrowPhase&,
                                              std::size_t, SurfaceContactState&, ClosedPoint<3>&);
extern template bool closed_normal_element<4>(const SurfaceContactInput&, const NarrowPhase&,
                                              std::size_t, SurfaceContactState&, ClosedPoint<4>&);
extern template bool closed_normal_element<6>(const SurfaceContactInput&, const NarrowPhase&,
                                              std::size_t, SurfaceContactState&, ClosedPoint<6>&);
extern template bool closed_normal_element<9>(const SurfaceContactInput&, const NarrowPhase&,
                                              std::size_t, SurfaceContactState&, ClosedPoint<9>&);

}  // namespace hypercontact::detail
