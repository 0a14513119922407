#include <hypercontact/assemble_surface_friction.hpp>
#include <hypercontact/node_to_surface.hpp>
#include <hypercontact/surface_friction.hpp>
#include <stdexcept>
#include <string>

#include "surface_pairing.hpp"

namespace hypercontact {

SurfaceFrictionState assemble_surface_friction(const SurfaceFrictionInput& fin, Vec b, Mat A) {
  constexpr const char* who = "assemble_surface_friction";
  const SurfaceContactInput& in = fin.contact;
  detail::check_surface_input(in, who);
  const std::size_t np = in.point_area.size();
  const std::int32_t nf = static_cast<std::int32_t>(in.facets.size() / 4);
  auto fail = [who](const std::string& what) { throw std::invalid_argument(std::string(who) + ": " + what); };
  if (fin.old_facet.size() != np || fin.xi_old.size() != 2 * np || fin.t_old.size() != 3 * np)
    fail("old_facet, xi_old, t_old must hold 1, 2, 3 entries per slave point");
  for (std::int32_t f : fin.old_facet)
    if (f < -1 || f >= nf) fail("an old facet index is out of range");
  if (!(fin.eps_t > 0)) fail("eps_t must be > 0");
  if (!(fin.mu >= 0)) fail("mu must be >= 0");

  const std::vector<char> boundary_node = detail::master_boundary_nodes(in);
  SurfaceFrictionState s;
  detail::init_state(s, np);
  s.traction.assign(3 * np, 0.0);
  s.slip_increment.assign(3 * np, 0.0);
  s.dissipation.assign(np, 0.0);
  s.stick.assign(np, static_cast<std::int32_t>(StickSlip::Open));
  s.total_force.setZero();

  std::vector<PetscInt> rows, cols;
  std::vector<PetscScalar> values;
  if (b != nullptr && VecSetOption(b, VEC_IGNORE_NEGATIVE_INDICES, PETSC_TRUE) != 0)
    throw std::runtime_error(std::string(who) + ": VecSetOption failed");
  for (std::size_t p = 0; p < np; ++p) {
    detail::SlavePointPairing pr;
    NodeCoordinates master;
    SurfaceContact e;
    if (!detail::closed_normal_element(in, boundary_node, p, s, pr, master, e)) continue;
    const std::int32_t f = pr.facet;
    const int ns = static_cast<int>(pr.nodes.size());

    // History: the old master material point, or none (then the current point, t_old = 0).
    const std::int32_t fo = fin.old_facet[p];
    const bool history = fo >= 0;
    const std::int32_t old = history ? fo : f;
    const Eigen::Vector2d xi_old =
        history ? Eigen::Vector2d(fin.xi_old[2 * p], fin.xi_old[2 * p + 1]) : pr.projection.xi;
    const Eigen::Vector3d t_old =
        history ? Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(&fin.t_old[3 * p])) : Eigen::Vector3d::Zero();
    const NodeCoordinates old_master = gather_facet(old, in.facets, 4, in.x);
    const SurfaceFriction fr = surface_friction(pr.slave, pr.weights, master, pr.projection, old_master, xi_old,
                                                t_old, in.point_area[p], in.eps_n, fin.eps_t, fin.mu,
                                                in.multipliers.empty() ? 0.0 : in.multipliers[p], in.smoothing);
    for (int k = 0; k < 3; ++k) {
      s.traction[3 * p + k] = fr.traction[k];
      s.slip_increment[3 * p + k] = fr.slip_increment[k];
    }
    s.dissipation[p] = fr.dissipation;
    s.stick[p] = static_cast<std::int32_t>(fr.state);

    // Rows: slave nodes + current facet; columns: those + old facet.
    std::vector<std::int32_t> nodes = pr.nodes;
    for (int i = 0; i < 4; ++i) nodes.push_back(in.facets[4 * f + i]);
    const int n = static_cast<int>(3 * nodes.size());
    for (int i = 0; i < 4; ++i) nodes.push_back(in.facets[4 * old + i]);
    const int m = static_cast<int>(3 * nodes.size());
    cols.resize(m);
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int k = 0; k < 3; ++k) cols[3 * a + k] = in.dofs[3 * nodes[a] + k];
    rows.assign(cols.begin(), cols.begin() + n);
    const Eigen::VectorXd R = e.residual + fr.residual.head(n);
    for (int i = 0; i < ns; ++i) {
      s.force -= e.residual.segment<3>(3 * i);
      s.total_force -= R.segment<3>(3 * i);
    }
    if (b != nullptr) {
      values.assign(R.data(), R.data() + n);
      if (const PetscErrorCode err = VecSetValues(b, n, rows.data(), values.data(), ADD_VALUES))
        throw std::runtime_error(std::string(who) + ": VecSetValues failed (PETSc error " +
                                 std::to_string(err) + ") for slave point " + std::to_string(p));
    }
    if (A != nullptr) {
      Eigen::Matrix<PetscScalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> K =
          Eigen::MatrixXd::Zero(n, m);
      K.leftCols(n) = e.tangent;
      if (history) K += fr.tangent.topRows(n);
      if (const PetscErrorCode err = MatSetValues(A, n, rows.data(), m, cols.data(), K.data(), ADD_VALUES))
        throw std::runtime_error(std::string(who) + ": MatSetValues failed (PETSc error " +
                                 std::to_string(err) + ") for slave point " + std::to_string(p) +
                                 " (is the coupling, old facet included, in the matrix pattern?)");
    }
  }
  return s;
}

}  // namespace hypercontact
