#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <hypercontact/facet_projection.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

namespace hypercontact {

namespace {

/// Relative size below which an area or a corner counts as zero.
constexpr double degenerate_tol = 1e-12;
/// How far outside the reference facet a Face point may lie (rounding of a minimiser on an edge).
constexpr double inside_tol = 1e-10;
constexpr int max_newton_iterations = 50;

void check_num_nodes(int num_nodes) {
  if (num_nodes != 3 && num_nodes != 4)
    throw std::invalid_argument("facet: a master facet has 3 (triangle) or 4 (quadrilateral) " +
                                std::string("nodes, got ") + std::to_string(num_nodes));
}

std::string format_xi(const Eigen::Vector2d& xi) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << xi[0] << ", " << xi[1] << ")";
  return s.str();
}

/// Longest edge of the facet.
template <int NM>
double longest_edge(const FacetNodes<NM>& x) {
  double length = 0;
  for (int k = 0; k < NM; ++k) length = std::max(length, (x.col((k + 1) % NM) - x.col(k)).norm());
  return length;
}

/// Throws unless x is a finite, non-degenerate facet; returns its longest edge L > 0.
template <int NM>
double check_facet(const FacetNodes<NM>& x, const char* who) {
  if (!x.allFinite())
    throw std::invalid_argument(std::string(who) + ": master facet coordinates must be finite");
  const double L = longest_edge<NM>(x);
  Eigen::Vector3d area;
  if constexpr (NM == 4)
    area = 0.5 * (x.col(2) - x.col(0)).cross(x.col(3) - x.col(1)).eval();
  else
    area = 0.5 * (x.col(1) - x.col(0)).cross(x.col(2) - x.col(0)).eval();
  if (!(area.norm() > degenerate_tol * L * L))
    throw std::invalid_argument(std::string(who) +
                                ": degenerate master facet: zero area (longest edge " +
                                std::to_string(L) + ")");
  if constexpr (NM == 4)
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d out = x.col((k + 1) % 4) - x.col(k);
      const Eigen::Vector3d in = x.col((k + 3) % 4) - x.col(k);
      if (!(out.cross(in).norm() > degenerate_tol * L * L))
        throw std::invalid_argument(
            std::string(who) + ": degenerate master quadrilateral: zero corner at node " +
            std::to_string(k) + " (coincident nodes or collinear adjacent edges)");
    }
  return L;
}

/// a_1 × a_2 at ξ, unit; throws if it vanishes (folded facet).
template <int NM>
Eigen::Vector3d unit_normal(const FacetNodes<NM>& x, const Eigen::Vector2d& xi, double L,
                            const char* who) {
  const Eigen::Matrix<double, NM, 2> dN = facet_shape_derivatives<NM>(xi);
  const Eigen::Vector3d c = (x * dN.col(0)).cross(x * dN.col(1));
  const double norm = c.norm();
  if (!(norm > degenerate_tol * L * L))
    throw std::invalid_argument(std::string(who) +
                                ": folded master facet: a_1 x a_2 = 0 at xi = " + format_xi(xi));
  return c / norm;
}

bool inside(int num_nodes, const Eigen::Vector2d& xi, double tol) {
  if (num_nodes == 4) return xi.cwiseAbs().maxCoeff() <= 1 + tol;
  return xi[0] >= -tol && xi[1] >= -tol && xi[0] + xi[1] <= 1 + tol;
}

/// A candidate closest point.
struct Candidate {
  Eigen::Vector2d xi;
  Feature feature;
  int local_index;
  double distance;
};

/// Outcome of one Newton start on the face.
struct NewtonOutcome {
  Eigen::Vector2d xi;
  bool stationary;  ///< converged to a stationary point with H positive semi-definite
  bool concluded;   ///< stationary, or left the facet: false if the iterations ran out
  int iterations;
};

