// Deformable–deformable normal contact assembled into PETSc objects with global indices (rows of
// master nodes may be owned by another rank): the interface before evaluations
// (surface_contact.hpp) and assembly.hpp, kept as a thin wrapper over them.
#pragma once

#include <petscmat.h>
#include <petscvec.h>

#include <hypercontact/surface_contact.hpp>

namespace hypercontact {

/// evaluate_surface_contact(in), then add_residual into b and add_tangent into A (either may be
/// null; VecSetValues / MatSetValues, global indices, ADD_VALUES; the caller assembles them).
/// Throws as evaluate_surface_contact, and std::runtime_error if PETSc reports an error.
SurfaceContactState assemble_surface_contact(const SurfaceContactInput& in, Vec b, Mat A);

}  // namespace hypercontact
