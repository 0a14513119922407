// The positional surface-friction assembly: assemble_surface_friction inserts the elements of
// evaluate_surface_friction (old-facet columns included) into a PETSc Vec and Mat.
#include <gtest/gtest.h>

#include <hypercontact/assemble_surface_friction.hpp>

#include "petsc_objects.hpp"
#include "surface_scene.hpp"

namespace hypercontact {
namespace {

TEST(AssembleSurfaceFriction, ResidualAndTangentAreTheEvaluationsElements) {
  const test::SurfaceScene s = test::face_scene();
  const std::size_t np = s.point_area.size();
  // Every point's history on facet 3, half a facet away: slip, old-facet columns off the pattern
  // of the current facet.
  const std::vector<std::int32_t> old_facet(np, 3);
  const std::vector<double> xi_old(2 * np, 0.0), t_old(3 * np, 0.5);
  const SurfaceFrictionInput in{s.input(), old_facet, xi_old, t_old, 300.0, 0.4};
  const auto n = static_cast<PetscInt>(s.x.size());
  const SurfaceFrictionEvaluation e = evaluate_surface_friction(in);
  Vec b = test::create_vector(n);
  Mat A = test::create_matrix(n);
  const SurfaceFrictionState state = assemble_surface_friction(in, b, A);
  EXPECT_EQ(test::dense(b), test::dense_residual(e.elements, n));
  EXPECT_EQ(test::dense(A), test::dense_tangent(e.elements, n));
  EXPECT_GT(test::dense(A).block(0, 3 * 8, 3 * 8, 3).norm(), 0);  // the old facet's node 8
  EXPECT_EQ(state.traction, e.traction);
  EXPECT_EQ(state.stick, e.stick);
  EXPECT_EQ(state.total_force, e.total_force);
  VecDestroy(&b);
  MatDestroy(&A);
}

}  // namespace
}  // namespace hypercontact
