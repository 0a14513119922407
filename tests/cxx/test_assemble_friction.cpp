// The positional rigid-friction assembly: the friction part alone (coulomb_friction of every
// node, its normal part being assemble_rigid's) into a local array and a PETSc Mat.
#include <gtest/gtest.h>

#include <hypercontact/assemble_friction.hpp>
#include <vector>

#include "finite_difference.hpp"
#include "petsc_objects.hpp"

namespace hypercontact {
namespace {

constexpr double eps_n = 400.0, eps_t = 300.0, mu = 0.4;
const Obstacle plane = RigidPlane{{0, 0, 0}, Eigen::Vector3d(0.3, -0.2, 1).normalized()};
// Node 0 sticks, node 1 slips (its y constrained), node 2 is open.
const std::vector<double> x = {0.1, 0.2, -0.05, -0.3, 0.1, -0.04, 0.0, 0.0, 0.5};
const std::vector<double> xi_old = {0.1001, 0.2, -0.05, -0.1, 0.1, -0.04, 0.0, 0.0, 0.5};
const std::vector<double> t_old(9, 0.0);
const std::vector<double> area = {0.5, 0.25, 0.75};
const std::vector<std::int32_t> dofs = {0, 1, 2, 3, -1, 5, 6, 7, 8};
constexpr PetscInt n = 9;

FrictionResult expected(std::size_t i) {
  const Eigen::Vector3d xi(&x[3 * i]);
  return coulomb_friction(project(plane, xi), xi, Eigen::Vector3d(&xi_old[3 * i]),
                          Eigen::Vector3d(&t_old[3 * i]), area[i], eps_n, eps_t, mu);
}

TEST(AssembleRigidFriction, ResidualIsTheFrictionPartOnTheDofs) {
  ASSERT_EQ(expected(0).state, StickSlip::Stick);
  ASSERT_EQ(expected(1).state, StickSlip::Slip);
  ASSERT_EQ(expected(2).state, StickSlip::Open);
  std::vector<double> b(n, 1.0);
  const RigidFrictionState s =
      assemble_rigid_friction_residual(plane, x, area, eps_n, eps_t, mu, xi_old, t_old, dofs, b);
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < 3; ++i) {
    const FrictionResult f = expected(i);
    for (int k = 0; k < 3; ++k)
      if (dofs[3 * i + k] >= 0) EXPECT_NEAR(b[dofs[3 * i + k]], 1.0 + f.residual[k], 1e-14);
    EXPECT_EQ(s.state[i], static_cast<std::int8_t>(f.state));
    EXPECT_EQ(Eigen::Vector3d(&s.traction[3 * i]), f.traction);
    EXPECT_EQ(s.dissipation[i], f.dissipation);
    force -= f.residual;
  }
  EXPECT_EQ(b[4], 1.0);
  EXPECT_LE((s.force - force).norm(), 1e-14 * force.norm());
}

TEST(AssembleRigidFriction, TangentIsTheFrictionPartOnTheDofs) {
  Mat A = test::create_matrix(n);
  assemble_rigid_friction_tangent(plane, x, area, eps_n, eps_t, mu, xi_old, t_old, dofs, A);
  const Eigen::MatrixXd K = test::dense(A);
  Eigen::MatrixXd reference = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < 2; ++i) reference.block<3, 3>(3 * i, 3 * i) = expected(i).tangent;
  reference.row(4).setZero();
  reference.col(4).setZero();
  EXPECT_LE(test::relative_error(K, reference), 1e-14);
  MatDestroy(&A);
}

}  // namespace
}  // namespace hypercontact
