"""Inflation of a thick spherical shell: an independent 1D reference.

Pure numpy/scipy, nothing from hypercontact. Units mm, MPa.

Geometry and kinematics
    Reference shell A ≤ R ≤ B (defaults A = 95, B = 96), deformed r = r(R).
    λ_r = dr/dR, λ_θ = λ_φ = r/R, J = λ_r λ_θ².
    Inner radius a = r(A); inner radial displacement u = a − A  (the control).
    Pressure p: Cauchy pressure on the deformed inner surface, σ_r(A) = −p;
    the outer surface is traction free, σ_r(B) = 0.

Laws (energy per reference volume, isochoric split), ``law``/``params`` as in
the scenes: ("mooney_rivlin", dict(alpha1, alpha2, K, i2="usual"|"paper"))
or ("neo_hookean", dict(mu, K)). With x = λ_r, y = λ_θ every isochoric
invariant is a sum of monomials c x^m y^n:
    Ī1 = J^(-2/3)(x² + 2y²)           = x^(4/3) y^(-4/3) + 2 x^(-2/3) y^(2/3)
    Ī2 usual = J^(-4/3)(2x²y² + y⁴)   = 2 x^(2/3) y^(-2/3) + x^(-4/3) y^(4/3)
    Ī2 paper = J^(-4/3)(x⁴ + 2y⁴)     = x^(8/3) y^(-8/3) + 2 x^(-4/3) y^(4/3)
    ψ = α1(Ī1 − 3) + α2(Ī2 − 3) + K/2 (J − 1)²      (neo-Hookean: μ/2 (Ī1 − 3) + ...)
so ψ and its first and second derivatives are written ANALYTICALLY (monomial
rule plus the volumetric term); ``psi`` also accepts complex stretches, and
the tests check the analytic derivatives against complex-step ones.

Equilibrium (total Lagrangian). Nominal stresses P_r = ∂ψ/∂λ_r and
P_θ = ½ ∂ψ/∂λ_θ (ψ(λ_r, λ_θ) has λ_θ twice). Div P = 0 in spherical symmetry:
    dP_r/dR + 2 (P_r − P_θ)/R = 0          ⇔  d(R² P_r)/dR = 2 R P_θ.
Cauchy: σ_r = P_r λ_r / J = P_r / λ_θ², σ_θ = P_θ / (λ_r λ_θ). Hence
    P_r(B) = 0,   p = −σ_r(A) = −P_r(A) / λ_θ(A)² = −P_r(A) (A/a)².
Discretisation: Chebyshev collocation (N+1 Gauss–Lobatto nodes) for r(R),
equilibrium at the interior nodes, r(A) = a and P_r(B) = 0 at the ends,
Newton with the analytic Jacobian, residual in long double (see ``Sphere``);
p from the integral form p a² = ∫_A^B 2R P_θ dR (Clenshaw–Curtis). Spectral
accuracy: the default N = 24 agrees with N = 32, 40 to ~1e-14 relative in p
and ~1e-9 mm in u_max (see tests). ``solve_shooting`` is a second,
independent discretisation (solve_ivp DOP853, rtol 1e-12, secant on P_r(B) = 0).

Incompressible closed form (Ogden, Non-linear elastic deformations §5.3.3):
r³ − a³ = R³ − A³, λ = r/R, Ŵ(λ) = W(λ^(-2), λ) (isochoric part), and
    p = ∫_{λ_b}^{λ_a} Ŵ'(λ) / (λ³ − 1) dλ,   λ_a = a/A, λ_b = b/B, b³ = a³ + B³ − A³,
    with Ī1 = λ^(-4) + 2λ², Ī2 usual = 2λ^(-2) + λ⁴, Ī2 paper = λ^(-8) + 2λ⁴.

Linear elasticity (Lamé, thick sphere), moduli μ0 and κ = K (small-strain
limit of the split energy; μ0 = 2(α1 + α2) usual, 2α1 + 8α2 paper, μ):
    u(R) = c1 R + c2/R²,  σ_r = 3κ c1 − 4μ0 c2/R³,  σ_r(A) = −p, σ_r(B) = 0
    ⇒ c1 = p A³ / (3κ(B³ − A³)),  c2 = p A³B³ / (4μ0(B³ − A³)),
      u(A) = p A³/(B³ − A³) · (A/(3κ) + B³/(4μ0 A²)).
"""
from collections import namedtuple

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

