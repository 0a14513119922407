#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <hypercontact/penetration.hpp>
#include <hypercontact/smooth_master.hpp>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace hypercontact {

namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d c;
  c << 0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0;
  return c;
}

Eigen::Vector3d node_x(std::span<const double> x, std::int32_t node) {
  return Eigen::Map<const Eigen::Vector3d>(&x[3 * static_cast<std::size_t>(node)]);
}

/// The corners of facet f next to and before corner c (linear facets).
std::pair<std::int32_t, std::int32_t> neighbours(const FacetConnectivity& facets, std::int32_t f,
                                                 int c) {
  const int k = facets.corners();
  return {facets.node(static_cast<std::size_t>(f), (c + 1) % k),
          facets.node(static_cast<std::size_t>(f), (c + k - 1) % k)};
}

/// ξ of node c of a quadratic facet: a corner, the middle of edge c − corners, or the centre.
Eigen::Vector2d quadratic_node_xi(int num_nodes, int c) {
  const int k = num_nodes == 6 ? 3 : 4;
  if (c < k) return facet_vertex_xi(num_nodes, c);
  if (c < 2 * k)
    return 0.5 * (facet_vertex_xi(num_nodes, c - k) + facet_vertex_xi(num_nodes, c - k + 1));
  return Eigen::Vector2d::Zero();
}

/// The tangent vectors a_1, a_2 of quadratic facet f at its node c, with ∂N/∂ξ there.
struct QuadraticCorner {
  Eigen::Matrix<double, 3, 2> a;
  Eigen::Matrix<double, Eigen::Dynamic, 2> dN;
};
QuadraticCorner quadratic_corner(const FacetConnectivity& facets, std::int32_t f, int c,
                                 std::span<const double> x) {
  const int k = facets.nodes_per_facet;
  QuadraticCorner out{Eigen::Matrix<double, 3, 2>::Zero(),
                      facet_shape_derivatives(k, quadratic_node_xi(k, c))};
  for (int b = 0; b < k; ++b)
    out.a += node_x(x, facets.node(static_cast<std::size_t>(f), b)) * out.dN.row(b);
  return out;
}

/// The contribution of facet f to the nodal normal at its node c: linear facets
/// (x_next − x_a) × (x_prev − x_a); quadratic facets a_1 × a_2 at the node.
Eigen::Vector3d corner_normal(const FacetConnectivity& facets, std::int32_t f, int c,
                              std::span<const double> x) {
  if (facets.nodes_per_facet == 6 || facets.nodes_per_facet == 9) {
    const QuadraticCorner q = quadratic_corner(facets, f, c, x);
    return q.a.col(0).cross(q.a.col(1));
  }
  const Eigen::Vector3d xa = node_x(x, facets.node(static_cast<std::size_t>(f), c));
  const auto [next, prev] = neighbours(facets, f, c);
  return (node_x(x, next) - xa).cross(node_x(x, prev) - xa);
}

Eigen::Vector3d unnormalised(std::int32_t node, const NodeFacets& at,
                             const FacetConnectivity& facets, std::span<const double> x) {
  const auto a = static_cast<std::size_t>(node);
  if (a + 1 >= at.offsets.size() || at.offsets[a] == at.offsets[a + 1])
    throw std::invalid_argument("nodal_normal: node " + std::to_string(node) +
                                " is on no facet of the master surface");
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (auto i = at.offsets[a]; i < at.offsets[a + 1]; ++i)
    m += corner_normal(facets, at.facet[i], at.corner[i], x);
  if (!(m.norm() > 0))
    throw std::invalid_argument("nodal_normal: the facet normals at node " + std::to_string(node) +
                                " cancel (a folded or degenerate master surface)");
  return m;
}

}  // namespace

