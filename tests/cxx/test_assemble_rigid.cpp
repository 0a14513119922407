// Assembly into a real PETSc Mat and a residual array: placement and skipped (−1) dofs.
#include <gtest/gtest.h>
#include <petscmat.h>

#include <array>
#include <hypercontact/assemble_rigid.hpp>
#include <hypercontact/normal_penalty.hpp>
#include <stdexcept>
#include <vector>

#include "petsc_objects.hpp"

namespace hypercontact {
namespace {

constexpr double eps_n = 1e3;
const RigidPlane tilted{{0, 0, 0}, Eigen::Vector3d(0.3, -0.2, 1.0).normalized()};
// Node 0 penetrates, node 1 penetrates (one dof constrained), node 2 is open.
const std::vector<double> x = {0.1, 0.2, -0.05, -0.3, 0.1, -0.02, 0.0, 0.0, 0.5};
const std::vector<double> area = {0.5, 0.25, 0.75};
const std::vector<std::int32_t> dofs = {0, 1, 2, 3, -1, 5, 6, 7, 8};
constexpr PetscInt n = 9;

NodalContact expected(std::size_t i) {
  const Eigen::Vector3d xi(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
  return normal_penalty(project(tilted, xi), area[i], eps_n);
}

/// Expected dense matrix: K_i at the mapped rows/columns of the non-negative dofs.
std::array<double, n * n> expected_dense(const std::array<PetscInt, n>& l2g) {
  std::array<double, n * n> values{};
  for (std::size_t i = 0; i < 3; ++i)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (dofs[3 * i + r] >= 0 && dofs[3 * i + c] >= 0)
          values[n * l2g[dofs[3 * i + r]] + l2g[dofs[3 * i + c]]] += expected(i).tangent(r, c);
  return values;
}

void expect_tangent_placement(const std::array<PetscInt, n>& l2g) {
  Mat A = test::create_matrix(n, std::vector<PetscInt>(l2g.begin(), l2g.end()));
  assemble_rigid_tangent(tilted, x, area, eps_n, dofs, A);
  assemble_rigid_tangent(tilted, x, area, eps_n, dofs, A);  // adds, does not overwrite
  const Eigen::MatrixXd values = test::dense(A);
  const std::array<double, n* n> reference = expected_dense(l2g);
  for (PetscInt k = 0; k < n * n; ++k)
    EXPECT_DOUBLE_EQ(values(k / n, k % n), 2 * reference[k])
        << "row " << k / n << ", column " << k % n;
  MatDestroy(&A);
}

TEST(AssembleRigid, TangentLandsOnDofsAndSkipsConstrained) {
  ASSERT_TRUE(expected(0).closed && expected(1).closed && !expected(2).closed);
  ASSERT_GT(expected(1).tangent.cwiseAbs().minCoeff(), 0);  // every entry matters
  const std::array<PetscInt, n> identity{0, 1, 2, 3, 4, 5, 6, 7, 8};
  expect_tangent_placement(identity);
  const std::array<double, n* n> reference = expected_dense(identity);
  for (PetscInt k = 0; k < n; ++k) {
    EXPECT_EQ(reference[n * 4 + k], 0.0);  // row and column of the constrained dof 4
    EXPECT_EQ(reference[n * k + 4], 0.0);
  }
}

TEST(AssembleRigid, TangentUsesLocalIndices) {
  expect_tangent_placement({8, 7, 6, 5, 4, 3, 2, 1, 0});
}

TEST(AssembleRigid, ResidualAddsIntoLocalArray) {
  std::vector<double> b(n + 1, 1.0);
  const RigidContactState state = assemble_rigid_residual(tilted, x, area, eps_n, dofs, b);
  const Eigen::Vector3d r0 = expected(0).residual, r1 = expected(1).residual;
  const std::vector<double> reference = {1 + r0[0], 1 + r0[1], 1 + r0[2], 1 + r1[0], 1.0,
                                         1 + r1[2], 1.0,       1.0,       1.0,       1.0};
  for (std::size_t k = 0; k < b.size(); ++k) EXPECT_DOUBLE_EQ(b[k], reference[k]) << "dof " << k;
  EXPECT_EQ(state.num_closed, 2);
  ASSERT_EQ(state.gap.size(), 3u);
  EXPECT_DOUBLE_EQ(state.gap[2], project(tilted, {0, 0, 0.5}).gap);
  EXPECT_DOUBLE_EQ(state.pressure[1], expected(1).pressure);
  EXPECT_EQ(state.pressure[2], 0.0);
  EXPECT_LE((state.force + r0 + r1).norm(), 1e-14);
  EXPECT_GT(state.force.dot(tilted.normal), 0);  // the obstacle pushes the body out
}

TEST(AssembleRigid, RejectsBadDofs) {
  std::vector<double> b(n - 1, 0.0);  // dof 8 is out of range
  EXPECT_THROW(assemble_rigid_residual(tilted, x, area, eps_n, dofs, b), std::out_of_range);
  std::vector<double> c(n, 0.0);
  const std::span<const std::int32_t> too_few(dofs.data(), 6);
  EXPECT_THROW(assemble_rigid_residual(tilted, x, area, eps_n, too_few, c), std::invalid_argument);
}

}  // namespace
}  // namespace hypercontact