A0, B0 = 95.0, 96.0
PAPER = dict(alpha1=0.1863, alpha2=0.0098)

LD = np.longdouble  # 80-bit x87 on x86-64: eps 1.1e-19 (see Sphere)
_3 = LD(3)
# isochoric invariants, as monomials (coefficient, power of λ_r, power of λ_θ)
_I1 = ((1, 4 / _3, -4 / _3), (2, -2 / _3, 2 / _3))
_I2 = {"usual": ((2, 2 / _3, -2 / _3), (1, -4 / _3, 4 / _3)),
       "paper": ((1, 8 / _3, -8 / _3), (2, -4 / _3, 4 / _3))}


def _terms(law, params):
    """(monomials [(c, m, n)], constant, K) with ψ = Σ c x^m y^n + constant + K/2 (J−1)²
    (K is None if absent: only the incompressible closed form may omit it)."""
    if params.get("volumetric", "quadratic") != "quadratic":
        raise ValueError(f"the 1-D sphere has the paper's volumetric energy K/2 (J − 1)² only, "
                         f"found volumetric = {params['volumetric']!r}")
    if law == "mooney_rivlin":
        a1, a2 = params["alpha1"], params["alpha2"]
        i2 = params.get("i2", "usual")
        if i2 not in _I2:
            raise ValueError(f"i2 must be 'usual' or 'paper', got {i2!r}")
        terms = [(a1 * c, m, n) for c, m, n in _I1] + [(a2 * c, m, n) for c, m, n in _I2[i2]]
        return terms, -3.0 * (a1 + a2), params.get("K")
    if law == "neo_hookean":
        mu = params["mu"]
        return [(0.5 * mu * c, m, n) for c, m, n in _I1], -1.5 * mu, params.get("K")
    raise ValueError(f"unknown law {law!r}")


def psi(law, params, lr, lt):
    """ψ(λ_r, λ_θ) (λ_φ = λ_θ); complex-safe, for complex-step checks
    (long-double exponents: the result is long double / complex long double)."""
    terms, const, K = _terms(law, params)
    J = lr * lt**2
    return sum(c * lr**m * lt**n for c, m, n in terms) + const + 0.5 * K * (J - 1) ** 2


def psi_derivs(law, params, lr, lt):
    """Analytic (ψ_r, ψ_θ, ψ_rr, ψ_rθ, ψ_θθ), ∂ w.r.t. λ_r and λ_θ (the λ_θ of
    both hoop directions together, so P_θ = ψ_θ/2)."""
    terms, _, K = _terms(law, params)
    x, y = np.asarray(lr) + 0.0, np.asarray(lt) + 0.0   # float64 or long double
    J = x * y**2
    out = [K * (J - 1) * y**2, K * (J - 1) * 2 * x * y,
           K * y**4, K * (2 * x * y**3 + 2 * y * (J - 1)), K * (4 * x**2 * y**2 + 2 * x * (J - 1))]
    for c, m, n in terms:
        t = c * x**m * y**n
        out[0] = out[0] + m * t / x
        out[1] = out[1] + n * t / y
        out[2] = out[2] + m * (m - 1) * t / x**2
        out[3] = out[3] + m * n * t / (x * y)
        out[4] = out[4] + n * (n - 1) * t / y**2
    return tuple(out)


def nominal_stresses(law, params, lr, lt):
    """(P_r, P_θ) = (∂ψ/∂λ_r, ½ ∂ψ/∂λ_θ)."""
    d = psi_derivs(law, params, lr, lt)
    return d[0], 0.5 * d[1]


def small_strain_moduli(law, params):
    """(μ0, κ): shear modulus of the law at rest and bulk modulus κ = K."""
    if law == "neo_hookean":
        return params["mu"], params["K"]
    a1, a2 = params["alpha1"], params["alpha2"]
    return (2 * (a1 + a2) if params.get("i2", "usual") == "usual" else 2 * a1 + 8 * a2), params["K"]


def lame_inner_displacement(p, mu0, kappa, A=A0, B=B0):
    """Linear-elastic u(A) = p A³/(B³ − A³) · (A/(3κ) + B³/(4μ0 A²))."""
    return p * A**3 / (B**3 - A**3) * (A / (3 * kappa) + B**3 / (4 * mu0 * A**2))