NodeFacets::NodeFacets(const FacetConnectivity& facets, std::size_t num_nodes) {
  const int k = facets.nodes_per_facet;
  if (k != 3 && k != 4 && k != 6 && k != 9)
    throw std::invalid_argument("smooth master: facets must have 3, 4, 6 or 9 nodes, got " +
                                std::to_string(k) + " nodes per facet");
  offsets.assign(num_nodes + 1, 0);
  for (const std::int32_t n : facets.nodes) {
    if (n < 0 || static_cast<std::size_t>(n) >= num_nodes)
      throw std::invalid_argument("smooth master: a facet node index is out of range");
    ++offsets[static_cast<std::size_t>(n) + 1];
  }
  for (std::size_t a = 0; a < num_nodes; ++a) offsets[a + 1] += offsets[a];
  facet.resize(facets.nodes.size());
  corner.resize(facets.nodes.size());
  std::vector<std::int32_t> fill(offsets.begin(), offsets.end() - 1);
  for (std::size_t f = 0; f < facets.size(); ++f)
    for (int c = 0; c < k; ++c) {
      const auto i = fill[static_cast<std::size_t>(facets.node(f, c))]++;
      facet[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(f);
      corner[static_cast<std::size_t>(i)] = static_cast<std::int8_t>(c);
    }
}

Eigen::Vector3d nodal_normal_value(std::int32_t node, const NodeFacets& at,
                                   const FacetConnectivity& facets, std::span<const double> x) {
  return unnormalised(node, at, facets, x).normalized();
}

bool is_crease(std::int32_t node, const Eigen::Vector3d& m, const NodeFacets& at,
               const FacetConnectivity& facets, std::span<const double> x) {
  const auto a = static_cast<std::size_t>(node);
  for (auto i = at.offsets[a]; i < at.offsets[a + 1]; ++i) {
    const Eigen::Vector3d corner = corner_normal(facets, at.facet[i], at.corner[i], x);
    if (!(corner.dot(m) > 0.7 * corner.norm())) return true;
  }
  return false;
}

NodalNormal nodal_normal(std::int32_t node, const NodeFacets& at, const FacetConnectivity& facets,
                         std::span<const double> x) {
  const Eigen::Vector3d mt = unnormalised(node, at, facets, x);
  const bool quadratic = facets.nodes_per_facet == 6 || facets.nodes_per_facet == 9;
  NodalNormal out;
  out.nodes.push_back(node);
  const auto add = [&](std::int32_t n) {
    if (std::find(out.nodes.begin(), out.nodes.end(), n) == out.nodes.end()) out.nodes.push_back(n);
  };
  const auto a = static_cast<std::size_t>(node);
  for (auto i = at.offsets[a]; i < at.offsets[a + 1]; ++i) {
    if (quadratic) {
      for (int b = 0; b < facets.nodes_per_facet; ++b)
        add(facets.node(static_cast<std::size_t>(at.facet[i]), b));
    } else {
      const auto [next, prev] = neighbours(facets, at.facet[i], at.corner[i]);
      add(next);
      add(prev);
    }
  }
  const auto slot = [&](std::int32_t n) {
    return 3 * static_cast<int>(std::find(out.nodes.begin(), out.nodes.end(), n) - out.nodes.begin());
  };
  Eigen::Matrix<double, 3, Eigen::Dynamic> dmt =
      Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, 3 * static_cast<int>(out.nodes.size()));
  const Eigen::Vector3d xa = node_x(x, node);
  for (auto i = at.offsets[a]; i < at.offsets[a + 1]; ++i) {
    if (quadratic) {  // d(a_1 × a_2) = −[a_2]× da_1 + [a_1]× da_2, da_α = Σ_b ∂N_b/∂ξ_α dx_b
      const QuadraticCorner q = quadratic_corner(facets, at.facet[i], at.corner[i], x);
      const Eigen::Matrix3d c1 = cross_matrix(q.a.col(0)), c2 = cross_matrix(q.a.col(1));
      for (int b = 0; b < facets.nodes_per_facet; ++b)
        dmt.block<3, 3>(0, slot(facets.node(static_cast<std::size_t>(at.facet[i]), b))) +=
            q.dN(b, 1) * c1 - q.dN(b, 0) * c2;
      continue;
    }
    const auto [next, prev] = neighbours(facets, at.facet[i], at.corner[i]);
    const Eigen::Vector3d en = node_x(x, next) - xa, ep = node_x(x, prev) - xa;
    dmt.block<3, 3>(0, slot(next)) -= cross_matrix(ep);
    dmt.block<3, 3>(0, slot(prev)) += cross_matrix(en);
    dmt.block<3, 3>(0, 0) += cross_matrix(ep) - cross_matrix(en);
  }
  const double s = mt.norm();
  out.m = mt / s;
  out.jacobian = (Eigen::Matrix3d::Identity() - out.m * out.m.transpose()) / s * dmt;
  return out;
}

