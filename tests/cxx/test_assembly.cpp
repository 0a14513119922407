// Insertion of element contributions into a local array, a PETSc Vec and a PETSc Mat, with local
// (through a local-to-global mapping) and global numbering: placement, constrained (−1) rows and
// columns skipped, repeated columns added, additions not overwrites, and the refusals; then the
// evaluations themselves inserted: a rigid plane's normal penalty and friction part (local
// numbering, a constrained dof) against the kernels, a deformable master's normal contact and
// friction (global numbering, old-facet columns) against the evaluation's own elements.
#include <gtest/gtest.h>

#include <array>
#include <hypercontact/assembly.hpp>
#include <hypercontact/coulomb_friction.hpp>
#include <hypercontact/normal_penalty.hpp>
#include <hypercontact/rigid_contact.hpp>
#include <hypercontact/rigid_contact_friction.hpp>
#include <hypercontact/surface_contact.hpp>
#include <hypercontact/surface_contact_friction.hpp>
#include <stdexcept>
#include <variant>
#include <vector>

#include "contact_elements_fd.hpp"
#include "finite_difference.hpp"
#include "petsc_objects.hpp"
#include "surface_scene.hpp"

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


// --- Evaluations inserted into PETSc ------------------------------------------------------------

/// Three slave nodes against a tilted plane, node 1's y constrained (dof −1): with the normal
/// penalty nodes 0 and 1 penetrate and node 2 is open; with friction (its own positions and
/// history) node 0 sticks, node 1 slips and node 2 is open.
namespace rigid {
constexpr PetscInt size = 9;
const Obstacle tilted = RigidPlane{{0, 0, 0}, Eigen::Vector3d(0.3, -0.2, 1.0).normalized()};
const std::vector<double> area = {0.5, 0.25, 0.75};
const std::vector<std::int32_t> dofs = {0, 1, 2, 3, -1, 5, 6, 7, 8};

constexpr double eps_n = 1e3;
const std::vector<double> x = {0.1, 0.2, -0.05, -0.3, 0.1, -0.02, 0.0, 0.0, 0.5};
RigidContactEvaluation evaluate() { return evaluate_rigid_contact({tilted, x, area, dofs, eps_n}); }
NodalContact expected(std::size_t i) {
  return normal_penalty(project(tilted, Eigen::Vector3d(&x[3 * i])), area[i], eps_n);
}

constexpr double friction_eps_n = 400.0, eps_t = 300.0, mu = 0.4;
const std::vector<double> friction_x = {0.1, 0.2, -0.05, -0.3, 0.1, -0.04, 0.0, 0.0, 0.5};
const std::vector<double> xi_old = {0.1001, 0.2, -0.05, -0.1, 0.1, -0.04, 0.0, 0.0, 0.5};
const std::vector<double> t_old(size, 0.0);
/// The friction part alone (its normal part is evaluate()'s business).
RigidFrictionEvaluation evaluate_friction() {
  return evaluate_rigid_friction(
      {{tilted, friction_x, area, dofs, friction_eps_n}, xi_old, t_old, eps_t, mu, false});
}
FrictionResult expected_friction(std::size_t i) {
  const Eigen::Vector3d xi(&friction_x[3 * i]);
  return coulomb_friction(project(tilted, xi), xi, Eigen::Vector3d(&xi_old[3 * i]),
                          Eigen::Vector3d(&t_old[3 * i]), area[i], friction_eps_n, eps_t, mu);
}

/// K_i at the mapped rows and columns of the non-negative dofs.
Eigen::MatrixXd expected_tangent(const std::vector<PetscInt>& l2g) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(size, size);
  for (std::size_t i = 0; i < 3; ++i)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (dofs[3 * i + r] >= 0 && dofs[3 * i + c] >= 0)
          A(l2g[dofs[3 * i + r]], l2g[dofs[3 * i + c]]) += expected(i).tangent(r, c);
  return A;
}
}  // namespace rigid

TEST(Assembly, RigidTangentLandsOnTheLocalDofsAndSkipsTheConstrained) {
  using namespace rigid;
  ASSERT_TRUE(expected(0).closed && expected(1).closed && !expected(2).closed);
  ASSERT_GT(expected(1).tangent.cwiseAbs().minCoeff(), 0);  // every entry of node 1's matters
  const RigidContactEvaluation e = evaluate();
  const std::vector<PetscInt> identity{0, 1, 2, 3, 4, 5, 6, 7, 8},
      reversed_dofs{8, 7, 6, 5, 4, 3, 2, 1, 0};
  for (const std::vector<PetscInt>* l2g : {&identity, &reversed_dofs}) {
    Mat A = test::create_matrix(size, *l2g);
    add_tangent(e, A);
    add_tangent(e, A);  // adds, does not overwrite
    const Eigen::MatrixXd K = test::dense(A), reference = expected_tangent(*l2g);
    for (PetscInt r = 0; r < size; ++r)
      for (PetscInt c = 0; c < size; ++c)
        EXPECT_DOUBLE_EQ(K(r, c), 2 * reference(r, c)) << "row " << r << ", column " << c;
    MatDestroy(&A);
  }
  EXPECT_EQ(expected_tangent(identity).row(4).norm(), 0.0);  // the constrained dof 4
  EXPECT_EQ(expected_tangent(identity).col(4).norm(), 0.0);
}

