// Test scenes of deformable–deformable contact: a master grid of facets z = height(x, y), slave
// points (single nodes or Gauss points of slave quadrilaterals), every facet a candidate of
// every point (so that the narrow phase alone decides), each coordinate its own dof.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <functional>
#include <hypercontact/narrow_phase.hpp>
#include <hypercontact/node_to_surface.hpp>
#include <hypercontact/surface_contact.hpp>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "contact_elements_fd.hpp"

namespace hypercontact::test {

struct SurfaceScene {
  std::vector<double> x;  ///< all contact nodes, 3 per node
  std::vector<std::int32_t> point_nodes, facets, edge_neighbour, offsets{0}, candidates;
  std::vector<double> point_weights, point_area, multipliers;
  double eps_n = 1e3, smoothing = 0.0;
  int nodes_per_facet = 4;

  std::int32_t num_nodes() const { return static_cast<std::int32_t>(x.size() / 3); }
  std::vector<std::int32_t> dofs;  ///< 3 n + k for coordinate k of node n

  std::int32_t add_node(const Eigen::Vector3d& p) {
    for (int k = 0; k < 3; ++k) dofs.push_back(static_cast<std::int32_t>(x.size()) + k);
    x.insert(x.end(), {p.x(), p.y(), p.z()});
    return num_nodes() - 1;
  }

  /// nx × ny quadrilaterals on [x0, x0 + nx h] × [y0, y0 + ny h], z = height(x, y), nodes
  /// counter-clockwise seen from +z (the outward side); with `triangles`, each split into two.
  void add_master_grid(int nx, int ny, double x0, double y0, double h,
                       const std::function<double(double, double)>& height,
                       bool triangles = false) {
    std::vector<std::int32_t> node((nx + 1) * (ny + 1));
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const double px = x0 + i * h, py = y0 + j * h;
        node[j * (nx + 1) + i] = add_node({px, py, height(px, py)});
      }
    nodes_per_facet = triangles ? 3 : 4;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::int32_t a = node[j * (nx + 1) + i], b = node[j * (nx + 1) + i + 1],
                           c = node[(j + 1) * (nx + 1) + i + 1], d = node[(j + 1) * (nx + 1) + i];
        if (triangles)
          facets.insert(facets.end(), {a, b, c, a, c, d});
        else
          facets.insert(facets.end(), {a, b, c, d});
      }
    compute_edge_neighbours();
  }

  /// Facet across each edge k (corner k → corner k + 1), −1 on the boundary.
  void compute_edge_neighbours() {
    const int n = nodes_per_facet;
    const int c = (n == 3 || n == 6) ? 3 : 4;  // corners = edges
    const std::size_t nf = facets.size() / n;
    edge_neighbour.assign(c * nf, -1);
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> owner;
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < c; ++k) {
        const std::int32_t a = facets[n * f + k], b = facets[n * f + (k + 1) % c];
        const auto key = std::minmax(a, b);
        if (auto it = owner.find(key); it != owner.end()) {
          const std::int32_t g = it->second / c;
          edge_neighbour[c * f + k] = g;
          edge_neighbour[it->second] = static_cast<std::int32_t>(f);
        } else {
          owner[key] = static_cast<std::int32_t>(c * f + k);
        }
      }
  }

  /// A slave point x_s = Σ M_i x_i of up to 4 nodes, weight w; every facet a candidate (none
  /// without `candidates`).
  void add_point(const std::vector<std::int32_t>& nodes, const std::vector<double>& weights,
                 double w, bool with_candidates = true) {
    for (int i = 0; i < 4; ++i) {
      point_nodes.push_back(i < static_cast<int>(nodes.size()) ? nodes[i] : -1);
      point_weights.push_back(i < static_cast<int>(weights.size()) ? weights[i] : 0.0);
    }
    point_area.push_back(w);
    const std::int32_t nf = static_cast<std::int32_t>(facets.size() / nodes_per_facet);
    for (std::int32_t f = 0; with_candidates && f < nf; ++f) candidates.push_back(f);
    offsets.push_back(static_cast<std::int32_t>(candidates.size()));
  }

  /// A slave node at p as a point of weight w.
  std::int32_t add_slave_node(const Eigen::Vector3d& p, double w) {
    const std::int32_t n = add_node(p);
    add_point({n}, {1.0}, w);
    return n;
  }

  /// A slave quadrilateral (corners counter-clockwise seen from −z) as its 2 × 2 Gauss points.
  void add_slave_quad(const std::vector<Eigen::Vector3d>& corners, double w) {
    std::vector<std::int32_t> q;
    for (const Eigen::Vector3d& c : corners) q.push_back(add_node(c));
    const double g = 1 / std::sqrt(3.0);
    for (const double a : {-g, g})
      for (const double b : {-g, g})
        add_point(q,
                  {0.25 * (1 - a) * (1 - b), 0.25 * (1 + a) * (1 - b), 0.25 * (1 + a) * (1 + b),
                   0.25 * (1 - a) * (1 + b)},
                  w);
  }

  /// The input at coordinates y (the scene's own by default).
  SurfaceContactInput input(std::span<const double> y) const {
    return {y,
            point_nodes,
            point_weights,
            point_area,
            {facets, nodes_per_facet},
            edge_neighbour,
            offsets,
            candidates,
            dofs,
            eps_n,
            multipliers,
            smoothing};
  }
  SurfaceContactInput input() const { return input(x); }

  /// Slave point p's nodes and weights, and its closest facet by closest_facet (the narrow phase
  /// without the rim rules: for points whose closest point is not on the master's boundary).
  struct Pairing {
    std::vector<std::int32_t> nodes;
    NodeCoordinates slave;
    Eigen::VectorXd weights;
    ClosestFacet closest;
    NodeCoordinates master;  ///< the closest facet's nodes
    double touch;            ///< 1e-10 × its diagonal x_2 − x_0, as the evaluation's
  };
  Pairing pairing(std::size_t p) const {
    Pairing out;
    for (int i = 0; i < 4; ++i)
      if (point_nodes[4 * p + i] >= 0) out.nodes.push_back(point_nodes[4 * p + i]);
    const auto ns = static_cast<Eigen::Index>(out.nodes.size());
    out.slave.resize(3, ns);
    out.weights.resize(ns);
    for (Eigen::Index i = 0; i < ns; ++i) {
      out.slave.col(i) = Eigen::Vector3d(&x[3 * out.nodes[i]]);
      out.weights[i] = point_weights[4 * p + i];
    }
    const std::span<const std::int32_t> c(candidates.data() + offsets[p],
                                          candidates.data() + offsets[p + 1]);
    out.closest = closest_facet(out.slave * out.weights, c, {facets, nodes_per_facet}, x);
    out.master = gather_facet(out.closest.facet, {facets, nodes_per_facet}, x);
    out.touch = 1e-10 * (out.master.col(2) - out.master.col(0)).norm();
    return out;
  }
  /// The dofs of [the point's nodes, the facet's nodes].
  std::vector<std::int32_t> element_dofs(const Pairing& pr) const {
    std::vector<std::int32_t> out;
    auto add = [&](std::int32_t n) {
      for (int k = 0; k < 3; ++k) out.push_back(dofs[3 * n + k]);
    };
    for (std::int32_t n : pr.nodes) add(n);
    for (int a = 0; a < nodes_per_facet; ++a) add(facets[nodes_per_facet * pr.closest.facet + a]);
    return out;
  }
  double multiplier(std::size_t p) const { return multipliers.empty() ? 0.0 : multipliers[p]; }
};

