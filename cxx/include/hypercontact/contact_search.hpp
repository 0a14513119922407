// Broad phase of node-to-surface contact: candidate master facets of every slave point.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace hypercontact {

/// Candidate lists in compressed sparse row form: the candidate facets of slave point i are
/// indices[offsets[i]], …, indices[offsets[i+1] − 1], strictly ascending.
struct ContactCandidates {
  std::vector<std::int32_t> offsets;  ///< num_slave + 1 entries, offsets[0] = 0, non-decreasing
  std::vector<std::int32_t> indices;  ///< facet indices, offsets.back() entries
};

/// Broad-phase contact search: facet f is a candidate of slave point x iff x lies in the
/// closed axis-aligned bounding box of f's nodes inflated by `capture` on every side:
///   min_a X_a,d − c ≤ x_d ≤ max_a X_a,d + c   for d = 0, 1, 2   (X_a: nodes of f).
/// This is a superset of the facets within distance c of x; the narrow phase (closest-point
/// projection) decides. The test is the same floating-point comparison as in
/// find_candidates_brute_force, so the two functions return identical lists.
///
/// slave_x:         n × 3 slave point coordinates, row-major; all finite.
/// master_x:        m × 3 master node coordinates, row-major; all finite.
/// facets:          num_facets × nodes_per_facet indices into master_x, row-major.
/// nodes_per_facet: 3, 6 (triangles) or 4, 9 (quadrilaterals); the node order does not matter.
///                  The box is that of the nodes: a curved facet may bulge beyond it by up to
///                  the distance of its edge nodes from the chords, which c must cover (the
///                  callers' default c, the largest facet size, does).
/// capture:         c, finite and ≥ 0.
/// Throws std::invalid_argument (message naming the argument) on a size that is not a multiple
/// of 3 or of nodes_per_facet, nodes_per_facet ∉ {3, 4, 6, 9}, a non-finite coordinate or a bad c;
/// std::out_of_range on a facet index outside [0, m); std::length_error if the number of
/// candidate pairs does not fit the int32 offsets.
///
/// Method: a nanoflann k-d tree over the SLAVE points,
/// queried once per facet with a ball around the centre of the facet's inflated box whose radius
/// is that box's half-diagonal |h + c| (h: half-extents; the ball contains the box), then the
/// exact box test; the per-facet hits are transposed to per-point lists by a counting sort,
/// which leaves every list ascending without sorting. Cost O((n + f) log n + candidates);
/// bench/contact_search.py measures it (bench/results/contact_search.md).
/// Why this one (throw-away prototypes, timed on one core with 10⁵–10⁶ nodes; all returned equal
/// lists):
///  - nanoflann over facet centroids, queried per point, needs ONE radius for all facets, the
///    largest |h + c| (c + |h| would be too small: the corners of the inflated box lie at
///    |h + c|). On uniform grids it was 1.0–1.6× slower; on a graded grid 4× slower, and on a
///    sheet with a patch refined 300× (10⁴ + 9·10⁴ facets) 650× slower (149 s against
///    0.23 s): every point pays for the largest facet.
///  - a hand-written AABB tree (median split, queried per point) was 1.6–1.9× slower on
///    uniform grids and 1.6× faster on the refined patch.
///  - a hashed bucket grid (one cell size) was 1.3–1.8× faster on uniform grids but 1.6×
///    slower on the refined patch, and its cost grows with the square of the facet-size
///    contrast.
///  This is the library solution without a bad case among these.
ContactCandidates find_candidates(std::span<const double> slave_x, std::span<const double> master_x,
                                  std::span<const std::int32_t> facets, int nodes_per_facet,
                                  double capture);

/// Reference for the tests: the same contract and result as find_candidates, by testing every
/// (point, facet) pair, O(n · num_facets).
ContactCandidates find_candidates_brute_force(std::span<const double> slave_x,
                                              std::span<const double> master_x,
                                              std::span<const std::int32_t> facets,
                                              int nodes_per_facet, double capture);

}  // namespace hypercontact