# ----------------------------------------------------------------- collocation
def _cheb(N, A, B):
    """Gauss–Lobatto nodes R_j (R_0 = B, R_N = A), d/dR matrix (Trefethen,
    Spectral methods in MATLAB, cheb) and Clenshaw–Curtis weights (clencurt),
    all in long double."""
    th = np.arccos(LD(-1)) * np.arange(N + 1) / N
    xi = np.cos(th)
    c = np.r_[2, np.ones(N - 1), 2] * (-1.0) ** np.arange(N + 1)
    dX = xi[:, None] - xi[None, :]
    D = np.outer(c, 1 / c) / (dX + np.eye(N + 1))
    D -= np.diag(D.sum(axis=1))
    v = np.ones(N + 1, LD)                       # clencurt, N even or odd
    inner = slice(1, N)
    if N % 2 == 0:
        v[inner] -= np.cos(N * th[inner]) / (N**2 - 1)
        kmax = N // 2
    else:
        kmax = (N + 1) // 2
    for k in range(1, kmax):
        v[inner] -= 2 * np.cos(2 * k * th[inner]) / (4 * k**2 - 1)
    w_end = LD(1) / (N**2 - 1 if N % 2 == 0 else N**2)
    wq = np.r_[w_end, 2 * v[inner] / N, w_end]
    h = (LD(B) - LD(A)) / 2
    return (LD(A) + LD(B)) / 2 + h * xi, D / h, wq * h


def _lsolve(M, b):
    """Solve M x = b in double with rows equilibrated (interior rows ~K N⁴,
    end rows ~K N² and 1: equilibration lowers cond from ~1e8 to ~1e4)."""
    s = 1 / np.abs(M).max(axis=1)
    return np.linalg.solve((s[:, None] * M).astype(float), (s * b).astype(float))


Solution = namedtuple("Solution", "u a p dpdu R r lr lt Pr Pt sr st")
Solution.__doc__ = """Radial field on the Chebyshev nodes (R[0] = B, R[-1] = A):
u = a − A, p inner Cauchy pressure, dpdu = dp/du (tangent, for limit points),
r(R), stretches lr = λ_r, lt = λ_θ, nominal Pr, Pt, Cauchy sr = σ_r, st = σ_θ."""


