// Test helpers for the assembly: small sequential PETSc matrices and vectors, optionally with a
// local-to-global mapping, and their dense contents.
#pragma once

#include <gtest/gtest.h>
#include <petscmat.h>
#include <petscvec.h>

#include <Eigen/Core>
#include <numeric>
#include <vector>

namespace hypercontact::test {

/// l2g of n entries, or the identity if empty.
inline ISLocalToGlobalMapping local_to_global(PetscInt n, std::vector<PetscInt> l2g) {
  if (l2g.empty()) {
    l2g.resize(n);
    std::iota(l2g.begin(), l2g.end(), 0);
  }
  ISLocalToGlobalMapping map;
  EXPECT_EQ(
      ISLocalToGlobalMappingCreate(PETSC_COMM_SELF, 1, n, l2g.data(), PETSC_COPY_VALUES, &map), 0);
  return map;
}

/// An n × n sequential AIJ matrix (room for a dense pattern) with the mapping local i → l2g[i].
inline Mat create_matrix(PetscInt n, const std::vector<PetscInt>& l2g = {}) {
  Mat A;
  EXPECT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, n, nullptr, &A), 0);
  ISLocalToGlobalMapping map = local_to_global(n, l2g);
  EXPECT_EQ(MatSetLocalToGlobalMapping(A, map, map), 0);
  ISLocalToGlobalMappingDestroy(&map);
  return A;
}

/// A sequential vector of n zeros with the mapping local i → l2g[i].
inline Vec create_vector(PetscInt n, const std::vector<PetscInt>& l2g = {}) {
  Vec b;
  EXPECT_EQ(VecCreateSeq(PETSC_COMM_SELF, n, &b), 0);
  ISLocalToGlobalMapping map = local_to_global(n, l2g);
  EXPECT_EQ(VecSetLocalToGlobalMapping(b, map), 0);
  ISLocalToGlobalMappingDestroy(&map);
  EXPECT_EQ(VecSet(b, 0.0), 0);
  return b;
}

/// The assembled matrix as a dense array.
inline Eigen::MatrixXd dense(Mat A) {
  EXPECT_EQ(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), 0);
  EXPECT_EQ(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), 0);
  PetscInt n;
  MatGetSize(A, &n, nullptr);
  std::vector<PetscInt> all(n);
  std::iota(all.begin(), all.end(), 0);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> values(n, n);
  EXPECT_EQ(MatGetValues(A, n, all.data(), n, all.data(), values.data()), 0);
  return values;
}

/// The assembled vector's entries.
inline Eigen::VectorXd dense(Vec b) {
  EXPECT_EQ(VecAssemblyBegin(b), 0);
  EXPECT_EQ(VecAssemblyEnd(b), 0);
  PetscInt n;
  VecGetSize(b, &n);
  const PetscScalar* a;
  VecGetArrayRead(b, &a);
  const Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(a, n);
  VecRestoreArrayRead(b, &a);
  return out;
}

}  // namespace hypercontact::test
