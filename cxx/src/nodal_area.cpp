#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <hypercontact/nodal_area.hpp>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {

/// Checks the sizes of coords and cells (k nodes per cell) and the range of the node indices.
void check_mesh(std::span<const double> coords, std::span<const std::int32_t> cells, int k,
                std::size_t num_nodes) {
  if (coords.size() != 3 * num_nodes)
    throw std::invalid_argument(
        "nodal_areas: coords has " + std::to_string(coords.size()) +
        " entries, expected num_nodes × 3 = " + std::to_string(3 * num_nodes));
  if (cells.size() % k != 0)
    throw std::invalid_argument("nodal_areas: connectivity size " + std::to_string(cells.size()) +
                                " is not a multiple of " + std::to_string(k));
  for (std::int32_t v : cells)
    if (v < 0 || static_cast<std::size_t>(v) >= num_nodes)
      throw std::out_of_range("nodal_areas: node index " + std::to_string(v) + " outside [0, " +
                              std::to_string(num_nodes) + ")");
}

Eigen::Vector3d node(std::span<const double> coords, std::int32_t v) {
  return Eigen::Vector3d(coords[3 * v], coords[3 * v + 1], coords[3 * v + 2]);
}

}  // namespace

std::vector<double> nodal_areas(std::span<const double> coords, std::span<const std::int32_t> quads,
                                std::size_t num_nodes) {
  check_mesh(coords, quads, 4, num_nodes);
  // Reference corners (ξ_a, η_a) in cyclic order; N_a = ¼ (1 + ξ_a ξ)(1 + η_a η).
  constexpr std::array<double, 4> xi_a{-1, 1, 1, -1};
  constexpr std::array<double, 4> eta_a{-1, -1, 1, 1};
  const double gauss = 1 / std::sqrt(3.0);  // 2×2 Gauss points ±1/√3, weights 1
  std::vector<double> area(num_nodes, 0.0);
  for (std::size_t q = 0; q < quads.size() / 4; ++q) {
    std::array<Eigen::Vector3d, 4> x;
    for (int a = 0; a < 4; ++a) x[a] = node(coords, quads[4 * q + a]);
    for (double xi : {-gauss, gauss}) {
      for (double eta : {-gauss, gauss}) {
        Eigen::Vector3d dx_dxi = Eigen::Vector3d::Zero(), dx_deta = Eigen::Vector3d::Zero();
        for (int a = 0; a < 4; ++a) {
          dx_dxi += 0.25 * xi_a[a] * (1 + eta_a[a] * eta) * x[a];
          dx_deta += 0.25 * eta_a[a] * (1 + xi_a[a] * xi) * x[a];
        }
        const double jacobian = dx_dxi.cross(dx_deta).norm();
        for (int a = 0; a < 4; ++a)
          area[quads[4 * q + a]] += 0.25 * (1 + xi_a[a] * xi) * (1 + eta_a[a] * eta) * jacobian;
      }
    }
  }
  return area;
}

std::vector<double> nodal_areas_tri(std::span<const double> coords,
                                    std::span<const std::int32_t> triangles,
                                    std::size_t num_nodes) {
  check_mesh(coords, triangles, 3, num_nodes);
  std::vector<double> area(num_nodes, 0.0);
  for (std::size_t t = 0; t < triangles.size() / 3; ++t) {
    const std::int32_t* v = &triangles[3 * t];
    const Eigen::Vector3d x0 = node(coords, v[0]);
    const double third = (node(coords, v[1]) - x0).cross(node(coords, v[2]) - x0).norm() / 6.0;
    for (int a = 0; a < 3; ++a) area[v[a]] += third;
  }
  return area;
}

}  // namespace hypercontact
