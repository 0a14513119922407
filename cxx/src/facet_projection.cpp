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
  if (num_nodes != 3 && num_nodes != 4 && num_nodes != 6 && num_nodes != 9)
    throw std::invalid_argument(
        "facet: a master facet has 3 or 6 (triangle) or 4 or 9 (quadrilateral) nodes, got " +
        std::to_string(num_nodes));
}

std::string format_xi(const Eigen::Vector2d& xi) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << xi[0] << ", " << xi[1] << ")";
  return s.str();
}

/// Longest edge chord (corner to corner) of the facet.
template <int NM>
double longest_edge(const FacetNodes<NM>& x) {
  constexpr int nc = facet_corners<NM>;
  double length = 0;
  for (int k = 0; k < nc; ++k) length = std::max(length, (x.col((k + 1) % nc) - x.col(k)).norm());
  return length;
}

/// Throws unless x is a finite, non-degenerate facet; returns its longest edge L > 0.
template <int NM>
double check_facet(const FacetNodes<NM>& x, const char* who) {
  if (!x.allFinite())
    throw std::invalid_argument(std::string(who) + ": master facet coordinates must be finite");
  const double L = longest_edge<NM>(x);
  Eigen::Vector3d area;
  if constexpr (facet_corners<NM> == 4)
    area = 0.5 * (x.col(2) - x.col(0)).cross(x.col(3) - x.col(1)).eval();
  else
    area = 0.5 * (x.col(1) - x.col(0)).cross(x.col(2) - x.col(0)).eval();
  if (!(area.norm() > degenerate_tol * L * L))
    throw std::invalid_argument(std::string(who) +
                                ": degenerate master facet: zero area (longest edge " +
                                std::to_string(L) + ")");
  if constexpr (facet_corners<NM> == 4)
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

bool inside(int num_corners, const Eigen::Vector2d& xi, double tol) {
  if (num_corners == 4) return xi.cwiseAbs().maxCoeff() <= 1 + tol;
  return xi[0] >= -tol && xi[1] >= -tol && xi[0] + xi[1] <= 1 + tol;
}

/// Far outside the reference facet: a Newton start that gets here has left it.
bool far_outside(int num_corners, const Eigen::Vector2d& xi) {
  if (num_corners == 4) return xi.cwiseAbs().maxCoeff() > 2;
  return std::max({-xi[0], -xi[1], xi[0] + xi[1] - 1}) > 1;
}

/// Second derivatives [x_,11 x_,22 x_,12] of the facet at ξ.
template <int NM>
Eigen::Matrix3d second_derivatives(const FacetNodes<NM>& x, const Eigen::Vector2d& xi) {
  return x * facet_shape_second_derivatives<NM>(xi);
}

/// Closest point t ∈ [0, 1] of the parabola p(t) = A + B t + C t² to y: the smallest of
/// ½ |y − p(t)|² over t = 0, 1 and the roots in (0, 1) of its derivative, the cubic
/// f(t) = (p(t) − y)·(B + 2 C t), each bracketed between the roots of f' (a quadratic) and found
/// by bisection: deterministic, no starting guess.
double closest_on_parabola(const Eigen::Vector3d& A, const Eigen::Vector3d& B,
                           const Eigen::Vector3d& C, const Eigen::Vector3d& y) {
  const Eigen::Vector3d d = y - A;
  // f(t) = c0 + c1 t + c2 t² + c3 t³
  const double c0 = -d.dot(B), c1 = B.dot(B) - 2 * d.dot(C), c2 = 3 * B.dot(C),
               c3 = 2 * C.dot(C);
  const auto f = [&](double t) { return c0 + t * (c1 + t * (c2 + t * c3)); };
  const auto distance2 = [&](double t) { return (y - A - t * (B + t * C)).squaredNorm(); };
  // Breaks of monotonicity of f in (0, 1): roots of f'(t) = c1 + 2 c2 t + 3 c3 t².
  std::array<double, 4> breaks{0.0, 1.0, 1.0, 1.0};
  int nb = 1;
  const double qa = 3 * c3, qb = 2 * c2, qc = c1;
  const double disc = qb * qb - 4 * qa * qc;
  if (qa > 0 && disc > 0) {
    const double s = std::sqrt(disc);
    const double q = -0.5 * (qb + (qb >= 0 ? s : -s));  // stable quadratic roots
    std::array<double, 2> roots{q / qa, q != 0 ? qc / q : 0.0};
    std::sort(roots.begin(), roots.end());
    for (double r : roots)
      if (r > 0 && r < 1) breaks[nb++] = r;
  } else if (qa == 0 && qb != 0) {
    const double r = -qc / qb;
    if (r > 0 && r < 1) breaks[nb++] = r;
  }
  breaks[nb++] = 1.0;
  double best_t = 0.0, best = distance2(0.0);
  if (distance2(1.0) < best) best = distance2(1.0), best_t = 1.0;
  for (int i = 0; i + 1 < nb; ++i) {
    double lo = breaks[i], hi = breaks[i + 1];
    double flo = f(lo), fhi = f(hi);
    if (!(flo < 0 && fhi > 0)) continue;  // a minimum needs f going from − to +
    for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (f(mid) < 0 ? lo : hi) = mid;
    }
    const double t = 0.5 * (lo + hi);
    if (distance2(t) < best) best = distance2(t), best_t = t;
  }
  return best_t;
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
  constexpr int nc = facet_corners<NM>;
  const auto objective = [&](const Eigen::Vector2d& xi) {
    return 0.5 * (xs - x * facet_shape_functions<NM>(xi)).squaredNorm();
  };
  Eigen::Vector2d xi = xi0;
  for (int it = 1; it <= max_newton_iterations; ++it) {
    const Eigen::Vector3d r = xs - x * facet_shape_functions<NM>(xi);
    const Eigen::Matrix<double, 3, 2> a = x * facet_shape_derivatives<NM>(xi);
    const Eigen::Vector2d grad = -a.transpose() * r;
    const Eigen::Matrix2d H = distance_hessian(a, r, second_derivatives<NM>(x, xi));
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
    if ((NM != 3 && far_outside(nc, xi))) return {xi, false, true, it};  // left the facet
  }
  return {xi, false, false, max_newton_iterations};
}

