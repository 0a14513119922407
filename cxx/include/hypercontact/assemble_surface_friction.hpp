// Coulomb friction against a deformable master surface assembled into PETSc objects with global
// indices: the interface before evaluations (surface_contact_friction.hpp) and assembly.hpp, kept
// as a thin wrapper over them.
#pragma once

#include <hypercontact/assemble_surface.hpp>
#include <hypercontact/surface_contact_friction.hpp>

namespace hypercontact {

/// evaluate_surface_friction(in), then add_residual into b and add_tangent into A (either may be
/// null). Rows: [slave nodes, current facet]; columns: [slave, current facet, old facet]
/// (duplicates of shared nodes are summed by ADD_VALUES); constrained dofs (−1) skipped. Throws
/// as evaluate_surface_friction, and std::runtime_error if PETSc reports an error.
SurfaceFrictionState assemble_surface_friction(const SurfaceFrictionInput& in, Vec b, Mat A);

}  // namespace hypercontact