template <int NM>
requires FacetNodeCount<NM> Overhang overhang(const Eigen::Vector2d& xi) {
  Overhang out{-1e300, -1};
  const auto consider = [&](double amount, int edge) {
    if (amount > out.amount) out = {amount, edge};
  };
  if constexpr (facet_corners<NM> == 4) {
    consider(-1 - xi[1], 0);
    consider(xi[0] - 1, 1);
    consider(xi[1] - 1, 2);
    consider(-1 - xi[0], 3);
  } else {
    consider(-xi[1], 0);
    consider(xi[0] + xi[1] - 1, 1);
    consider(-xi[0], 2);
  }
  return out;
}

namespace {

/// x_M, m and their ξ derivatives at ξ, and the projection's residual and Jacobian.
template <int NM>
struct FieldAt {
  Eigen::Matrix<double, NM, 1> N;
  Eigen::Matrix<double, NM, 2> dN;
  Eigen::Vector3d xm, m;
  Eigen::Matrix<double, 3, 2> a, dm;

  FieldAt(const FacetNodes<NM>& X, const FacetNodes<NM>& M, const Eigen::Vector2d& xi)
      : N(facet_shape_functions<NM>(xi)), dN(facet_shape_derivatives<NM>(xi)) {
    xm = X * N;
    m = M * N;
    a = X * dN;
    dm = M * dN;
  }
  Eigen::Matrix3d jacobian(double t) const {
    Eigen::Matrix3d J;
    J.col(0) = a.col(0) + t * dm.col(0);
    J.col(1) = a.col(1) + t * dm.col(1);
    J.col(2) = m;
    return J;
  }
};

/// |det J| small against the product of its columns' lengths: no unique projection.
bool singular(const Eigen::Matrix3d& J) {
  const double scale = J.col(0).norm() * J.col(1).norm() * J.col(2).norm();
  return !(std::abs(J.determinant()) > 1e-12 * scale);
}

}  // namespace

template <int NM>
requires FacetNodeCount<NM> NormalFieldProjection
project_along_normals(const Eigen::Vector3d& x_s, const FacetNodes<NM>& X, const FacetNodes<NM>& M,
                      const Eigen::Vector2d& xi0) {
  NormalFieldProjection out;
  double size = 0;
  for (int a = 0; a < NM; ++a)
    for (int b = a + 1; b < NM; ++b) size = std::max(size, (X.col(a) - X.col(b)).norm());
  // the rounding of x_M + t m − x_s is relative to the coordinates, not to the facet: a facet of
  // size 1 at 1e3 from the origin cannot resolve ξ below 1e-13 × 1e3
  const double reach = std::max({size, X.cwiseAbs().maxCoeff(), x_s.cwiseAbs().maxCoeff()});
  Eigen::Vector2d xi = xi0;
  double t;
  {
    const FieldAt<NM> f(X, M, xi);
    t = (x_s - f.xm).dot(f.m) / f.m.squaredNorm();
  }
  for (int it = 1; it <= 50; ++it) {
    const FieldAt<NM> f(X, M, xi);
    const Eigen::Matrix3d J = f.jacobian(t);
    if (singular(J)) break;
    Eigen::Vector3d step = -J.partialPivLu().solve(f.xm + t * f.m - x_s);
    const double longest = step.head<2>().lpNorm<Eigen::Infinity>();
    if (longest > 0.5) step *= 0.5 / longest;  // far starts: at most half a facet per step
    xi += step.head<2>();
    t += step[2];
    out.iterations = it;
    if (step.head<2>().lpNorm<Eigen::Infinity>() <= 1e-13 * reach / size &&
        std::abs(step[2]) * f.m.norm() <= 1e-13 * (reach + std::abs(t) * f.m.norm())) {
      out.converged = std::isfinite(t) && xi.allFinite();
      break;
    }
  }
  out.xi = xi;
  out.t = t;
  const FieldAt<NM> f(X, M, xi);
  const double s = f.m.norm();
  out.gap = t * s;
  out.normal = f.m / s;
  if (singular(f.jacobian(t))) out.converged = false;
  return out;
}