/// Order of preference at equal distance.
int rank(Feature f) { return f == Feature::Face ? 0 : f == Feature::Edge ? 1 : 2; }

}  // namespace

Eigen::VectorXd facet_shape_functions(int num_nodes, const Eigen::Vector2d& xi) {
  check_num_nodes(num_nodes);
  switch (num_nodes) {
    case 3: return facet_shape_functions<3>(xi);
    case 4: return facet_shape_functions<4>(xi);
    case 6: return facet_shape_functions<6>(xi);
    default: return facet_shape_functions<9>(xi);
  }
}

Eigen::Matrix<double, Eigen::Dynamic, 2> facet_shape_derivatives(int num_nodes,
                                                                 const Eigen::Vector2d& xi) {
  check_num_nodes(num_nodes);
  switch (num_nodes) {
    case 3: return facet_shape_derivatives<3>(xi);
    case 4: return facet_shape_derivatives<4>(xi);
    case 6: return facet_shape_derivatives<6>(xi);
    default: return facet_shape_derivatives<9>(xi);
  }
}

Eigen::Matrix<double, Eigen::Dynamic, 3> facet_shape_second_derivatives(int num_nodes,
                                                                        const Eigen::Vector2d& xi) {
  check_num_nodes(num_nodes);
  switch (num_nodes) {
    case 3: return facet_shape_second_derivatives<3>(xi);
    case 4: return facet_shape_second_derivatives<4>(xi);
    case 6: return facet_shape_second_derivatives<6>(xi);
    default: return facet_shape_second_derivatives<9>(xi);
  }
}

