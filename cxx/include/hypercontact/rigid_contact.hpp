// Normal penalty contact of a set of slave nodes against one rigid obstacle (PETSc-free): the
// kernel of one node, and the evaluation of all nodes with their element contributions.
#pragma once

#include <cstdint>
#include <hypercontact/contact_elements.hpp>
#include <hypercontact/normal_penalty.hpp>
#include <hypercontact/obstacle.hpp>
#include <span>
#include <vector>

namespace hypercontact {

/// One slave node: its projection onto the obstacle and its penalty contribution.
struct RigidContactNode {
  ObstacleProjection projection;  ///< with the true gap g
  NodalContact contact;
};

/// The projection p with its gap shifted to g − λ/ε_N: the penalty law on it is the augmented
/// Lagrangian law p_N = ⟨λ − ε_N g⟩ (λ = 0: p itself, operation for operation).
inline ObstacleProjection augmented_projection(const ObstacleProjection& p, double lambda,
                                               double eps_n) {
  ObstacleProjection shifted = p;
  shifted.gap -= lambda / eps_n;
  return shifted;
}

/// The node at x with tributary area A and multiplier λ ≥ 0 (0: pure penalty):
///   projection = project(obstacle, x),
///   contact    = normal_penalty(augmented_projection(projection, λ, ε_N), A, ε_N, δ),
/// so that p_N = ⟨λ − ε_N g⟩, r = A ε_N g̃ n and K = A ε_N (n ⊗ n + g̃ ∂n/∂x) with
/// g̃ = g − λ/ε_N (λ is held fixed during a Newton solve; its Uzawa update is the caller's).
/// Throws as normal_penalty.
RigidContactNode rigid_contact_node(const Obstacle& obstacle, const Eigen::Vector3d& x, double area,
                                    double eps_n, double lambda = 0.0, double smoothing = 0.0);

/// rigid_contact_node of every slave node i (x: n × 3 row-major, area: n, multipliers: n or
/// empty, smoothing: the band δ of normal_penalty, 0: none).
/// Throws std::invalid_argument on inconsistent sizes or bad parameters (a multiplier < 0 or not
/// finite), and std::runtime_error naming the node if a coordinate is not finite.
std::vector<RigidContactNode> evaluate_rigid_contact(const Obstacle& obstacle,
                                                     std::span<const double> x,
                                                     std::span<const double> area, double eps_n,
                                                     std::span<const double> multipliers = {},
                                                     double smoothing = 0.0);

/// Slave points against one rigid obstacle. A point is a slave node (nodal integration:
/// point_weights empty) or a combination x_p = Σ_a M_a x_a of k nodes (a Gauss point of a slave
/// facet: point_weights holds M_a, n × k), whose element spreads r and K over the k nodes:
/// R_a = M_a r, K_ab = M_a M_b K.
///
/// With points_per_facet = Q > 0 the constraint is a facet's, not a point's ("facet"
/// integration): the n points are the Q Gauss points of n / Q slave facets, facet after facet,
/// each facet carries one pressure, that of its mean gap ḡ = Σ_q w_q g_q / A (A = Σ_q w_q), and
/// dofs and multipliers are per facet (n / Q × k × 3 and n / Q). Then
///   p = p_N(ḡ) (normal_pressure.hpp),  R_a = −p Σ_q w_q M_qa n_q,
///   K_ab = −(dp_N/dḡ / A) B_a ⊗ B_b − p Σ_q w_q M_qa M_qb ∂n_q/∂x,  B_a = Σ_q w_q M_qa n_q,
/// the gradient and Hessian of A Q(ḡ) ε_N (a piecewise-constant pressure: a uniform pressure
/// gives each node its consistent load ∫ N_a p dA, and the facets, fewer than the nodes of a
/// quadratic surface, do not over-constrain it).
struct RigidContactInput {
  Obstacle obstacle;
  std::span<const double> x;                 ///< n × 3 current point coordinates, row-major
  std::span<const double> area;              ///< n tributary areas (weights) A_i ≥ 0
  std::span<const std::int32_t> dofs;        ///< n × k × 3 process-local dofs, −1: constrained
  double eps_n;                              ///< penalty ε_N > 0
  std::span<const double> multipliers = {};  ///< n augmented-Lagrangian λ_i ≥ 0, or empty
  double smoothing = 0.0;  ///< band δ ≥ 0 of the smoothed law (penetration.hpp)
  std::span<const double> point_weights = {};  ///< n × k node weights M_a, or empty (k = 1)
  int points_per_facet = 0;  ///< Q > 0: one constraint per facet of Q points (see above)
};

/// Per-node and total output of an evaluation (per facet with points_per_facet > 0).
struct RigidContactState {
  std::vector<double> gap;       ///< g_i per slave node (a facet's mean gap ḡ)
  std::vector<double> pressure;  ///< p_N,i = ε_N ⟨−g_i⟩ (augmented: ⟨λ_i − ε_N g_i⟩)
  Eigen::Vector3d force;         ///< normal force of the obstacle on the body, −Σ_i r_i
  std::int32_t num_closed;       ///< number of active nodes (g_i ≤ 0 without λ and δ)
};

/// The state and, for every active node, its element: rows = columns = dofs(i, :),
/// R = r_i, K = K_i (3 × 3), process-local numbering.
struct RigidContactEvaluation : RigidContactState {
  ContactElements elements;
};

/// rigid_contact_node of every slave node, once (or the facets' constraints, points_per_facet
/// > 0). Throws as the vector form above, and std::invalid_argument unless dofs has 3 entries
/// per node (per node of each facet), or if Q does not divide n or a facet's area is not > 0.
RigidContactEvaluation evaluate_rigid_contact(const RigidContactInput& in);

namespace detail {
/// Throws std::invalid_argument (prefixed by `who`) unless x holds 3 entries and multipliers 1 or
/// none per node of `area`.
void check_rigid_sizes(std::span<const double> x, std::span<const double> area,
                       std::span<const double> multipliers, const char* who);
/// As check_rigid_sizes, and dofs must hold 3 entries per node of each point (k = 1, or
/// point_weights' k = its size / n, with n > 0 when given). Returns k.
int check_rigid_input(const RigidContactInput& in, const char* who);
/// Appends the element of point i (k nodes): rows = columns = its k × 3 dofs, R_a = M_a r,
/// K_ab = M_a M_b K (M = 1 for a node).
void append_point_element(ContactElements& elements, const RigidContactInput& in, int k,
                          std::size_t i, const Eigen::Vector3d& r, const Eigen::Matrix3d& K);
/// x_i, or std::runtime_error naming the node if it is not finite.
Eigen::Vector3d slave_node(std::span<const double> x, std::size_t i, const char* who);
/// λ_i (0 without multipliers); std::invalid_argument unless it is finite and ≥ 0.
double multiplier(std::span<const double> multipliers, std::size_t i, const char* who);
}  // namespace detail

}  // namespace hypercontact
