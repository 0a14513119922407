// Tributary areas of the nodes of a contact surface (weights of nodal integration).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace hypercontact {

/// Nodal areas of a surface of bilinear quadrilaterals:
///   A_i = Σ_facets ∫ N_i dA,   dA = |∂x/∂ξ × ∂x/∂η| dξ dη,
/// evaluated with 2×2 Gauss points (exact for planar quadrilaterals, whose area element is
/// linear in ξ, η; an approximation for warped ones).
///
/// coords: num_nodes × 3, row-major.
/// quads:  m × 4 node indices in CYCLIC order around the facet (v0 → v1 → v2 → v3 → v0).
///         Note: dolfinx lists a hexahedron facet's vertices in tensor-product order, whose
///         cycle is (0, 1, 3, 2); swap the last two entries before calling.
/// Throws std::invalid_argument on inconsistent sizes, std::out_of_range on a bad index.
std::vector<double> nodal_areas(std::span<const double> coords, std::span<const std::int32_t> quads,
                                std::size_t num_nodes);

/// Nodal areas of a surface of linear triangles: A_i = Σ_facets |T|/3.
/// coords: num_nodes × 3, row-major; triangles: m × 3 node indices (any order).
std::vector<double> nodal_areas_tri(std::span<const double> coords,
                                    std::span<const std::int32_t> triangles, std::size_t num_nodes);

}  // namespace hypercontact
