// The positional surface assembly: assemble_surface_contact inserts the elements of
// evaluate_surface_contact into a PETSc Vec and Mat with global indices, skipping constrained
// dofs, and either may be null.
#include <gtest/gtest.h>

#include <hypercontact/assemble_surface.hpp>

#include "petsc_objects.hpp"
#include "surface_scene.hpp"

namespace hypercontact {
namespace {

TEST(AssembleSurface, ResidualAndTangentAreTheEvaluationsElements) {
  test::SurfaceScene s = test::face_scene();
  s.dofs[0] = s.dofs[3 * 4 + 2] = -1;  // a master and a slave dof constrained
  const auto n = static_cast<PetscInt>(s.x.size());
  const SurfaceContactEvaluation e = evaluate_surface_contact(s.input());
  Vec b = test::create_vector(n);
  Mat A = test::create_matrix(n);
  const SurfaceContactState residual_state = assemble_surface_contact(s.input(), b, nullptr);
  const SurfaceContactState tangent_state = assemble_surface_contact(s.input(), nullptr, A);
  const SurfaceContactState state = assemble_surface_contact(s.input(), nullptr, nullptr);
  EXPECT_EQ(test::dense(b), test::dense_residual(e.elements, n));
  EXPECT_EQ(test::dense(A), test::dense_tangent(e.elements, n));
  EXPECT_EQ(test::dense(b)[0], 0.0);
  EXPECT_GT(e.elements.size(), 0u);
  for (const SurfaceContactState* t : {&residual_state, &tangent_state, &state}) {
    EXPECT_EQ(t->gap, e.gap);
    EXPECT_EQ(t->facet, e.facet);
    EXPECT_EQ(t->force, e.force);
    EXPECT_EQ(t->num_closed, e.num_closed);
  }
  VecDestroy(&b);
  MatDestroy(&A);
}

}  // namespace
}  // namespace hypercontact