/// Safeguarded Newton for min_ξ ½|x_s − x_M(ξ)|² from xi0 (coordinates relative to the centroid).
template <int NM>
NewtonOutcome newton(const FacetNodes<NM>& x, const Eigen::Vector3d& xs, const Eigen::Vector2d& xi0,
                     double xi_tol, double L) {
  constexpr int n = NM;
  const Eigen::Vector3d x12 = x * facet_shape_mixed_derivatives<NM>();
  const auto objective = [&](const Eigen::Vector2d& xi) {
    return 0.5 * (xs - x * facet_shape_functions<NM>(xi)).squaredNorm();
  };
  Eigen::Vector2d xi = xi0;
  for (int it = 1; it <= max_newton_iterations; ++it) {
    const Eigen::Vector3d r = xs - x * facet_shape_functions<NM>(xi);
    const Eigen::Matrix<double, 3, 2> a = x * facet_shape_derivatives<NM>(xi);
    const Eigen::Vector2d grad = -a.transpose() * r;
    Eigen::Matrix2d H = a.transpose() * a;
    H(0, 1) -= r.dot(x12);
    H(1, 0) = H(0, 1);
    const double trace = H.trace(), det = H.determinant();
    const bool positive_definite = trace > 0 && det > 1e-14 * trace * trace;
    // Stationary to rounding (also ends the slow convergence to a degenerate minimum, where
    // H is singular).
    if (grad.norm() <= 1e-13 * L * (L + r.norm())) {
      const bool semi_definite = trace >= 0 && det >= -1e-12 * trace * trace;
      return {xi, semi_definite, true, it - 1};
    }
    Eigen::Vector2d d;
    if (positive_definite)
      d = -H.inverse() * grad;
    else
      d = -grad / (a.col(0).squaredNorm() + a.col(1).squaredNorm());
    const double step = d.cwiseAbs().maxCoeff();
    if (!std::isfinite(step)) return {xi, false, false, it};
    if (step > 1) d /= step;  // at most one unit of ξ per iteration
    if (positive_definite && step <= 1e-4) {
      xi += d;  // quadratic convergence region: the full Newton step
      if (step <= xi_tol) return {xi, true, true, it};
    } else {
      const double f = 0.5 * r.squaredNorm(), slope = grad.dot(d);
      double s = 1;
      while (objective(xi + s * d) > f + 1e-4 * s * slope) {
        s *= 0.5;
        if (s < 1e-12) {
          // No decrease to rounding: a stationary point if H is positive definite here.
          return {xi, positive_definite, positive_definite, it};
        }
      }
      xi += s * d;
    }
    if (n == 4 && xi.cwiseAbs().maxCoeff() > 2) return {xi, false, true, it};  // left the facet
  }
  return {xi, false, false, max_newton_iterations};
}

/// Order of preference at equal distance.
int rank(Feature f) { return f == Feature::Face ? 0 : f == Feature::Edge ? 1 : 2; }

}  // namespace

Eigen::VectorXd facet_shape_functions(int num_nodes, const Eigen::Vector2d& xi) {
  check_num_nodes(num_nodes);
  if (num_nodes == 4) return facet_shape_functions<4>(xi);
  return facet_shape_functions<3>(xi);
}

Eigen::Matrix<double, Eigen::Dynamic, 2> facet_shape_derivatives(int num_nodes,
                                                                 const Eigen::Vector2d& xi) {
  check_num_nodes(num_nodes);
  if (num_nodes == 4) return facet_shape_derivatives<4>(xi);
  return facet_shape_derivatives<3>(xi);
}

Eigen::VectorXd facet_shape_mixed_derivatives(int num_nodes) {
  check_num_nodes(num_nodes);
  if (num_nodes == 4) return facet_shape_mixed_derivatives<4>();
  return facet_shape_mixed_derivatives<3>();
}

Eigen::Vector2d facet_vertex_xi(int num_nodes, int k) {
  check_num_nodes(num_nodes);
  return num_nodes == 4 ? facet_vertex_xi<4>(k) : facet_vertex_xi<3>(k);
}

template <int NM>
requires FacetNodeCount<NM> Eigen::Vector3d facet_normal(const FacetNodes<NM>& x,
                                                         const Eigen::Vector2d& xi) {
  const double L = check_facet<NM>(x, "facet_normal");
  if (!xi.allFinite()) throw std::invalid_argument("facet_normal: xi must be finite");
  return unit_normal<NM>(x, xi, L, "facet_normal");
}