TEST(Assembly, RigidResidualAddsIntoALocalArrayAndRefusesAShortOne) {
  using namespace rigid;
  const RigidContactEvaluation e = evaluate();
  std::vector<double> b(size + 1, 1.0);  // one entry past every dof (a ghost's) stays untouched
  add_residual(e, b);
  const Eigen::Vector3d r0 = expected(0).residual, r1 = expected(1).residual;
  const std::vector<double> reference = {1 + r0[0], 1 + r0[1], 1 + r0[2], 1 + r1[0], 1.0,
                                         1 + r1[2], 1.0,       1.0,       1.0,       1.0};
  for (std::size_t k = 0; k < b.size(); ++k) EXPECT_DOUBLE_EQ(b[k], reference[k]) << "dof " << k;
  EXPECT_EQ(e.num_closed, 2);
  ASSERT_EQ(e.gap.size(), 3u);
  EXPECT_DOUBLE_EQ(e.gap[2], project(tilted, {0, 0, 0.5}).gap);
  EXPECT_DOUBLE_EQ(e.pressure[1], expected(1).pressure);
  EXPECT_EQ(e.pressure[2], 0.0);
  EXPECT_LE((e.force + r0 + r1).norm(), 1e-14);
  EXPECT_GT(e.force.dot(std::get<RigidPlane>(tilted).normal), 0);  // the obstacle pushes out
  std::vector<double> shorter(5, 0.0);  // dof 5 of the closed node 1 is out of range
  EXPECT_THROW(add_residual(e, shorter), std::out_of_range);
  EXPECT_EQ(shorter, std::vector<double>(5, 0.0));
}

TEST(Assembly, RigidFrictionPartIntoALocalArrayAndAMat) {
  using namespace rigid;
  ASSERT_EQ(expected_friction(0).state, StickSlip::Stick);
  ASSERT_EQ(expected_friction(1).state, StickSlip::Slip);
  ASSERT_EQ(expected_friction(2).state, StickSlip::Open);
  const RigidFrictionEvaluation e = evaluate_friction();
  std::vector<double> b(size, 1.0);
  add_residual(e, b);
  Mat A = test::create_matrix(size);
  add_tangent(e, A);
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::MatrixXd reference = Eigen::MatrixXd::Zero(size, size);
  for (std::size_t i = 0; i < 3; ++i) {
    const FrictionResult f = expected_friction(i);
    for (int k = 0; k < 3; ++k) {
      if (dofs[3 * i + k] >= 0) {
        EXPECT_NEAR(b[dofs[3 * i + k]], 1.0 + f.residual[k], 1e-14);
      }
    }
    EXPECT_EQ(e.state[i], static_cast<std::int8_t>(f.state));
    EXPECT_EQ(Eigen::Vector3d(&e.traction[3 * i]), f.traction);
    EXPECT_EQ(e.dissipation[i], f.dissipation);
    force -= f.residual;
    reference.block<3, 3>(3 * i, 3 * i) = f.tangent;  // not symmetric in slip: rows are rows
  }
  EXPECT_EQ(b[4], 1.0);
  EXPECT_LE((e.friction_force - force).norm(), 1e-14 * force.norm());
  reference.row(4).setZero();
  reference.col(4).setZero();
  EXPECT_LE(test::relative_error(test::dense(A), reference), 1e-14);
  MatDestroy(&A);
}

TEST(Assembly, SurfaceContactIntoAVecAndAMatWithGlobalNumbers) {
  test::SurfaceScene s = test::face_scene();
  const auto size = static_cast<PetscInt>(s.x.size());
  const SurfaceContactEvaluation free = evaluate_surface_contact(s.input());
  // A master dof (node 0's x) and a dof of the master node every facet shares (node 4's z).
  ASSERT_NE(test::dense_residual(free.elements, size)[0], 0.0);
  ASSERT_NE(test::dense_residual(free.elements, size)[14], 0.0);
  s.dofs[0] = s.dofs[3 * 4 + 2] = -1;
  const SurfaceContactEvaluation e = evaluate_surface_contact(s.input());
  ASSERT_GT(e.elements.size(), 0u);
  EXPECT_EQ(e.elements.numbering, DofNumbering::Global);
  Vec b = test::create_vector(size);
  Mat A = test::create_matrix(size);
  add_residual(e, b);
  add_tangent(e, A);
  const Eigen::VectorXd R = test::dense(b);
  const Eigen::MatrixXd K = test::dense(A);
  EXPECT_EQ(R, test::dense_residual(e.elements, size));
  EXPECT_EQ(K, test::dense_tangent(e.elements, size));
  for (const int dof : {0, 14}) {
    EXPECT_EQ(R[dof], 0.0);
    EXPECT_EQ(K.row(dof).norm(), 0.0);
    EXPECT_EQ(K.col(dof).norm(), 0.0);
  }
  VecDestroy(&b);
  MatDestroy(&A);
}

TEST(Assembly, SurfaceFrictionIntoAVecAndAMatWithTheOldFacetsColumns) {
  const test::SurfaceScene s = test::face_scene();
  const std::size_t np = s.point_area.size();
  // Every point's history on facet 3, half a facet away: slip, old-facet columns off the pattern
  // of the current facet.
  const std::vector<std::int32_t> old_facet(np, 3);
  const std::vector<double> xi_old(2 * np, 0.0), t_old(3 * np, 0.5);
  const auto size = static_cast<PetscInt>(s.x.size());
  const SurfaceFrictionEvaluation e =
      evaluate_surface_friction({s.input(), old_facet, xi_old, t_old, 300.0, 0.4});
  Vec b = test::create_vector(size);
  Mat A = test::create_matrix(size);
  add_residual(e, b);
  add_tangent(e, A);
  EXPECT_EQ(test::dense(b), test::dense_residual(e.elements, size));
  EXPECT_EQ(test::dense(A), test::dense_tangent(e.elements, size));
  EXPECT_GT(test::dense(A).block(0, 3 * 8, 3 * 8, 3).norm(), 0);  // the old facet's node 8
  VecDestroy(&b);
  MatDestroy(&A);
}

}  // namespace
}  // namespace hypercontact
