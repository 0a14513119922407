#include <hypercontact/assemble_surface_friction.hpp>
#include <hypercontact/assembly.hpp>

namespace hypercontact {

SurfaceFrictionState assemble_surface_friction(const SurfaceFrictionInput& in, Vec b, Mat A) {
  SurfaceFrictionEvaluation e = evaluate_surface_friction(in);
  if (b != nullptr) add_residual(e, b);
  if (A != nullptr) add_tangent(e, A);
  return std::move(static_cast<SurfaceFrictionState&>(e));
}

}  // namespace hypercontact
