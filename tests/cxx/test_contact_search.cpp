// Broad-phase contact search: the k-d tree search equals the brute force exactly, on seeded
// random surfaces; boundary cases by hand; bad input is refused with a message naming it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <hypercontact/contact_search.hpp>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace hypercontact {
namespace {

using Index = std::int32_t;

/// A parametrisation (u, v) ↦ x of a surface.
using Map = std::function<Eigen::Vector3d(double, double)>;

/// A master surface: m × 3 node coordinates and f × k connectivity, row-major.
struct Surface {
  std::vector<double> x;
  std::vector<Index> facets;
  int k = 4;
};

/// Structured (nx + 1) × (ny + 1) grid of the parameter square [0, 1]², mapped by `map`;
/// quadrilaterals in cyclic order, or each quadrilateral split into two triangles.
Surface grid(int nx, int ny, bool triangles, const Map& map) {
  Surface s;
  s.k = triangles ? 3 : 4;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const Eigen::Vector3d p = map(double(i) / nx, double(j) / ny);
      s.x.insert(s.x.end(), {p.x(), p.y(), p.z()});
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Index a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      if (triangles)
        s.facets.insert(s.facets.end(), {a, b, c, a, c, d});
      else
        s.facets.insert(s.facets.end(), {a, b, c, d});
    }
  return s;
}

/// Random points in the bounding box of `s` grown by `margin` on every side.
std::vector<double> points_around(const Surface& s, std::size_t n, double margin,
                                  std::mt19937& rng) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (std::size_t i = 0; i < s.x.size() / 3; ++i) {
    lo = lo.cwiseMin(Eigen::Vector3d(&s.x[3 * i]));
    hi = hi.cwiseMax(Eigen::Vector3d(&s.x[3 * i]));
  }
  std::vector<double> x;
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      x.push_back(std::uniform_real_distribution<double>(lo[d] - margin, hi[d] + margin)(rng));
  return x;
}

/// n points map(u, v) + N(0, σ²) per coordinate, (u, v) uniform in [−0.1, 1.1]²: half of them
/// exactly on the mapped surface (σ = 0), half jittered with σ = jitter.
std::vector<double> points_near(const Map& map, std::size_t n, double jitter, std::mt19937& rng) {
  std::uniform_real_distribution<double> param(-0.1, 1.1);
  std::normal_distribution<double> normal(0, 1);
  std::vector<double> x;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector3d p = map(param(rng), param(rng));
    if (i % 2) p += jitter * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    x.insert(x.end(), {p.x(), p.y(), p.z()});
  }
  return x;
}

/// Both searches; expects identical, well-formed results and returns them.
ContactCandidates search_both(const std::vector<double>& slave, const Surface& s, double c) {
  const ContactCandidates tree = find_candidates(slave, s.x, s.facets, s.k, c);
  const ContactCandidates brute = find_candidates_brute_force(slave, s.x, s.facets, s.k, c);
  EXPECT_EQ(tree.offsets, brute.offsets);
  EXPECT_EQ(tree.indices, brute.indices);
  const std::size_t n = slave.size() / 3;
  EXPECT_EQ(tree.offsets.size(), n + 1);
  EXPECT_EQ(tree.offsets.front(), 0);
  EXPECT_EQ(static_cast<std::size_t>(tree.offsets.back()), tree.indices.size());
  for (std::size_t i = 0; i < n; ++i)
    for (Index p = tree.offsets[i] + 1; p < tree.offsets[i + 1]; ++p)
      EXPECT_LT(tree.indices[p - 1], tree.indices[p]) << "list of point " << i << " not ascending";
  return tree;
}

std::size_t empty_lists(const ContactCandidates& r) {
  std::size_t count = 0;
  for (std::size_t i = 0; i + 1 < r.offsets.size(); ++i) count += r.offsets[i] == r.offsets[i + 1];
  return count;
}

const Eigen::Matrix3d rotation =
    Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();

