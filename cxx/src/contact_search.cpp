#include <algorithm>
#include <cmath>
#include <cstddef>
#include <hypercontact/contact_search.hpp>
#include <limits>
#include <nanoflann.hpp>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {

constexpr std::size_t int32_max = std::numeric_limits<std::int32_t>::max();

/// v as in "-1e-20", "nan", "inf" (std::to_string would print "-0.000000").
std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// Inflated axis-aligned boxes of the facets, num_facets × 3 each, row-major.
struct Boxes {
  std::vector<double> lo, hi;
};

/// Throws unless every entry of the n × 3 array x is finite.
void check_coordinates(std::span<const double> x, const char* function, const char* name) {
  if (x.size() % 3 != 0)
    throw std::invalid_argument(std::string(function) + ": " + name + " has " +
                                std::to_string(x.size()) +
                                " entries, not a multiple of 3 (expected n × 3, row-major)");
  if (x.size() / 3 > int32_max)
    throw std::length_error(std::string(function) + ": " + name + " has more than 2³¹ − 1 points");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]))
      throw std::invalid_argument(std::string(function) + ": " + name + "[" +
                                  std::to_string(i / 3) + ", " + std::to_string(i % 3) +
                                  "] = " + str(x[i]) + " is not finite");
}

/// Validates all arguments and returns the facets' boxes inflated by `capture`.
Boxes inflated_boxes(std::span<const double> slave_x, std::span<const double> master_x,
                     std::span<const std::int32_t> facets, int nodes_per_facet, double capture,
                     const char* function) {
  const std::string fn(function);
  check_coordinates(slave_x, function, "slave_x");
  check_coordinates(master_x, function, "master_x");
  if (nodes_per_facet != 3 && nodes_per_facet != 4 && nodes_per_facet != 6 &&
      nodes_per_facet != 9)
    throw std::invalid_argument(fn + ": nodes_per_facet = " + std::to_string(nodes_per_facet) +
                                ", expected 3 or 6 (triangles), 4 or 9 (quadrilaterals)");
  const std::size_t k = static_cast<std::size_t>(nodes_per_facet);
  if (facets.size() % k != 0)
    throw std::invalid_argument(
        fn + ": facets has " + std::to_string(facets.size()) +
        " entries, not a multiple of nodes_per_facet = " + std::to_string(k));
  if (facets.size() / k > int32_max) throw std::length_error(fn + ": more than 2³¹ − 1 facets");
  if (!std::isfinite(capture) || capture < 0)
    throw std::invalid_argument(fn + ": capture = " + str(capture) +
                                ", expected a finite distance ≥ 0");
  const std::size_t num_master = master_x.size() / 3;
  for (std::size_t i = 0; i < facets.size(); ++i)
    if (facets[i] < 0 || static_cast<std::size_t>(facets[i]) >= num_master)
      throw std::out_of_range(fn + ": facets[" + std::to_string(i / k) + ", " +
                              std::to_string(i % k) + "] = " + std::to_string(facets[i]) +
                              " is not a master node index in [0, " + std::to_string(num_master) +
                              ")");

  const std::size_t num_facets = facets.size() / k;
  Boxes box{std::vector<double>(3 * num_facets), std::vector<double>(3 * num_facets)};
  for (std::size_t f = 0; f < num_facets; ++f) {
    for (std::size_t d = 0; d < 3; ++d) {
      double lo = master_x[3 * facets[k * f] + d], hi = lo;
      for (std::size_t a = 1; a < k; ++a) {
        const double v = master_x[3 * facets[k * f + a] + d];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      box.lo[3 * f + d] = lo - capture;
      box.hi[3 * f + d] = hi + capture;
    }
  }
  return box;
}

/// The one test both functions use, so that their results are identical.
inline bool in_box(const Boxes& box, std::size_t f, const double* x) {
  const double* lo = &box.lo[3 * f];
  const double* hi = &box.hi[3 * f];
  return lo[0] <= x[0] && x[0] <= hi[0] && lo[1] <= x[1] && x[1] <= hi[1] && lo[2] <= x[2] &&
         x[2] <= hi[2];
}

void check_total(std::size_t total, const char* function) {
  if (total > int32_max)
    throw std::length_error(std::string(function) + ": " + std::to_string(total) +
                            " candidate pairs exceed the int32 range of the offsets; "
                            "is capture far larger than the facets?");
}

/// The slave points as a nanoflann dataset (no copy).
struct PointCloud {
  std::span<const double> x;
  std::size_t kdtree_get_point_count() const { return x.size() / 3; }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return x[3 * i + d]; }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox&) const {
    return false;
  }
};

using PointTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>,
                                        PointCloud, 3, std::uint32_t>;

/// nanoflann result set: keeps the points of the ball that pass the exact box test of facet f.
struct BoxHits {
  const Boxes& box;
  std::size_t facet;
  std::span<const double> x;
  std::vector<std::int32_t>& hits;
  double radius_squared;

  std::size_t size() const { return 0; }
  bool full() const { return true; }
  double worstDist() const { return radius_squared; }
  bool addPoint(double, std::uint32_t i) {
    if (in_box(box, facet, &x[3 * i])) hits.push_back(static_cast<std::int32_t>(i));
    return true;
  }
};

}  // namespace

ContactCandidates find_candidates(std::span<const double> slave_x, std::span<const double> master_x,
                                  std::span<const std::int32_t> facets, int nodes_per_facet,
                                  double capture) {
  constexpr const char* function = "find_candidates";
  const Boxes box = inflated_boxes(slave_x, master_x, facets, nodes_per_facet, capture, function);
  const std::size_t n = slave_x.size() / 3;
  const std::size_t num_facets = box.lo.size() / 3;
  ContactCandidates result{std::vector<std::int32_t>(n + 1, 0), {}};
  if (n == 0 || num_facets == 0) return result;

  // Per facet, the slave points in its inflated box (CSR over facets).
  const PointCloud cloud{slave_x};
  const PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  const nanoflann::SearchParams unsorted(32, 0, false);
  std::vector<std::int32_t> hits;
  hits.reserve(2 * std::max(n, num_facets));
  std::vector<std::size_t> facet_offsets(num_facets + 1, 0);
  for (std::size_t f = 0; f < num_facets; ++f) {
    double centre[3], r2 = 0, scale = 0;
    for (std::size_t d = 0; d < 3; ++d) {
      centre[d] = 0.5 * (box.lo[3 * f + d] + box.hi[3 * f + d]);
      const double h = 0.5 * (box.hi[3 * f + d] - box.lo[3 * f + d]);
      r2 += h * h;
      scale = std::max(scale, std::abs(centre[d]));
    }
    // The ball of radius |h| around the centre contains the box; the margin (far above the
    // rounding of centre, h and the distance) keeps points on the box's surface in the ball.
    const double r = std::sqrt(r2);
    const double radius = r + 1e-12 * (r + scale);
    BoxHits found{box, f, slave_x, hits, radius * radius};
    tree.findNeighbors(found, centre, unsorted);
    facet_offsets[f + 1] = hits.size();
  }
  check_total(hits.size(), function);

  // Transpose by counting sort; facets are visited in ascending order, so each list ascends.
  for (std::int32_t i : hits) ++result.offsets[i + 1];
  std::partial_sum(result.offsets.begin(), result.offsets.end(), result.offsets.begin());
  result.indices.resize(hits.size());
  std::vector<std::int32_t> next(result.offsets.begin(), result.offsets.end() - 1);
  for (std::size_t f = 0; f < num_facets; ++f)
    for (std::size_t h = facet_offsets[f]; h < facet_offsets[f + 1]; ++h)
      result.indices[next[hits[h]]++] = static_cast<std::int32_t>(f);
  return result;
}

ContactCandidates find_candidates_brute_force(std::span<const double> slave_x,
                                              std::span<const double> master_x,
                                              std::span<const std::int32_t> facets,
                                              int nodes_per_facet, double capture) {
  constexpr const char* function = "find_candidates_brute_force";
  const Boxes box = inflated_boxes(slave_x, master_x, facets, nodes_per_facet, capture, function);
  const std::size_t n = slave_x.size() / 3;
  const std::size_t num_facets = box.lo.size() / 3;
  ContactCandidates result{{0}, {}};
  result.offsets.reserve(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t f = 0; f < num_facets; ++f)
      if (in_box(box, f, &slave_x[3 * i])) result.indices.push_back(static_cast<std::int32_t>(f));
    check_total(result.indices.size(), function);
    result.offsets.push_back(static_cast<std::int32_t>(result.indices.size()));
  }
  return result;
}

}  // namespace hypercontact