/// A 2 × 2 warped master on [0, 2]² (quadrilaterals, or each split into two triangles), three
/// slave nodes (below cells 0 and 3, above cell 1) and the four Gauss points of a slave
/// quadrilateral below cell 2.
inline SurfaceScene face_scene(bool triangles = false) {
  SurfaceScene s;
  s.add_master_grid(
      2, 2, 0.0, 0.0, 1.0, [](double x, double y) { return 0.1 * std::sin(x) * std::cos(1.3 * y); },
      triangles);
  s.add_slave_node({0.4, 0.6, -0.05}, 0.3);
  s.add_slave_node({1.6, 1.3, -0.05}, 0.2);
  s.add_slave_node({1.5, 0.5, 0.3}, 0.25);
  s.add_slave_quad({{0.2, 1.2, -0.05}, {0.8, 1.25, -0.06}, {0.75, 1.8, -0.07}, {0.25, 1.7, -0.08}},
                   0.07);
  return s;
}

/// A valley z = 0.5 |x| (two facets meeting along x = 0) and a slave node deep below its line:
/// the closest point of both facets is on their common edge (Edge, the lower facet wins).
inline SurfaceScene valley_scene() {
  SurfaceScene s;
  s.add_master_grid(2, 1, -1.0, 0.0, 1.0, [](double x, double) { return 0.5 * std::abs(x); });
  s.add_slave_node({0.01, 0.55, -0.2}, 0.3);
  return s;
}

/// A bowl z = 0.5 (|x| + |y|) (four facets around the node at the origin) and a slave node deep
/// below it: the closest point of every facet is that node (Vertex).
inline SurfaceScene bowl_scene() {
  SurfaceScene s;
  s.add_master_grid(2, 2, -1.0, -1.0, 1.0,
                    [](double x, double y) { return 0.5 * (std::abs(x) + std::abs(y)); });
  s.add_slave_node({0.01, 0.02, -0.2}, 0.3);
  return s;
}

}  // namespace hypercontact::test