TEST(ContactSearch, FlatGridsMatchBruteForce) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 6; ++trial) {
    const int nx = 3 + rng() % 25, ny = 3 + rng() % 25;
    const bool rotated = trial % 2, triangles = trial % 3 == 0;
    const double sx = 0.5 + trial, sy = 2.0 / (1 + trial);
    const Map map = [&](double u, double v) {
      const Eigen::Vector3d p(sx * u, sy * v, 0.3);
      return rotated ? Eigen::Vector3d(rotation * p) : p;
    };
    const Surface s = grid(nx, ny, triangles, map);
    const double h = std::min(sx / nx, sy / ny);
    for (double c : {0.0, 0.05 * h, 0.7 * h}) {
      std::vector<double> slave = points_near(map, 400, 0.5 * h, rng);
      const std::vector<double> around = points_around(s, 100, 2 * h, rng);
      slave.insert(slave.end(), around.begin(), around.end());
      const ContactCandidates r = search_both(slave, s, c);
      // Most points on the surface inside the square have a candidate; (u, v) outside
      // [−c/h, 1 + c/h]² (about 30 %) and most of the random points have none.
      EXPECT_GT(r.indices.size(), 100u) << "trial " << trial << ", c = " << c;
      EXPECT_GT(empty_lists(r), 100u) << "trial " << trial << ", c = " << c;
    }
  }
}

TEST(ContactSearch, WarpedGridsMatchBruteForce) {
  std::mt19937 rng(12);
  for (int trial = 0; trial < 6; ++trial) {
    const int n = 10 + 7 * trial;
    const double amplitude = 0.02 * (trial + 1);
    // A wavy sheet and a spherical cap (curved in both directions).
    const Map map = [&](double u, double v) {
      if (trial < 3) return Eigen::Vector3d(u, v, amplitude * std::sin(7 * u) * std::cos(5 * v));
      const double theta = 0.2 + 1.0 * u, phi = 2.5 * v;
      return Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                             std::cos(theta));
    };
    const Surface s = grid(n, n + 3, trial % 2, map);
    // Points on and near the surface (as in contact), on the nodes, and random around.
    std::vector<double> slave = points_near(map, 1000, 0.3 / n, rng);
    const std::vector<double> around = points_around(s, 300, 0.3, rng);
    slave.insert(slave.end(), around.begin(), around.end());
    slave.insert(slave.end(), s.x.begin(), s.x.end());
    for (double c : {0.0, 0.1 / n, 1.0 / n}) {
      const ContactCandidates r = search_both(slave, s, c);
      EXPECT_GT(r.indices.size(), 800u) << "trial " << trial << ", c = " << c;
      EXPECT_GT(empty_lists(r), 50u) << "trial " << trial << ", c = " << c;
    }
  }
}

TEST(ContactSearch, RandomFacetSoupsMatchBruteForce) {
  // Facets of sizes spread over three decades, random orientation, shared and repeated nodes,
  // degenerate facets; a tree over facet centroids with one radius would still be exact but
  // slow here, a wrong per-facet radius would drop candidates.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 8; ++trial) {
    Surface s;
    s.k = trial % 2 ? 3 : 4;
    const int num_facets = 50 + 60 * trial;
    for (int f = 0; f < num_facets; ++f) {
      const Eigen::Vector3d centre(unit(rng), unit(rng), unit(rng));
      const double size = std::pow(10.0, -3 + 3 * unit(rng));
      for (int a = 0; a < s.k; ++a) {
        const Eigen::Vector3d p =
            centre + size * Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
        s.x.insert(s.x.end(), {p.x(), p.y(), p.z()});
      }
    }
    const Index m = static_cast<Index>(s.x.size() / 3);
    for (int f = 0; f < num_facets; ++f)
      for (int a = 0; a < s.k; ++a)
        s.facets.push_back(f % 5 == 0 ? static_cast<Index>(rng() % m) : s.k * f + a);
    // Degenerate: every node the same (a zero-size box).
    s.facets.insert(s.facets.end(), static_cast<std::size_t>(s.k), Index{0});
    std::vector<double> slave = points_around(s, 1500, 0.1, rng);
    slave.insert(slave.end(), s.x.begin(), s.x.end());             // points on the nodes themselves
    slave.insert(slave.end(), slave.begin(), slave.begin() + 30);  // repeated points
    for (double c : {0.0, 1e-3, 0.03}) {
      const ContactCandidates r = search_both(slave, s, c);
      EXPECT_GT(r.indices.size(), static_cast<std::size_t>(m)) << "trial " << trial;
    }
  }
}