template <int NM>
requires FacetNodeCount<NM> SmoothContact smooth_node_to_surface(
    std::span<const std::int32_t> slave_nodes, const SlaveNodes& slave, const SlaveWeights& weights,
    std::int32_t facet, const NodeFacets& at, const FacetConnectivity& facets,
    std::span<const double> x, const NormalFieldProjection& projection, double w, double eps_n,
    double touch, double lambda, double smoothing, const SmoothFrictionHistory* friction) {
  const int ns = static_cast<int>(slave_nodes.size());
  if (ns < 1 || slave.cols() != ns || weights.size() != ns || facets.nodes_per_facet != NM)
    throw std::invalid_argument("smooth_node_to_surface: inconsistent slave point or facet sizes");
  if (!(w >= 0) || !(eps_n > 0))
    throw std::invalid_argument("smooth_node_to_surface: needs w >= 0 and eps_n > 0");
  SmoothContact out;
  out.xi = projection.xi;
  out.gap = projection.gap;
  out.normal = projection.normal;
  const double g = projection.gap;
  const NormalPressure pressure =
      (lambda > 0 || smoothing > 0)
          ? normal_pressure(g, eps_n, lambda, smoothing)
          : (g <= touch ? NormalPressure{eps_n * std::max(0.0, -g), -eps_n, true}
                        : NormalPressure{0.0, 0.0, false});
  if (!pressure.active) return out;
  out.closed = true;
  out.pressure = pressure.value;

  // The facet's nodes and nodal normals with their stencils; the element's columns.
  FacetNodes<NM> X, M;
  std::array<NodalNormal, NM> normals;
  out.columns.assign(slave_nodes.begin(), slave_nodes.end());
  const auto column_of = [&](std::int32_t node) {
    const auto it = std::find(out.columns.begin() + ns, out.columns.end(), node);
    if (it != out.columns.end()) return static_cast<int>(it - out.columns.begin());
    out.columns.push_back(node);
    return static_cast<int>(out.columns.size()) - 1;
  };
  std::array<int, NM> facet_column;
  for (int a = 0; a < NM; ++a) {
    const std::int32_t node = facets.node(static_cast<std::size_t>(facet), a);
    X.col(a) = node_x(x, node);
    normals[a] = nodal_normal(node, at, facets, x);
    M.col(a) = normals[a].m;
    facet_column[a] = column_of(node);
  }
  std::array<std::vector<int>, NM> stencil_column;
  for (int a = 0; a < NM; ++a)
    for (const std::int32_t node : normals[a].nodes) stencil_column[a].push_back(column_of(node));
  const bool history = friction != nullptr && !friction->old_nodes.empty();
  if (friction != nullptr) {
    if (!(friction->eps_t > 0) || !(friction->mu >= 0))
      throw std::invalid_argument("smooth_node_to_surface: friction needs eps_t > 0 and mu >= 0");
    if (history && static_cast<int>(friction->old_nodes.size()) != NM)
      throw std::invalid_argument("smooth_node_to_surface: the old facet must have NM nodes");
    // no history: t_trial = 0, as the faceted law reports it (return_map: Slip at μ = 0)
    out.state = friction->mu > 0 ? StickSlip::Stick : StickSlip::Slip;
  }
  std::array<int, NM> old_column{};
  FacetNodes<NM> X_old;
  if (history)
    for (int b = 0; b < NM; ++b) {
      old_column[b] = column_of(friction->old_nodes[static_cast<std::size_t>(b)]);
      X_old.col(b) = node_x(x, friction->old_nodes[static_cast<std::size_t>(b)]);
    }

  // Linearisation in y = (x_s, x_a, m_a): 3 + 6 NM entries.
  constexpr int ny = 3 + 6 * NM;
  const FieldAt<NM> f(X, M, projection.xi);
  const double t = projection.t, s = f.m.norm();
  const Eigen::Vector3d n = f.m / s;
  const Eigen::Matrix3d J = f.jacobian(t);
  if (singular(J))
    throw std::runtime_error("smooth_node_to_surface: the projection along the normal field is "
                             "singular (the slave point at a focus of the normal field)");
  const Eigen::Matrix3d Ji = J.inverse();
  Eigen::Matrix<double, 3, ny> dr;  // ∂(r)/∂y with r = x_M + t m − x_s, du = −J⁻¹ dr
  dr.template block<3, 3>(0, 0) = -Eigen::Matrix3d::Identity();
  for (int a = 0; a < NM; ++a) {
    dr.template block<3, 3>(0, 3 + 3 * a) = f.N[a] * Eigen::Matrix3d::Identity();
    dr.template block<3, 3>(0, 3 + 3 * NM + 3 * a) = t * f.N[a] * Eigen::Matrix3d::Identity();
  }
  const Eigen::Matrix<double, 3, ny> du = -Ji * dr;
  Eigen::Matrix<double, 3, ny> dm = f.dm.col(0) * du.row(0) + f.dm.col(1) * du.row(1);
  for (int a = 0; a < NM; ++a) dm.template block<3, 3>(0, 3 + 3 * NM + 3 * a).diagonal().array() += f.N[a];
  const Eigen::Matrix<double, 3, ny> dn = (Eigen::Matrix3d::Identity() - n * n.transpose()) / s * dm;
  const Eigen::Matrix<double, 1, ny> dg = s * du.row(2) + t * n.transpose() * dm;
  const Eigen::Matrix<double, 1, ny> dp = pressure.slope * dg;
  const double p = pressure.value;

  // Residual rows: the slave point's force on its nodes, then the facet's nodes.
  const int rows = 3 * (ns + NM);
  out.residual.resize(rows);
  Eigen::MatrixXd Ky(rows, ny);
  const Eigen::Vector3d Fs = -w * p * n;
  const Eigen::Matrix<double, 3, ny> dFs = -w * (n * dp + p * dn);
  for (int i = 0; i < ns; ++i) {
    out.residual.segment<3>(3 * i) = weights[i] * Fs;
    Ky.block(3 * i, 0, 3, ny) = weights[i] * dFs;
  }
  for (int a = 0; a < NM; ++a) {
    out.residual.segment<3>(3 * (ns + a)) = w * p * f.N[a] * n;
    const Eigen::Matrix<double, 1, ny> dNa = f.dN(a, 0) * du.row(0) + f.dN(a, 1) * du.row(1);
    Ky.block(3 * (ns + a), 0, 3, ny) = w * (f.N[a] * n * dp + p * n * dNa + p * f.N[a] * dn);
  }

  // Friction: R_i += w M_i t, R_a −= w N_a t; its tangent in y and in the old facet's nodes.
  Eigen::MatrixXd Kold;  // rows × 3 NM: ∂R/∂x_old
  if (history) {
    const Eigen::Vector3d x_s = slave * weights;
    const Eigen::Matrix<double, NM, 1> N_old = facet_shape_functions<NM>(friction->xi_old);
    const Eigen::Vector3d v = friction->t_old + friction->eps_t * (x_s - X_old * N_old);
    const Eigen::Matrix3d PT = Eigen::Matrix3d::Identity() - n * n.transpose();
    const Eigen::Vector3d t_trial = PT * v;
    const ReturnMapResult rm = return_map(t_trial, p, friction->mu);
    const Eigen::Vector3d tr = rm.traction;
    out.state = rm.state;
    out.traction = tr;
    out.slip_increment = (t_trial - tr) / friction->eps_t;
    out.dissipation = w * tr.dot(out.slip_increment);
    // dt_trial = P_T dv − n (v·dn) − (n·v) dn, dv = ε_T (dx_s − Σ N_b(ξ_old) dx_b)
    Eigen::Matrix<double, 3, ny> dtt = -n * (v.transpose() * dn) - n.dot(v) * dn;
    dtt.template leftCols<3>() += friction->eps_t * PT;
    Eigen::Matrix<double, 3, 3 * NM> dtt_old;
    for (int b = 0; b < NM; ++b) dtt_old.template block<3, 3>(0, 3 * b) = -friction->eps_t * N_old[b] * PT;
    Eigen::Matrix<double, 3, ny> dt = dtt;
    Eigen::Matrix<double, 3, 3 * NM> dt_old = dtt_old;
    if (rm.state == StickSlip::Slip) {
      const double norm = t_trial.norm();
      const Eigen::Vector3d m_dir = t_trial / norm;
      const Eigen::Matrix3d Q = friction->mu * p / norm * (Eigen::Matrix3d::Identity() - m_dir * m_dir.transpose());
      dt = friction->mu * m_dir * dp + Q * dtt;
      dt_old = Q * dtt_old;
    }
    Kold = Eigen::MatrixXd::Zero(rows, 3 * NM);
    for (int i = 0; i < ns; ++i) {
      out.residual.segment<3>(3 * i) += w * weights[i] * tr;
      Ky.block(3 * i, 0, 3, ny) += w * weights[i] * dt;
      Kold.block(3 * i, 0, 3, 3 * NM) = w * weights[i] * dt_old;
    }
    for (int a = 0; a < NM; ++a) {
      out.residual.segment<3>(3 * (ns + a)) -= w * f.N[a] * tr;
      const Eigen::Matrix<double, 1, ny> dNa = f.dN(a, 0) * du.row(0) + f.dN(a, 1) * du.row(1);
      Ky.block(3 * (ns + a), 0, 3, ny) -= w * (f.N[a] * dt + tr * dNa);
      Kold.block(3 * (ns + a), 0, 3, 3 * NM) = -w * f.N[a] * dt_old;
    }
  }

  // dy = Y dx over the columns: x_s = Σ M_i x_i, x_a, m_a(x of its stencil).
  const int cols = 3 * static_cast<int>(out.columns.size());
  Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(ny, cols);
  for (int i = 0; i < ns; ++i) Y.block<3, 3>(0, 3 * i).diagonal().array() += weights[i];
  for (int a = 0; a < NM; ++a) {
    Y.block<3, 3>(3 + 3 * a, 3 * facet_column[a]).diagonal().array() += 1.0;
    for (std::size_t j = 0; j < stencil_column[a].size(); ++j)
      Y.block<3, 3>(3 + 3 * NM + 3 * a, 3 * stencil_column[a][j]) +=
          normals[a].jacobian.template block<3, 3>(0, 3 * static_cast<int>(j));
  }
  out.tangent = Ky * Y;
  if (history)
    for (int b = 0; b < NM; ++b) out.tangent.middleCols(3 * old_column[b], 3) += Kold.middleCols(3 * b, 3);
  return out;
}