Eigen::Vector2d facet_vertex_xi(int num_nodes, int k) {
  check_num_nodes(num_nodes);
  return (num_nodes == 4 || num_nodes == 9) ? facet_vertex_xi<4>(k) : facet_vertex_xi<3>(k);
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
  constexpr int nc = facet_corners<NM>;

  // Work relative to the centroid: rounding then scales with the facet, not with |x|.
  const Eigen::Vector3d centroid = master.rowwise().mean();
  const FacetNodes<NM> x = master.colwise() - centroid;
  const Eigen::Vector3d xs = x_s - centroid;
  const double xi_tol = 1e-12 * std::max(1.0, xs.norm() / L);

  // Boundary: exact closest point of each edge (a segment, or a parabola through the edge node).
  Candidate best{facet_vertex_xi<NM>(0), Feature::Vertex, 0, (xs - x.col(0)).norm()};
  for (int k = 0; k < nc; ++k) {
    const Eigen::Vector3d p = x.col(k), e = x.col((k + 1) % nc) - p;
    double t;
    Eigen::Vector3d to_point;  // x_s − p(t)
    if constexpr (facet_is_quadratic<NM>) {
      // p(t) = x_k (1 − t)(1 − 2t) + 4 x_m t (1 − t) + x_{k+1} t (2t − 1) = A + B t + C t².
      const Eigen::Vector3d q = x.col((k + 1) % nc), m = x.col(nc + k);
      const Eigen::Vector3d B = -3 * p + 4 * m - q, C = 2 * p - 4 * m + 2 * q;
      t = closest_on_parabola(p, B, C, xs);
      to_point = t == 1.0 ? Eigen::Vector3d(xs - q) : Eigen::Vector3d(xs - p - t * (B + t * C));
    } else {
      t = std::clamp((xs - p).dot(e) / e.squaredNorm(), 0.0, 1.0);
      to_point = xs - p - t * e;
    }
    Candidate c;
    if (t == 0.0) {
      c = {facet_vertex_xi<NM>(k), Feature::Vertex, k, (xs - p).norm()};
    } else if (t == 1.0) {
      c = {facet_vertex_xi<NM>(k + 1), Feature::Vertex, (k + 1) % nc, to_point.norm()};
    } else {
      // ξ_k + t (ξ_{k+1} − ξ_k) keeps the coordinate constant along the edge exact.
      const Eigen::Vector2d xi_k = facet_vertex_xi<NM>(k);
      c = {xi_k + t * (facet_vertex_xi<NM>(k + 1) - xi_k), Feature::Edge, k, to_point.norm()};
    }
    if (c.distance < best.distance ||
        (c.distance == best.distance && rank(c.feature) < rank(best.feature)))
      best = c;
  }

  // Face: Newton from several starts; keep the closest interior local minimum. A flat triangle
  // has one minimum at most; warped and curved facets may have several.
  std::array<Eigen::Vector2d, 5> starts{Eigen::Vector2d(0, 0), Eigen::Vector2d(0.5, 0.5),
                                        Eigen::Vector2d(-0.5, 0.5), Eigen::Vector2d(-0.5, -0.5),
                                        Eigen::Vector2d(0.5, -0.5)};
  int num_starts = 5;
  if constexpr (NM == 3) {
    starts[0] = Eigen::Vector2d(1.0 / 3, 1.0 / 3);
    num_starts = 1;
  } else if constexpr (NM == 6) {
    starts = {Eigen::Vector2d(1.0 / 3, 1.0 / 3), Eigen::Vector2d(0.6, 0.2),
              Eigen::Vector2d(0.2, 0.6), Eigen::Vector2d(0.2, 0.2), Eigen::Vector2d(1.0 / 3, 1.0 / 3)};
    num_starts = 4;
  }
  int iterations = 0;
  bool converged = true;
  bool have_face = false;
  Candidate face{};
  for (int s = 0; s < num_starts; ++s) {
    const NewtonOutcome o = newton<NM>(x, xs, starts[s], xi_tol, L);
    iterations += o.iterations;
    converged = converged && o.concluded;
    if (!o.stationary || !inside(nc, o.xi, inside_tol)) continue;
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

#define HYPERCONTACT_FACET(NM)                                                           \
  template Eigen::Vector3d facet_normal<NM>(const FacetNodes<NM>&, const Eigen::Vector2d&); \
  template FacetProjection project_to_facet<NM>(const FacetNodes<NM>&, const Eigen::Vector3d&);
HYPERCONTACT_FACET(3)
HYPERCONTACT_FACET(4)
HYPERCONTACT_FACET(6)
HYPERCONTACT_FACET(9)
#undef HYPERCONTACT_FACET

Eigen::Vector3d facet_normal(const NodeCoordinates& x, const Eigen::Vector2d& xi) {
  check_num_nodes(static_cast<int>(x.cols()));
  switch (x.cols()) {
    case 3: return facet_normal<3>(FacetNodes<3>(x), xi);
    case 4: return facet_normal<4>(FacetNodes<4>(x), xi);
    case 6: return facet_normal<6>(FacetNodes<6>(x), xi);
    default: return facet_normal<9>(FacetNodes<9>(x), xi);
  }
}

FacetProjection project_to_facet(const NodeCoordinates& master, const Eigen::Vector3d& x_s) {
  check_num_nodes(static_cast<int>(master.cols()));
  switch (master.cols()) {
    case 3: return project_to_facet<3>(FacetNodes<3>(master), x_s);
    case 4: return project_to_facet<4>(FacetNodes<4>(master), x_s);
    case 6: return project_to_facet<6>(FacetNodes<6>(master), x_s);
    default: return project_to_facet<9>(FacetNodes<9>(master), x_s);
  }
}

}  // namespace hypercontact