TEST(ContactSearch, ZeroCaptureOnAxisAlignedGridGivesIncidentFacets) {
  // Slave points exactly on the nodes of a flat axis-aligned grid, c = 0: the closed boxes
  // that contain a node are exactly those of the facets that share it (boundary inclusive).
  const int nx = 7, ny = 5;
  const Surface s = grid(nx, ny, false, [](double u, double v) {
    return Eigen::Vector3d(10 + 3 * u, -4 + 2 * v, 1.5);
  });
  const ContactCandidates r = search_both(s.x, s, 0.0);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      std::vector<Index> expected;
      for (int fj = std::max(j - 1, 0); fj <= std::min(j, ny - 1); ++fj)
        for (int fi = std::max(i - 1, 0); fi <= std::min(i, nx - 1); ++fi)
          expected.push_back(fj * nx + fi);
      const int p = j * (nx + 1) + i;
      const std::vector<Index> actual(r.indices.begin() + r.offsets[p],
                                      r.indices.begin() + r.offsets[p + 1]);
      EXPECT_EQ(actual, expected) << "node " << i << ", " << j;
    }
}

TEST(ContactSearch, CaptureInflatesTheBoxOnEverySide) {
  // One unit square in z = 0 with c = 0.5: the inflated box is [−0.5, 1.5]² × [−0.5, 0.5].
  const Surface s{{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 3}, 4};
  const double c = 0.5, tiny = 1e-9;
  const std::vector<std::vector<double>> inside = {
      {0.5, 0.5, 0},
      {1.5, 0.5, 0},
      {-0.5, 0.5, 0.5},
      // The corner of the inflated box: at |h + c| = 1.5 from the centre, beyond c + |h|.
      {1.5, 1.5, 0.5},
      {-0.5, -0.5, -0.5}};
  const std::vector<std::vector<double>> outside = {{1.5 + tiny, 0.5, 0},   {0.5, -0.5 - tiny, 0},
                                                    {0.5, 0.5, 0.5 + tiny}, {1.5 + tiny, 1.5, 0.5},
                                                    {100, 100, 100},        {0.5, 0.5, -1e6}};
  for (const auto& x : inside) {
    const ContactCandidates r = search_both(x, s, c);
    EXPECT_EQ(r.indices, std::vector<Index>{0}) << x[0] << ", " << x[1] << ", " << x[2];
  }
  for (const auto& x : outside) {
    const ContactCandidates r = search_both(x, s, c);
    EXPECT_TRUE(r.indices.empty()) << x[0] << ", " << x[1] << ", " << x[2];
  }
}

TEST(ContactSearch, FarPointsGetEmptyLists) {
  std::mt19937 rng(14);
  const Surface s = grid(20, 20, false, [](double u, double v) {
    return Eigen::Vector3d(u, v, 0.1 * std::sin(6 * u));
  });
  const double c = 0.05;
  std::vector<double> slave = points_around(s, 300, 0.0, rng);  // near: most have candidates
  const std::size_t near = 300;
  std::normal_distribution<double> normal(0, 1);
  for (int i = 0; i < 300; ++i) {  // far: at distance 2 … 1002 in a random direction
    const Eigen::Vector3d dir = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const Eigen::Vector3d p = Eigen::Vector3d(0.5, 0.5, 0) + (2 + 1000 * i / 300.0) * dir;
    slave.insert(slave.end(), {p.x(), p.y(), p.z()});
  }
  const ContactCandidates r = search_both(slave, s, c);
  for (std::size_t i = near; i < near + 300; ++i)
    EXPECT_EQ(r.offsets[i], r.offsets[i + 1]) << "far point " << i;
  EXPECT_LT(empty_lists(r), near + 300 - 100) << "most near points have candidates";
}

TEST(ContactSearch, LargerCaptureGivesSupersets) {
  std::mt19937 rng(15);
  const Surface s =
      grid(15, 12, true, [](double u, double v) { return Eigen::Vector3d(u, v, 0.2 * u * v); });
  const std::vector<double> slave = points_around(s, 400, 0.2, rng);
  const ContactCandidates small = search_both(slave, s, 0.01), large = search_both(slave, s, 0.1);
  EXPECT_GT(large.indices.size(), small.indices.size());
  for (std::size_t i = 0; i < slave.size() / 3; ++i)
    EXPECT_TRUE(std::includes(
        large.indices.begin() + large.offsets[i], large.indices.begin() + large.offsets[i + 1],
        small.indices.begin() + small.offsets[i], small.indices.begin() + small.offsets[i + 1]))
        << "point " << i;
}

