// assemble_contact: the hypercontact C++ library without Python.
//
// Four slave nodes against a rigid plane z = 0 (normal +z): two above it (open), two below it
// (closed, g < 0). One evaluation (evaluate_rigid_contact: the projection and penalty of every
// node, once) gives the state and each closed node's element; add_residual and add_tangent put
// them into a PETSc Vec and an AIJ Mat the way a C++ finite element code would: process-local
// dof numbers 3 i + k through a local-to-global mapping, −1 for a constrained dof (skipped).
// Closed form of a closed node i on the plane (n = e_z, ∂n/∂x = 0):
//   r_i = A_i ε_N g_i n,   K_i = A_i ε_N n ⊗ n,
// so b[3 i + 2] = A_i ε_N z_i, A[3 i + 2, 3 i + 2] = A_i ε_N; an open node adds nothing.
// Exits 0 if the assembled numbers are these, 1 otherwise.
#include <petscmat.h>
#include <petscvec.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <hypercontact/assembly.hpp>
#include <hypercontact/rigid_contact.hpp>
#include <vector>

namespace hc = hypercontact;

namespace {

constexpr PetscInt num_dofs = 12;  // 4 nodes × 3

/// The identity local-to-global mapping (on one process local and global numbers agree; the
/// assembly inserts local numbers with VecSetValuesLocal / MatSetValuesLocal).
ISLocalToGlobalMapping identity_mapping() {
  std::array<PetscInt, num_dofs> identity;
  for (PetscInt i = 0; i < num_dofs; ++i) identity[i] = i;
  ISLocalToGlobalMapping map;
  ISLocalToGlobalMappingCreate(PETSC_COMM_SELF, 1, num_dofs, identity.data(), PETSC_COPY_VALUES,
                               &map);
  return map;
}

/// |actual − expected| ≤ 1e-12 |expected|, printed.
bool check(const char* what, double actual, double expected) {
  const bool ok = std::abs(actual - expected) <= 1e-12 * std::abs(expected);
  std::printf("%-28s %.15g (closed form %.15g) %s\n", what, actual, expected, ok ? "ok" : "WRONG");
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 1;
  bool ok = true;
  {
    const hc::Obstacle plane = hc::RigidPlane{{0, 0, 0}, {0, 0, 1}};
    const double eps_n = 1e4;
    // Nodes 0, 2 above the plane (open); nodes 1, 3 below it (closed); node 3's x is constrained.
    const std::vector<double> x = {0.0, 0.0, 0.02, 1.0, 0.0, -0.01, 0.0, 1.0, 0.5, 1.0, 1.0, -0.03};
    const std::vector<double> area = {0.25, 0.5, 0.25, 0.125};
    std::vector<std::int32_t> dofs(num_dofs);
    for (PetscInt i = 0; i < num_dofs; ++i) dofs[i] = static_cast<std::int32_t>(i);
    dofs[9] = -1;

    const hc::RigidContactEvaluation contact = hc::evaluate_rigid_contact(
        {.obstacle = plane, .x = x, .area = area, .dofs = dofs, .eps_n = eps_n});

    ISLocalToGlobalMapping map = identity_mapping();
    Vec b;
    VecCreateSeq(PETSC_COMM_SELF, num_dofs, &b);
    VecSetLocalToGlobalMapping(b, map);
    VecSet(b, 0.0);
    hc::add_residual(contact, b);
    VecAssemblyBegin(b);
    VecAssemblyEnd(b);
    Mat A;
    MatCreateSeqAIJ(PETSC_COMM_SELF, num_dofs, num_dofs, 3, nullptr, &A);
    MatSetLocalToGlobalMapping(A, map, map);
    ISLocalToGlobalMappingDestroy(&map);
    hc::add_tangent(contact, A);
    MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);

    PetscScalar r1, r3, r0, k1;
    const PetscInt z0 = 2, z1 = 5, z3 = 11;
    VecGetValues(b, 1, &z1, &r1);
    VecGetValues(b, 1, &z3, &r3);
    VecGetValues(b, 1, &z0, &r0);
    MatGetValues(A, 1, &z1, 1, &z1, &k1);
    ok = check("closed nodes", contact.num_closed, 2) && ok;
    ok = check("residual of node 1, z", r1, area[1] * eps_n * x[5]) && ok;
    ok = check("residual of node 3, z", r3, area[3] * eps_n * x[11]) && ok;
    ok = check("tangent of node 1, zz", k1, area[1] * eps_n) && ok;
    ok = check("residual of open node 0, z", r0 + 1.0, 1.0) && ok;  // exactly 0
    MatDestroy(&A);
    VecDestroy(&b);
  }
  PetscFinalize();
  std::printf("%s\n", ok ? "assemble_contact: all numbers match" : "assemble_contact: MISMATCH");
  return ok ? 0 : 1;
}