class Sphere:
    """Collocation solver for one law; remembers its last solution as the
    warm start of the next ``solve`` (displacement control, continuation).

    Unknown: the displacement w = r − R at the nodes; λ_r = 1 + D (w − w_A)
    and λ_θ = 1 + w/R keep their digits (D r with r ≈ 95 would lose ~4).
    Mixed precision: residual, p and dp/du are evaluated in long double,
    the Newton corrections solved in double (iterative refinement), because
    near incompressibility P_θ ~ μ is a difference of O(K δλ) terms and
    dp/du ≈ 0 at the limit point; in double, u_max would carry ~1e-7 mm of
    rounding noise at K = 200, in long double it is below 1e-9 mm."""

    def __init__(self, law, params, N=24, A=A0, B=B0):
        self.law, self.params, self.N, self.A, self.B = law, params, N, A, B
        self.R, self.D, self.wq = _cheb(N, A, B)
        self._last = None  # (u, w, dw/du)

    def _state(self, w):
        lr, lt = 1 + self.D @ (w - w[-1]), 1 + w / self.R
        return lr, lt, psi_derivs(self.law, self.params, lr, lt)

    def _residual(self, w, u, jac=True, dtype=float):
        """Collocation residual F (long double) and, if jac, its Jacobian
        ∂F/∂w in dtype (double for the Newton corrections, long double for
        the refined tangent)."""
        R, D = self.R, self.D
        lr, lt, d = self._state(w)
        Pr, Pt = d[0], 0.5 * d[1]
        F = D @ Pr + 2 * (Pr - Pt) / R          # equilibrium, interior rows
        F[0] = Pr[0]                           # P_r(B) = 0
        F[-1] = w[-1] - u                      # w(A) = u
        if not jac:
            return F, None
        R, D = R.astype(dtype), D.astype(dtype)
        drr, drt, dtt = (v.astype(dtype) for v in d[2:])
        dPr = drr[:, None] * D + np.diag(drt / R)          # ∂P_r/∂w
        dPt = 0.5 * (drt[:, None] * D + np.diag(dtt / R))  # ∂P_θ/∂w
        Jm = D @ dPr + (2 / R)[:, None] * (dPr - dPt)
        Jm[0] = dPr[0]
        Jm[-1] = 0
        Jm[-1, -1] = 1
        return F, Jm

    def _newton(self, u, w):
        prev = np.inf
        for it in range(80):
            F, Jm = self._residual(w, u)
            dw = _lsolve(Jm, -F)
            step = 1.0
            if it > 4:  # damped only if the plain steps did not settle
                f0 = np.linalg.norm(F.astype(float))
                while step > 1e-3 and np.linalg.norm(
                        self._residual(w + step * dw, u, False)[0].astype(float)) > f0:
                    step *= 0.5
            w = w + step * dw
            size = np.max(np.abs(dw)) / (1 + np.max(np.abs(w)))
            # converged: at long-double rounding, or stagnating below 1e-15
            if size < 1e-17 or (size < 1e-15 and size > 0.3 * prev):
                return w
            prev = size
        raise RuntimeError(f"Newton did not converge at u = {u}")

    def solve(self, u, max_step=5.0):
        """Equilibrium at inner displacement u = a − A (continuation from the
        last solution, or from the undeformed shell, in steps ≤ max_step,
        with the tangent dw/du as predictor)."""
        if self._last is None:
            self._last = (0.0, np.zeros_like(self.R), None)
        u0, w, t = self._last
        n = max(1, int(np.ceil(abs(u - u0) / max_step)))
        for ui in np.linspace(u0, LD(u), n + 1)[1:]:
            w = self._newton(ui, w + (ui - u0) * t if t is not None else w)
            Jm = self._residual(w, ui, dtype=LD)[1]
            e = np.zeros_like(w)
            e[-1] = 1
            t = _lsolve(Jm, e)                 # dw/du (∂F/∂u = −e_A), refined:
            for _ in range(2):
                t = t + _lsolve(Jm, e - Jm @ t)
            u0 = ui
        self._last = (u0, w, t)
        return self._solution(w, t)

    def _solution(self, w, t):
        """p from the integral form of equilibrium, better conditioned than
        −P_r(A)/λ_θ(A)² (P_r(A) ~ μ t/R is a small difference of O(μ + K δλ)):
            R² P_r |_A^B = ∫ 2R P_θ dR  ⇒  p a² = ∫_A^B 2 R P_θ dR,
        by Clenshaw–Curtis; dp/du = (2/a²) Σ w_j R_j (∂P_θ/∂w · dw/du)_j − 2p/a,
        with the tangent dw/du from the Jacobian."""
        R = self.R
        lr, lt, d = self._state(w)
        Pr, Pt = d[0], 0.5 * d[1]
        a = R[-1] + w[-1]
        p = 2 * (self.wq * R) @ Pt / a**2
        dPt_t = 0.5 * (d[3] * (self.D @ (t - t[-1])) + d[4] * t / R)  # ∂P_θ/∂w · t
        dpdu = 2 * (self.wq * R) @ dPt_t / a**2 - 2 * p / a
        f = lambda z: np.asarray(z, float)
        return Solution(float(w[-1]), float(a), float(p), float(dpdu), f(R), f(R + w),
                        f(lr), f(lt), f(Pr), f(Pt), f(Pr / lt**2), f(Pt / (lr * lt)))


def solve(law, params, u, N=24, A=A0, B=B0):
    """Radial field (``Solution``) at inner displacement u = a − A."""
    return Sphere(law, params, N, A, B).solve(u)


def pressure_curve(law, params, u, N=24, A=A0, B=B0):
    """Inner pressure p (MPa) for each inner radial displacement u = a − A (mm);
    the shell is followed by continuation in u, so the curve may pass the
    limit point (p decreasing in u)."""
    u = np.atleast_1d(np.asarray(u, float))
    sph, p = Sphere(law, params, N, A, B), np.empty(len(u))
    for i in np.argsort(u):
        p[i] = sph.solve(u[i]).p
    return p


def limit_point(law, params, N=24, A=A0, B=B0, du=2.0, u_stop=None):
    """(u_max, p_max): the first maximum of p(u), i.e. the first root of the
    analytic tangent dp/du (brentq, xtol 1e-13 mm). Scans u in steps of du up
    to u_stop (default 3A); returns (nan, nan) if p(u) keeps rising."""
    sph = Sphere(law, params, N, A, B)
    u_stop = 3 * A if u_stop is None else u_stop
    u0, g0 = 0.0, sph.solve(0.0).dpdu
    while u0 < u_stop:
        g1 = sph.solve(u0 + du).dpdu
        if g0 > 0 >= g1:
            um = brentq(lambda v: sph.solve(v).dpdu, u0, u0 + du, xtol=1e-13, rtol=1e-15)
            return um, sph.solve(um).p
        u0, g0 = u0 + du, g1
    return np.nan, np.nan


