// Insertion of element contributions into a local array, a PETSc Vec and a PETSc Mat, with local
// (through a local-to-global mapping) and global numbering: placement, constrained (−1) rows and
// columns skipped, repeated columns added, additions not overwrites, and the refusals.
#include <gtest/gtest.h>

#include <hypercontact/assembly.hpp>
#include <stdexcept>
#include <vector>

#include "contact_elements_fd.hpp"
#include "petsc_objects.hpp"

namespace hypercontact {
namespace {

constexpr PetscInt n = 6;
/// Reverses the numbering, so that a local dof d lands on global 5 − d.
const std::vector<PetscInt> reversed{5, 4, 3, 2, 1, 0};

/// Two elements: a 2 × 3 block with a constrained row and a repeated column, a 1 × 1 block.
ContactElements two_elements(DofNumbering numbering) {
  ContactElements c;
  c.numbering = numbering;
  ContactElements::Slot a = c.append(3, 2, 3);
  a.rows[0] = 1, a.rows[1] = -1;
  a.columns[0] = 1, a.columns[1] = 4, a.columns[2] = 4;
  a.residual << 0.5, 7.0;
  a.tangent << 1, 2, 3, 4, 5, 6;
  ContactElements::Slot b = c.append(0, 1, 1);
  b.rows[0] = b.columns[0] = 4;
  b.residual << -2.0;
  b.tangent << 10;
  return c;
}

/// What two_elements adds, by dof: b[1] += 0.5, b[4] −= 2, A(1, 1) += 1, A(1, 4) += 2 + 3,
/// A(4, 4) += 10; row −1 (7, 4, 5, 6) skipped.
Eigen::VectorXd expected_residual() {
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  b[1] = 0.5, b[4] = -2.0;
  return b;
}
Eigen::MatrixXd expected_tangent() {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  A(1, 1) = 1, A(1, 4) = 5, A(4, 4) = 10;
  return A;
}
/// The same, renumbered by `reversed`.
Eigen::MatrixXd reversed_matrix(const Eigen::MatrixXd& A) {
  return A.colwise().reverse().rowwise().reverse();
}

TEST(Assembly, ResidualIntoALocalArrayAdds) {
  const ContactElements c = two_elements(DofNumbering::Local);
  std::vector<double> b(n, 1.0);
  add_residual(c, b);
  add_residual(c, b);
  const Eigen::VectorXd expected = Eigen::VectorXd::Ones(n) + 2 * expected_residual();
  EXPECT_EQ(Eigen::Map<const Eigen::VectorXd>(b.data(), n), expected);
  EXPECT_EQ(test::dense_residual(c, n), expected_residual());  // the tests' own assembly agrees
}

TEST(Assembly, ResidualIntoALocalArrayRefusesGlobalNumbersAndShortArrays) {
  std::vector<double> b(n, 0.0), shorter(4, 0.0);
  EXPECT_THROW(add_residual(two_elements(DofNumbering::Global), b), std::invalid_argument);
  EXPECT_THROW(add_residual(two_elements(DofNumbering::Local), shorter), std::out_of_range);
  EXPECT_EQ(shorter, std::vector<double>(4, 0.0));  // nothing added before the refusal
}

TEST(Assembly, ResidualIntoAVecWithLocalAndGlobalNumbers) {
  Vec local = test::create_vector(n, reversed), global = test::create_vector(n, reversed);
  add_residual(two_elements(DofNumbering::Local), local);
  add_residual(two_elements(DofNumbering::Global), global);
  EXPECT_EQ(test::dense(local), expected_residual().reverse());
  EXPECT_EQ(test::dense(global), expected_residual());
  VecDestroy(&local);
  VecDestroy(&global);
}

TEST(Assembly, TangentIntoAMatWithLocalAndGlobalNumbers) {
  Mat local = test::create_matrix(n, reversed), global = test::create_matrix(n, reversed);
  add_tangent(two_elements(DofNumbering::Local), local);
  add_tangent(two_elements(DofNumbering::Global), global);
  add_tangent(two_elements(DofNumbering::Global), global);
  EXPECT_EQ(test::dense(local), reversed_matrix(expected_tangent()));
  EXPECT_EQ(test::dense(global), 2 * expected_tangent());
  EXPECT_EQ(test::dense_tangent(two_elements(DofNumbering::Local), n), expected_tangent());
  MatDestroy(&local);
  MatDestroy(&global);
}

TEST(Assembly, TangentOutsideThePatternNamesTheSlavePoint) {
  Mat A;
  ASSERT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 1, nullptr, &A), 0);
  ASSERT_EQ(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), 0);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);  // no traceback in the test log
  try {
    add_tangent(two_elements(DofNumbering::Global), A);
    ADD_FAILURE() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("slave point 3"), std::string::npos) << e.what();
  }
  PetscPopErrorHandler();
  MatDestroy(&A);
}

}  // namespace
}  // namespace hypercontact