// The four facet kinds (3, 4, 6, 9 nodes).
#define HYPERCONTACT_INSTANTIATE_SMOOTH_MASTER(NM)                                         \
  template Overhang overhang<NM>(const Eigen::Vector2d&);                                  \
  template NormalFieldProjection project_along_normals<NM>(                                \
      const Eigen::Vector3d&, const FacetNodes<NM>&, const FacetNodes<NM>&,                \
      const Eigen::Vector2d&);                                                             \
  template SmoothContact smooth_node_to_surface<NM>(                                       \
      std::span<const std::int32_t>, const SlaveNodes&, const SlaveWeights&, std::int32_t, \
      const NodeFacets&, const FacetConnectivity&, std::span<const double>,                \
      const NormalFieldProjection&, double, double, double, double, double,                \
      const SmoothFrictionHistory*);
HYPERCONTACT_INSTANTIATE_SMOOTH_MASTER(3)
HYPERCONTACT_INSTANTIATE_SMOOTH_MASTER(4)
HYPERCONTACT_INSTANTIATE_SMOOTH_MASTER(6)
HYPERCONTACT_INSTANTIATE_SMOOTH_MASTER(9)
#undef HYPERCONTACT_INSTANTIATE_SMOOTH_MASTER

}  // namespace hypercontact
