// Normal penalty contact of a set of slave nodes against one rigid obstacle (PETSc-free).
#pragma once

#include <hypercontact/normal_penalty.hpp>
#include <hypercontact/obstacle.hpp>
#include <span>
#include <vector>

namespace hypercontact {

/// One slave node: its projection onto the obstacle and its penalty contribution.
struct RigidContactNode {
  ObstacleProjection projection;
  NodalContact contact;
};

/// Evaluates, for every slave node i with current position x_i and nodal area A_i,
///   projection_i = project(obstacle, x_i),   contact_i = normal_penalty(projection_i, A_i, ε_N).
/// With multipliers λ (augmented Lagrangian, one pressure per node, ≥ 0; empty: pure penalty)
/// the penalty acts on the shifted gap g̃_i = g_i − λ_i/ε_N: contact_i = normal_penalty with
/// gap g̃_i, so p_N,i = ⟨λ_i − ε_N g_i⟩, r_i = A_i ε_N g̃_i n_i and K_i = A_i ε_N (n_i ⊗ n_i +
/// g̃_i ∂n_i/∂x) (λ is held fixed during a Newton solve; its Uzawa update is the caller's).
/// projection_i keeps the true gap g_i. smoothing: the band δ of normal_penalty (0: none).
/// x: n × 3 row-major; area: n; multipliers: n or empty.
/// Throws std::invalid_argument on inconsistent sizes or bad parameters, and
/// std::runtime_error naming the node if a coordinate is not finite.
std::vector<RigidContactNode> evaluate_rigid_contact(const Obstacle& obstacle,
                                                     std::span<const double> x,
                                                     std::span<const double> area, double eps_n,
                                                     std::span<const double> multipliers = {},
                                                     double smoothing = 0.0);

}  // namespace hypercontact
