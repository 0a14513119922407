// Eigen types of the deformable-master contact elements that live on the stack: a slave point of
// at most nine nodes, element vectors and matrices bounded by the largest element (dynamic
// sizes within fixed maxima, so that an element allocates nothing on the heap).
#pragma once

#include <Eigen/Core>

namespace hypercontact {

/// A slave point x_s = Σ_i M_i x_i has 1 (a node) to 9 (a Gauss point of a biquadratic
/// quadrilateral) nodes.
constexpr int max_slave_nodes = 9;
/// Nodes of the largest master facet (the biquadratic quadrilateral).
constexpr int max_facet_nodes = 9;
/// Unknowns of a normal element: 3 per slave node and per node of its facet.
constexpr int max_element_dofs = 3 * (max_slave_nodes + max_facet_nodes);
/// Unknowns of a friction element: those and the old facet's nodes.
constexpr int max_friction_dofs = max_element_dofs + 3 * max_facet_nodes;

/// The slave point's node coordinates (3 × ns) and weights M_i (ns).
using SlaveNodes = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, max_slave_nodes>;
using SlaveWeights = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, max_slave_nodes, 1>;

/// Column vector and square matrix of at most N entries per dimension.
template <int N>
using BoundedVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, N, 1>;
template <int N>
using BoundedMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, N, N>;

using ElementVector = BoundedVector<max_element_dofs>;
using ElementMatrix = BoundedMatrix<max_element_dofs>;
using FrictionVector = BoundedVector<max_friction_dofs>;
using FrictionMatrix = BoundedMatrix<max_friction_dofs>;

}  // namespace hypercontact