def solve_shooting(law, params, u, lr_guess, A=A0, B=B0, rtol=1e-12):
    """Second discretisation (check): integrate r'' from
    d/dR P_r(r', r/R) = −2(P_r − P_θ)/R, i.e.
        r'' = −[ψ_rθ (λ_r − λ_θ) + 2ψ_r − ψ_θ] / (R ψ_rr),
    from r(A) = a, r'(A) = λ_r(A), with Newton (secant) on λ_r(A) until
    P_r(B) = 0. Returns (p, λ_r(A))."""
    a = A + u

    def rhs(R, z):
        r, dr = z
        d = [float(v) for v in psi_derivs(law, params, dr, r / R)]
        return [dr, -(d[3] * (dr - r / R) + 2 * d[0] - d[1]) / (R * d[2])]

    def outer(s):
        z = solve_ivp(rhs, (A, B), [a, s], method="DOP853", rtol=rtol, atol=1e-14 * a).y[:, -1]
        return float(psi_derivs(law, params, z[1], z[0] / B)[0])

    s0, s1 = lr_guess, lr_guess * (1 + 1e-7)
    f0, f1 = outer(s0), outer(s1)
    for _ in range(30):
        if f1 == f0:
            break
        s0, s1, f0 = s1, s1 - f1 * (s1 - s0) / (f1 - f0), f1
        f1 = outer(s1)
        if abs(s1 - s0) < 1e-15 * abs(s1):
            break
    return -float(psi_derivs(law, params, s1, a / A)[0]) * (A / a) ** 2, s1


# ---------------------------------------------------------- incompressible
def _What_prime(law, params, lam):
    """Ŵ'(λ) for Ŵ(λ) = W_iso(λ^(-2), λ): monomial x^m y^n → λ^(n − 2m)."""
    terms, _, _ = _terms(law, params)
    return float(sum(c * float(n - 2 * m) * lam ** float(n - 2 * m - 1) for c, m, n in terms))


def incompressible_pressure(law, params, u, A=A0, B=B0, with_derivative=False):
    """Closed form p = ∫_{λ_b}^{λ_a} Ŵ'(λ)/(λ³ − 1) dλ at u = a − A (K ignored);
    optionally also dp/du = f(λ_a)/A − f(λ_b) a²/(b² B), f = Ŵ'/(λ³ − 1)."""
    f = lambda lam: _What_prime(law, params, lam) / (lam**3 - 1)
    out = []
    for ui in np.atleast_1d(np.asarray(u, float)):
        a = A + ui
        b = np.cbrt(a**3 + B**3 - A**3)
        la, lb = a / A, b / B
        p = quad(f, lb, la, epsabs=0, epsrel=1e-13, limit=200)[0] if ui != 0 else 0.0
        out.append((p, f(la) / A - f(lb) * a**2 / (b**2 * B)) if with_derivative else p)
    return np.array(out) if np.ndim(u) else out[0]


def incompressible_limit_point(law, params, A=A0, B=B0, du=2.0, u_stop=None):
    """(u_max, p_max) of the incompressible closed form (root of dp/du)."""
    g = lambda v: incompressible_pressure(law, params, v, A, B, True)[1]
    u0, u_stop = du, 3 * A if u_stop is None else u_stop
    while u0 < u_stop:
        if g(u0) > 0 >= g(u0 + du):
            um = brentq(g, u0, u0 + du, xtol=1e-13, rtol=1e-15)
            return um, incompressible_pressure(law, params, um, A, B)
        u0 += du
    return np.nan, np.nan


if __name__ == "__main__":
    print("limit points of p(u), A = 95, B = 96, alpha1 = 0.1863, alpha2 = 0.0098")
    print(f"{'I2':>6} {'K':>8} {'u_max [mm]':>16} {'p_max [MPa]':>18}")
    for i2 in ("usual", "paper"):
        for K in (1.0, 5.0, 200.0):
            um, pm = limit_point("mooney_rivlin", dict(PAPER, K=K, i2=i2))
            print(f"{i2:>6} {K:8g} {um:16.10f} {pm:18.12e}")
        um, pm = incompressible_limit_point("mooney_rivlin", dict(PAPER, i2=i2))
        print(f"{i2:>6} {'inf':>8} {um:16.10f} {pm:18.12e}")