TEST(ContactSearch, EmptyInputs) {
  const Surface s = grid(3, 3, false, [](double u, double v) { return Eigen::Vector3d(u, v, 0); });
  const std::vector<double> none, two_points = {0.5, 0.5, 0, 0.2, 0.1, 0};
  const std::vector<Index> no_facets;
  // No slave points.
  ContactCandidates r = search_both(none, s, 0.1);
  EXPECT_EQ(r.offsets, std::vector<Index>{0});
  EXPECT_TRUE(r.indices.empty());
  // No facets (with or without master nodes).
  for (const std::vector<double>& master : {s.x, none}) {
    for (auto* search : {&find_candidates, &find_candidates_brute_force}) {
      r = search(two_points, master, no_facets, 3, 0.1);
      EXPECT_EQ(r.offsets, (std::vector<Index>{0, 0, 0}));
      EXPECT_TRUE(r.indices.empty());
    }
  }
  // Nothing at all.
  r = find_candidates(none, none, no_facets, 4, 0.0);
  EXPECT_EQ(r.offsets, std::vector<Index>{0});
}

/// Expects `call` to throw E with a message containing `text`.
template <class E>
void expect_throw_with(const std::function<void()>& call, const std::string& text) {
  try {
    call();
    ADD_FAILURE() << "no exception; expected one mentioning '" << text << "'";
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos)
        << "message '" << e.what() << "' does not mention '" << text << "'";
  }
}

TEST(ContactSearch, RejectsBadInput) {
  const std::vector<double> x = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<Index> quad = {0, 1, 2, 3};
  const std::vector<double> slave = {0.5, 0.5, 0};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  using reals = std::vector<double>;
  using indices = std::vector<Index>;
  for (auto* search : {&find_candidates, &find_candidates_brute_force}) {
    using IA = std::invalid_argument;
    expect_throw_with<IA>(
        [&] {
          search(reals{0.5, 0.5}, x, quad, 4, 0.1);
        },
        "slave_x has 2 entries");
    expect_throw_with<IA>(
        [&] {
          search(slave, reals{0, 0, 0, 1}, quad, 4, 0.1);
        },
        "master_x has 4 entries");
    expect_throw_with<IA>(
        [&] {
          search(slave, x, indices{0, 1, 2}, 4, 0.1);
        },
        "facets has 3 entries, not a multiple of nodes_per_facet = 4");
    expect_throw_with<IA>([&] { search(slave, x, quad, 2, 0.1); }, "nodes_per_facet = 2");
    expect_throw_with<IA>([&] { search(slave, x, quad, 5, 0.1); }, "nodes_per_facet = 5");
    for (double c : {-0.1, nan, inf})
      expect_throw_with<IA>([&] { search(slave, x, quad, 4, c); }, "capture =");
    expect_throw_with<IA>(
        [&] {
          search(reals{0.5, nan, 0}, x, quad, 4, 0.1);
        },
        "slave_x[0, 1] = nan is not finite");
    std::vector<double> bad_master = x;
    bad_master[7] = -inf;
    expect_throw_with<IA>([&] { search(slave, bad_master, quad, 4, 0.1); },
                          "master_x[2, 1] = -inf is not finite");
    expect_throw_with<std::out_of_range>(
        [&] {
          search(slave, x, indices{0, 1, 2, 4}, 4, 0.1);
        },
        "facets[0, 3] = 4 is not a master node index in [0, 4)");
    expect_throw_with<std::out_of_range>(
        [&] {
          search(slave, x, indices{0, 1, 2, 3, 0, -1, 2, 3}, 4, 0.1);
        },
        "facets[1, 1] = -1");
    // A facet index is checked even when there are no slave points.
    expect_throw_with<std::out_of_range>(
        [&] {
          search(reals{}, x, indices{0, 1, 9}, 3, 0.1);
        },
        "facets[0, 2] = 9");
  }
  expect_throw_with<std::invalid_argument>(
      [&] { find_candidates_brute_force(slave, x, quad, 4, -1); }, "find_candidates_brute_force:");
}

}  // namespace
}  // namespace hypercontact
