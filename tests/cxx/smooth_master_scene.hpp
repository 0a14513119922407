// Test scenes of the smooth master (smooth_master.hpp), shared by test_smooth_master.cpp and
// test_smooth_master_friction.cpp: a curved, distorted quadrilateral or triangle cap, and slave
// points placed along the kernel's interpolated normal field.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <hypercontact/facet_shape.hpp>
#include <hypercontact/smooth_master.hpp>

#include "surface_scene.hpp"

namespace hypercontact::test {

/// An n × n grid of distorted quadrilaterals of size h (or each split into two triangles)
/// centred at the origin, on the sphere of radius `radius` about (0, 0, −radius) (radius 0: the
/// plane z = 0); `placed`: rotated and shifted off the axes. Facets counter-clockwise seen from
/// outside (+z), quad facet j n + i (triangles 2 (j n + i) and 2 (j n + i) + 1, split along the
/// diagonal from the cell's corner (i, j)), edge neighbours by the scene's compute_edge_neighbours.
/// order 1: 4- and 3-node facets, node j (n + 1) + i at grid point (i, j). order 2: 9- and 6-node
/// facets on the (2n + 1)² grid of half steps (node J (2n + 1) + I at (I/2, J/2)), the same
/// distortion evaluated at the half steps, so that the facets' edges are curved.
inline SurfaceScene cap(bool triangles, double radius, int n = 3, double h = 1.0,
                        bool placed = true, int order = 1) {
  SurfaceScene s;
  const int g = order * n;  // grid intervals per side
  for (int J = 0; J <= g; ++J)
    for (int I = 0; I <= g; ++I) {
      const double i = static_cast<double>(I) / order, j = static_cast<double>(J) / order;
      const double u = h * (i - 0.5 * n + 0.15 * std::sin(1.3 * i + 2.1 * j + 0.4));
      const double v = h * (j - 0.5 * n + 0.12 * std::cos(0.7 * i - 1.9 * j));
      const double z = radius > 0 ? std::sqrt(radius * radius - u * u - v * v) - radius : 0.0;
      const Eigen::Vector3d p(u, v, z);
      s.add_node(placed ? (test_rotation * p + test_shift).eval() : p);
    }
  s.nodes_per_facet = order == 1 ? (triangles ? 3 : 4) : (triangles ? 6 : 9);
  const auto node = [g](int I, int J) { return static_cast<std::int32_t>(J * (g + 1) + I); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (order == 1) {
        const std::int32_t a = node(i, j), b = node(i + 1, j), c = node(i + 1, j + 1),
                           d = node(i, j + 1);
        if (triangles)
          s.facets.insert(s.facets.end(), {a, b, c, a, c, d});
        else
          s.facets.insert(s.facets.end(), {a, b, c, d});
        continue;
      }
      const int I = 2 * i, J = 2 * j;
      const std::int32_t a = node(I, J), b = node(I + 2, J), c = node(I + 2, J + 2),
                         d = node(I, J + 2);
      const std::int32_t ab = node(I + 1, J), bc = node(I + 2, J + 1), cd = node(I + 1, J + 2),
                         da = node(I, J + 1), centre = node(I + 1, J + 1);
      if (triangles)  // (a, b, c; a–b, b–c, c–a) and (a, c, d; a–c, c–d, d–a)
        s.facets.insert(s.facets.end(), {a, b, c, ab, bc, centre, a, c, d, centre, cd, da});
      else
        s.facets.insert(s.facets.end(), {a, b, c, d, ab, bc, cd, da, centre});
    }
  s.compute_edge_neighbours();
  return s;
}

inline FacetConnectivity connectivity(const SurfaceScene& s) { return {s.facets, s.nodes_per_facet}; }

/// x_M(ξ) + g m(ξ)/|m(ξ)| on facet f: its projection along the nodal normals is (f, ξ), gap g.
inline Eigen::Vector3d above(const SurfaceScene& s, std::int32_t f, const Eigen::Vector2d& xi,
                             double g) {
  const NodeFacets at(connectivity(s), s.x.size() / 3);
  const Eigen::VectorXd N = facet_shape_functions(s.nodes_per_facet, xi);
  Eigen::Vector3d xm = Eigen::Vector3d::Zero(), m = Eigen::Vector3d::Zero();
  for (int a = 0; a < s.nodes_per_facet; ++a) {
    const std::int32_t node = connectivity(s).node(static_cast<std::size_t>(f), a);
    xm += N[a] * Eigen::Vector3d(&s.x[3 * static_cast<std::size_t>(node)]);
    m += N[a] * nodal_normal_value(node, at, connectivity(s), s.x);
  }
  return xm + g * m.normalized();
}

}  // namespace hypercontact::test