template <int NM>
requires FacetNodeCount<NM> FacetProjection project_to_facet(const FacetNodes<NM>& master,
                                                             const Eigen::Vector3d& x_s) {
  constexpr const char* who = "project_to_facet";
  const double L = check_facet<NM>(master, who);
  if (!x_s.allFinite()) throw std::invalid_argument("project_to_facet: x_s must be finite");
  constexpr int n = NM;

  // Work relative to the centroid: rounding then scales with the facet, not with |x|.
  const Eigen::Vector3d centroid = master.rowwise().mean();
  const FacetNodes<NM> x = master.colwise() - centroid;
  const Eigen::Vector3d xs = x_s - centroid;
  const double xi_tol = 1e-12 * std::max(1.0, xs.norm() / L);

  // Boundary: exact closest point of each straight edge.
  Candidate best{facet_vertex_xi<NM>(0), Feature::Vertex, 0, (xs - x.col(0)).norm()};
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d p = x.col(k), e = x.col((k + 1) % n) - p;
    const double t = std::clamp((xs - p).dot(e) / e.squaredNorm(), 0.0, 1.0);
    Candidate c;
    if (t == 0.0) {
      c = {facet_vertex_xi<NM>(k), Feature::Vertex, k, (xs - p).norm()};
    } else if (t == 1.0) {
      c = {facet_vertex_xi<NM>(k + 1), Feature::Vertex, (k + 1) % n, (xs - p - e).norm()};
    } else {
      // ξ_k + t (ξ_{k+1} − ξ_k) keeps the coordinate constant along the edge exact.
      const Eigen::Vector2d xi_k = facet_vertex_xi<NM>(k);
      c = {xi_k + t * (facet_vertex_xi<NM>(k + 1) - xi_k), Feature::Edge, k,
           (xs - p - t * e).norm()};
    }
    if (c.distance < best.distance ||
        (c.distance == best.distance && rank(c.feature) < rank(best.feature)))
      best = c;
  }

  // Face: Newton from several starts; keep the closest interior local minimum.
  std::array<Eigen::Vector2d, 5> starts{Eigen::Vector2d(0, 0), Eigen::Vector2d(0.5, 0.5),
                                        Eigen::Vector2d(-0.5, 0.5), Eigen::Vector2d(-0.5, -0.5),
                                        Eigen::Vector2d(0.5, -0.5)};
  const int num_starts = n == 4 ? 5 : 1;
  if (n == 3) starts[0] = Eigen::Vector2d(1.0 / 3, 1.0 / 3);
  int iterations = 0;
  bool converged = true;
  bool have_face = false;
  Candidate face{};
  for (int s = 0; s < num_starts; ++s) {
    const NewtonOutcome o = newton<NM>(x, xs, starts[s], xi_tol, L);
    iterations += o.iterations;
    converged = converged && o.concluded;
    if (!o.stationary || !inside(n, o.xi, inside_tol)) continue;
    const double distance = (xs - x * facet_shape_functions<NM>(o.xi)).norm();
    if (!have_face || distance < face.distance) {
      face = {o.xi, Feature::Face, -1, distance};
      have_face = true;
    }
  }
  if (have_face && face.distance <= best.distance + 1e-12 * L) best = face;

  const Eigen::Vector3d point = master * facet_shape_functions<NM>(best.xi);
  return {best.xi,
          best.feature,
          best.local_index,
          point,
          (x_s - point).norm(),
          unit_normal<NM>(x, best.xi, L, who),
          iterations,
          converged};
}

template Eigen::Vector3d facet_normal<3>(const FacetNodes<3>&, const Eigen::Vector2d&);
template Eigen::Vector3d facet_normal<4>(const FacetNodes<4>&, const Eigen::Vector2d&);
template FacetProjection project_to_facet<3>(const FacetNodes<3>&, const Eigen::Vector3d&);
template FacetProjection project_to_facet<4>(const FacetNodes<4>&, const Eigen::Vector3d&);

Eigen::Vector3d facet_normal(const NodeCoordinates& x, const Eigen::Vector2d& xi) {
  check_num_nodes(static_cast<int>(x.cols()));
  if (x.cols() == 4) return facet_normal<4>(FacetNodes<4>(x), xi);
  return facet_normal<3>(FacetNodes<3>(x), xi);
}

FacetProjection project_to_facet(const NodeCoordinates& master, const Eigen::Vector3d& x_s) {
  check_num_nodes(static_cast<int>(master.cols()));
  if (master.cols() == 4) return project_to_facet<4>(FacetNodes<4>(master), x_s);
  return project_to_facet<3>(FacetNodes<3>(master), x_s);
}

}  // namespace hypercontact
