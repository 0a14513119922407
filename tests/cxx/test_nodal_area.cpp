// Nodal areas of bilinear quadrilaterals and linear triangles against closed forms.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <hypercontact/nodal_area.hpp>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace hypercontact {
namespace {

/// An arbitrary rotation, so that the surfaces are not aligned with the axes.
const Eigen::Matrix3d rotation =
    Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();

/// Row-major n × 3 coordinates of 2-D points (x, y) placed in a rotated, shifted plane.
std::vector<double> embed(const std::vector<Eigen::Vector2d>& points) {
  std::vector<double> coords;
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector3d x =
        rotation * Eigen::Vector3d(p.x(), p.y(), 0) + Eigen::Vector3d(1, 2, 3);
    coords.insert(coords.end(), {x.x(), x.y(), x.z()});
  }
  return coords;
}

TEST(NodalArea, RectangleGivesQuarterPerVertex) {
  const std::vector<double> coords = embed({{0, 0}, {2, 0}, {2, 0.5}, {0, 0.5}});
  const std::vector<double> area = nodal_areas(coords, std::vector<std::int32_t>{0, 1, 2, 3}, 4);
  for (double a : area) EXPECT_NEAR(a, 0.25, 1e-14);
}

TEST(NodalArea, TrapezoidMatchesClosedForm) {
  // Nodes (−b, 0), (b, 0), (t, h), (−t, h): ∫N dA = h(2b + t)/6 at the bottom, h(b + 2t)/6 top.
  const double b = 1.0, t = 0.5, h = 0.8;
  const std::vector<double> coords = embed({{-b, 0}, {b, 0}, {t, h}, {-t, h}});
  const std::vector<double> area = nodal_areas(coords, std::vector<std::int32_t>{0, 1, 2, 3}, 4);
  EXPECT_NEAR(area[0], h * (2 * b + t) / 6, 1e-14);
  EXPECT_NEAR(area[1], h * (2 * b + t) / 6, 1e-14);
  EXPECT_NEAR(area[2], h * (b + 2 * t) / 6, 1e-14);
  EXPECT_NEAR(area[3], h * (b + 2 * t) / 6, 1e-14);
}

TEST(NodalArea, DistortedMeshSumsToTotalArea) {
  // 3 × 3 nodes, 4 distorted convex quads; total area by the shoelace formula.
  const std::vector<Eigen::Vector2d> p = {{0, 0},     {1.1, 0.1}, {2, -0.1},
                                          {0.1, 0.9}, {1.3, 1.2}, {2.2, 1.0},
                                          {-0.1, 2},  {0.9, 2.1}, {2.1, 2.3}};
  const std::vector<std::int32_t> quads = {0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7};
  double total = 0;
  for (std::size_t q = 0; q < 4; ++q)
    for (std::size_t a = 0; a < 4; ++a) {
      const Eigen::Vector2d u = p[quads[4 * q + a]], v = p[quads[4 * q + (a + 1) % 4]];
      total += 0.5 * (u.x() * v.y() - v.x() * u.y());
    }
  const std::vector<double> area = nodal_areas(embed(p), quads, 9);
  EXPECT_NEAR(std::accumulate(area.begin(), area.end(), 0.0), total, 1e-13);
  for (double a : area) EXPECT_GT(a, 0);
}

TEST(NodalArea, TrianglesGiveThirdPerVertex) {
  const std::vector<double> coords = embed({{0, 0}, {2, 0}, {0, 1}, {2, 1}});
  const std::vector<double> area =
      nodal_areas_tri(coords, std::vector<std::int32_t>{0, 1, 2, 1, 3, 2}, 4);
  EXPECT_NEAR(area[0], 1.0 / 3, 1e-14);
  EXPECT_NEAR(area[1], 2.0 / 3, 1e-14);
  EXPECT_NEAR(area[2], 2.0 / 3, 1e-14);
  EXPECT_NEAR(area[3], 1.0 / 3, 1e-14);
}

TEST(NodalArea, RejectsBadInput) {
  const std::vector<double> coords = embed({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_THROW(nodal_areas(coords, std::vector<std::int32_t>{0, 1, 2, 4}, 4), std::out_of_range);
  EXPECT_THROW(nodal_areas(coords, std::vector<std::int32_t>{0, 1, 2, -1}, 4), std::out_of_range);
  EXPECT_THROW(nodal_areas(coords, std::vector<std::int32_t>{0, 1, 2}, 4), std::invalid_argument);
  EXPECT_THROW(nodal_areas(coords, std::vector<std::int32_t>{0, 1, 2, 3}, 5),
               std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
