// The kernels' input structs for Python: the same fields, holding the numpy arrays (so that the
// spans of the C++ input stay valid while the Python object lives); view() checks the shapes and
// returns the C++ input.
#pragma once

#include <hypercontact/rigid_contact.hpp>
#include <hypercontact/surface_contact.hpp>
#include <hypercontact/surface_contact_friction.hpp>
#include <hypercontact/surface_element_types.hpp>

#include "array.hpp"

namespace hypercontact::python {

/// RigidContactInput: x (n, 3), area (n,), dofs (n, 3k) int32, multipliers (n,) or (0,),
/// point_weights (n, k) or (0, 0) (nodal: k = 1).
struct OwnedRigidContactInput {
  Obstacle obstacle;
  RealArray x, area;
  IndexArray dofs;
  double eps_n;
  RealArray multipliers;
  double smoothing;
  RealArray point_weights;
  int points_per_facet = 0;

  RigidContactInput view() const {
    check_shape(x, "x", {any, 3});
    check_shape(area, "area", {x.shape(0)});
    check_shape(multipliers, "multipliers", {any});
    py::ssize_t k = 1;  // (0, 0) or (0,): nodes; (n, k): points of k nodes (n may be 0)
    if (point_weights.ndim() == 2 && point_weights.shape(1) > 0) {
      check_shape(point_weights, "point_weights", {x.shape(0), any});
      k = point_weights.shape(1);
    } else if (point_weights.size() > 0) {
      check_shape(point_weights, "point_weights", {x.shape(0), any});
    }
    const py::ssize_t constraints =
        points_per_facet > 0 ? x.shape(0) / points_per_facet : x.shape(0);
    check_shape(dofs, "dofs", {constraints, 3 * k});
    return {obstacle,        as_span(x),           as_span(area), as_span(dofs),
            eps_n,           as_span(multipliers), smoothing,     as_span(point_weights),
            points_per_facet};
  }
};

/// SurfaceContactInput: x (nn, 3); point_nodes, point_weights (np, k ≤ 9); point_area (np,);
/// facets (nf, k), k = 3, 6 (triangles) or 4, 9 (quadrilaterals); edge_neighbour (nf, corners);
/// offsets (np + 1,),
/// candidates; dofs (nn, 3) int32; multipliers (np,) or (0,).
struct OwnedSurfaceContactInput {
  RealArray x;
  IndexArray point_nodes;
  RealArray point_weights, point_area;
  IndexArray facets, edge_neighbour, offsets, candidates, dofs;
  double eps_n;
  RealArray multipliers;
  double smoothing;
  bool smooth_master = false;

  SurfaceContactInput view() const {
    check_shape(multipliers, "multipliers", {any});
    check_shape(x, "x", {any, 3});
    check_shape(point_area, "point_area", {any});
    check_shape(point_nodes, "point_nodes", {point_area.shape(0), any});
    if (point_nodes.shape(1) < 1 || point_nodes.shape(1) > max_slave_nodes)
      throw py::value_error("point_nodes: expected 1 to " + std::to_string(max_slave_nodes) +
                            " nodes per slave point, got shape " +
                            shape_string({point_nodes.shape(0), point_nodes.shape(1)}));
    check_shape(point_weights, "point_weights", {point_area.shape(0), point_nodes.shape(1)});
    check_shape(facets, "facets", {any, any});
    const auto k = static_cast<int>(facets.shape(1));
    if (k != 3 && k != 4 && k != 6 && k != 9)
      throw py::value_error("facets: expected shape (*, 3), (*, 4), (*, 6) or (*, 9), got " +
                            shape_string({facets.shape(0), facets.shape(1)}));
    const py::ssize_t corners = (k == 3 || k == 6) ? 3 : 4;
    check_shape(edge_neighbour, "edge_neighbour", {facets.shape(0), corners});
    check_shape(offsets, "offsets", {point_area.shape(0) + 1});
    check_shape(candidates, "candidates", {any});
    check_shape(dofs, "dofs", {x.shape(0), 3});
    return {as_span(x),
            as_span(point_nodes),
            as_span(point_weights),
            as_span(point_area),
            {as_span(facets), k},
            as_span(edge_neighbour),
            as_span(offsets),
            as_span(candidates),
            as_span(dofs),
            eps_n,
            as_span(multipliers),
            smoothing,
            smooth_master};
  }
};

/// SurfaceFrictionInput: the contact plus old_facet (np,) int32, xi_old (np, 2), t_old (np, 3).
struct OwnedSurfaceFrictionInput {
  OwnedSurfaceContactInput contact;
  IndexArray old_facet;
  RealArray xi_old, t_old;
  double eps_t, mu;

  SurfaceFrictionInput view() const {
    SurfaceContactInput c = contact.view();
    const py::ssize_t np = contact.point_area.shape(0);
    check_shape(old_facet, "old_facet", {np});
    check_shape(xi_old, "xi_old", {np, 2});
    check_shape(t_old, "t_old", {np, 3});
    return {c, as_span(old_facet), as_span(xi_old), as_span(t_old), eps_t, mu};
  }
};

}  // namespace hypercontact::python
