#include <hypercontact/assemble_surface.hpp>
#include <hypercontact/assembly.hpp>

namespace hypercontact {

SurfaceContactState assemble_surface_contact(const SurfaceContactInput& in, Vec b, Mat A) {
  SurfaceContactEvaluation e = evaluate_surface_contact(in);
  if (b != nullptr) add_residual(e, b);
  if (A != nullptr) add_tangent(e, A);
  return std::move(static_cast<SurfaceContactState&>(e));
}

}  // namespace hypercontact
