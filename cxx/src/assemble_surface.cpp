#include <hypercontact/assemble_surface.hpp>
#include <hypercontact/node_to_surface.hpp>
#include <stdexcept>
#include <string>

#include "surface_pairing.hpp"

namespace hypercontact {

SurfaceContactState assemble_surface_contact(const SurfaceContactInput& in, Vec b, Mat A) {
  detail::check_surface_input(in, "assemble_surface_contact");
  const std::size_t np = in.point_area.size();
  const std::vector<char> boundary_node = detail::master_boundary_nodes(in);
  SurfaceContactState s;
  detail::init_state(s, np);

  std::vector<PetscInt> idx;
  std::vector<PetscScalar> values;
  // Constrained dofs are −1: MatSetValues skips negative indices, VecSetValues only when told.
  if (b != nullptr && VecSetOption(b, VEC_IGNORE_NEGATIVE_INDICES, PETSC_TRUE) != 0)
    throw std::runtime_error("assemble_surface_contact: VecSetOption failed");
  for (std::size_t p = 0; p < np; ++p) {
    detail::SlavePointPairing pr;
    NodeCoordinates master;
    SurfaceContact e;
    if (!detail::closed_normal_element(in, boundary_node, p, s, pr, master, e)) continue;
    const std::int32_t f = pr.facet;
    const int ns = static_cast<int>(pr.nodes.size());
    std::vector<std::int32_t>& nodes = pr.nodes;
    for (int i = 0; i < 4; ++i) nodes.push_back(in.facets[4 * f + i]);
    const int n = static_cast<int>(3 * nodes.size());
    idx.resize(n);
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int k = 0; k < 3; ++k) idx[3 * a + k] = in.dofs[3 * nodes[a] + k];
    for (int i = 0; i < ns; ++i) s.force -= e.residual.segment<3>(3 * i);
    if (b != nullptr) {
      values.assign(e.residual.data(), e.residual.data() + n);
      if (const PetscErrorCode err = VecSetValues(b, n, idx.data(), values.data(), ADD_VALUES))
        throw std::runtime_error("assemble_surface_contact: VecSetValues failed (PETSc error " +
                                 std::to_string(err) + ") for slave point " + std::to_string(p));
    }
    if (A != nullptr) {
      const Eigen::Matrix<PetscScalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> K = e.tangent;
      if (const PetscErrorCode err = MatSetValues(A, n, idx.data(), n, idx.data(), K.data(), ADD_VALUES))
        throw std::runtime_error("assemble_surface_contact: MatSetValues failed (PETSc error " +
                                 std::to_string(err) + ") for slave point " + std::to_string(p) +
                                 " (is the coupling in the matrix pattern?)");
    }
  }
  return s;
}

}  // namespace hypercontact
