"""Exact resistance functions of two equal spheres (lambda = a2/a1 = 1) from the twin-multipole
recurrences of Jeffrey & Onishi (1984, J. Fluid Mech. 139, 261; JO) and Jeffrey (1992, Phys.
Fluids A 4, 16; J92), in the corrected form of Townsend (2018, arXiv:1802.08226, eqs. 5-9 and the
J&O 4.6-4.11, 7.3-7.5 equations it restates).

Normalisation and signs are JO's (Kim & Karrila 1991, ch. 11): A by 6 pi mu a, B and G by
4 pi mu a^2, C and H by 8 pi mu a^3; d points from sphere 1 to sphere 2 and the "12" functions
are those of sphere 1 responding to sphere 2.

Method. The recurrences give the coefficients c_m of the far-field series f(s) = sum c_m y^m in
y = 2/s (s = r/a), even or odd m only. The series converges for s > 2 but only algebraically at
contact, because f has the near-contact form g1/xi + g2 ln(1/xi) + const + g3 xi ln(1/xi)
(xi = s - 2). Following JO section 3, the part of c_m that produces these singular terms,
a_m = g1 + 2 g2/m - 4 g3/(m (m + 2)), is summed in closed form and only c_m - a_m is summed
numerically; the singular coefficients g are JO's / Townsend's. The remainder c_m - a_m decays like
m^-2 with an oscillating sign, so at contact the partial sums oscillate about the limit: with
K = 150-200 terms the functions change by <= 2e-4 (relative) between K = 150 and 200 at s = 2.001
(make_reference.py reports it). This gives the functions at any s >= 2 with one set of coefficients.

Run as a script to print the functions at a few distances: python3 jeffrey_onishi.py [K].
"""
import math
import os
import pickle

import numpy as np

# Singular coefficients (g1, g2, g3) of each function at lambda = 1 (Townsend 2018 eqs. 10-12 and
# the G-, H-polynomials there, evaluated at lambda = 1; physics-reference-values.md section 2b).
SINGULAR = {
    "XA11": (1 / 4, 9 / 40, 3 / 112), "XA12": (-1 / 4, -9 / 40, -3 / 112),
    "YA11": (0.0, 1 / 6, 0.0), "YA12": (0.0, -1 / 6, 0.0),
    "YB11": (0.0, -1 / 4, -1 / 8), "YB12": (0.0, 1 / 4, 1 / 8),
    "XC11": (0.0, 0.0, -1 / 8), "XC12": (0.0, 0.0, 1 / 8),
    "YC11": (0.0, 1 / 5, 47 / 250), "YC12": (0.0, 1 / 20, 31 / 500),
    "XG11": (3 / 8, 27 / 80, 117 / 560), "XG12": (-3 / 8, -27 / 80, -117 / 560),
    "YG11": (0.0, 1 / 8, 1 / 16), "YG12": (0.0, -1 / 8, -1 / 16),
    "YH11": (0.0, 1 / 40, 137 / 2000), "YH12": (0.0, 1 / 10, 113 / 2000),
}
NAMES = list(SINGULAR)


def _binomials(nmax):
    """B[a, b] = C(a, b) as floats for a <= 2 nmax + 2."""
    size = 2 * nmax + 3
    B = np.zeros((size, size))
    for a in range(size):
        for b in range(a + 1):
            B[a, b] = float(math.comb(a, b))
    return B


class _Grid:
    """Index arrays for one (p, q) step of a recurrence: s = 1..q (rows) against n = 1..N (columns)."""

    def __init__(self, N, p, q):
        self.s = np.arange(1, q + 1)[:, None]
        self.n = np.arange(1, N + 1)[None, :]
        self.p, self.q = p, q

    def take(self, X, second_offset, third_offset):
        """X[s, q - s + second_offset, p - n + third_offset], zero outside the stored range."""
        s, n = self.s, self.n
        second = np.broadcast_to(self.q - s + second_offset, (s.shape[0], n.shape[1]))
        third = np.broadcast_to(self.p - n + third_offset, (s.shape[0], n.shape[1]))
        first = np.broadcast_to(s, second.shape)
        ok = (second >= 0) & (second < X.shape[1]) & (third >= 0) & (third < X.shape[2])
        out = np.zeros(second.shape)
        out[ok] = X[first[ok], second[ok], third[ok]]
        return out


def _columns(N, K, T):
    """Largest n needed at total order T = p + q: an entry of order T is read only by entries of
    order >= T + n, and the series needs orders <= K, so n <= K - T (and n = 1, 2 always)."""
    return min(N, max(2, K - T))


def axisymmetric(K, start_n):
    """JO/Townsend X-problem recurrences (Townsend eqs. 5-8): P[n, p, q] for p + q <= K, with
    P(n,0,0) = V(n,0,0) = delta(start_n, n):
      P(n,p,q) = sum_s C(n+s, n) [ n(2n+1)(2ns-n-s+2) / (2(n+1)(2s-1)(n+s)) P(s, q-s, p-n+1)
                                   - n(2n-1)/(2(n+1)) P(s, q-s, p-n-1)
                                   - n(4n^2-1)/(2(n+1)(2s+1)) V(s, q-s-2, p-n+1) ],
      V(n,p,q) = P(n,p,q) - 2n/((n+1)(2n+3)) sum_s C(n+s, n) P(s, q-s, p-n-1).
    start_n = 1 gives X^A and, from P(2, ...), X^G (J92)."""
    N = K + 2
    P = np.zeros((N + 1, K + 1, K + 1))
    V = np.zeros_like(P)
    P[start_n, 0, 0] = V[start_n, 0, 0] = 1.0
    B = _binomials(N)
    for T in range(1, K + 1):
        for p in range(T + 1):
            q = T - p
            Nt = _columns(N, K, T)
            g = _Grid(Nt, p, q)
            s, n = g.s.astype(float), g.n.astype(float)
            c = B[g.n + g.s, g.n]
            up, dn, vv = g.take(P, 0, 1), g.take(P, 0, -1), g.take(V, -2, 1)
            acc = (c * (n * (2 * n + 1) * (2 * n * s - n - s + 2) / (2 * (n + 1) * (2 * s - 1) * (n + s)) * up
                        - n * (2 * n - 1) / (2 * (n + 1)) * dn
                        - n * (4 * n * n - 1) / (2 * (n + 1) * (2 * s + 1)) * vv)).sum(axis=0)
            corr = (c * dn).sum(axis=0)
            n1 = n[0]
            P[1:Nt + 1, p, q] = acc
            V[1:Nt + 1, p, q] = acc - 2 * n1 / ((n1 + 1) * (2 * n1 + 3)) * corr
    return P


def transverse(K, p_start, q_start):
    """JO/Townsend Y-problem recurrences (J&O 4.6-4.11 and 7.3-7.5 as corrected by Townsend):
      P(n,p,q) = sum_s C(n+s, n+1) [ (2n+1)/(2(n+1)) (3(n+s) - (ns+1)(2ns-s-n+2))/(s(n+s)(2s-1)) P(s,q-s,p-n+1)
                                     + n(2n-1)/(2(n+1)) P(s,q-s,p-n-1)
                                     + n(4n^2-1)/(2(n+1)(2s+1)) V(s,q-s-2,p-n+1)
                                     - 2(4n^2-1)/(3(n+1)) Q(s,q-s-1,p-n+1) ],
      V(n,p,q) = P(n,p,q) + 2n/((n+1)(2n+3)) sum_s C(n+s, n+1) P(s,q-s,p-n-1),
      Q(n,p,q) = sum_s C(n+s, n+1) [ s/(n+1) Q(s,q-s-1,p-n) - 3/(2ns(n+1)) P(s,q-s,p-n) ],
    with P(n,0,0) = V(n,0,0) = p_start delta(1,n), Q(n,0,0) = q_start delta(1,n). (1, 0) gives
    Y^A, Y^B (and Y^G from P(2, ...)); (0, 1) gives Y^C (and Y^H from P(2, ...))."""
    N = K + 2
    P = np.zeros((N + 1, K + 1, K + 1))
    V = np.zeros_like(P)
    Q = np.zeros_like(P)
    P[1, 0, 0] = V[1, 0, 0] = p_start
    Q[1, 0, 0] = q_start
    B = _binomials(N)
    for T in range(1, K + 1):
        for p in range(T + 1):
            q = T - p
            Nt = _columns(N, K, T)
            g = _Grid(Nt, p, q)
            s, n = g.s.astype(float), g.n.astype(float)
            c = B[g.n + g.s, g.n + 1]
            up, dn, vv, qq = g.take(P, 0, 1), g.take(P, 0, -1), g.take(V, -2, 1), g.take(Q, -1, 1)
            q0, p0 = g.take(Q, -1, 0), g.take(P, 0, 0)
            accP = (c * ((2 * n + 1) / (2 * (n + 1))
                         * (3 * (n + s) - (n * s + 1) * (2 * n * s - s - n + 2)) / (s * (n + s) * (2 * s - 1)) * up
                         + n * (2 * n - 1) / (2 * (n + 1)) * dn
                         + n * (4 * n * n - 1) / (2 * (n + 1) * (2 * s + 1)) * vv
                         - 2 * (4 * n * n - 1) / (3 * (n + 1)) * qq)).sum(axis=0)
            accQ = (c * (s / (n + 1) * q0 - 3 / (2 * n * s * (n + 1)) * p0)).sum(axis=0)
            accV = (c * dn).sum(axis=0)
            n1 = n[0]
            P[1:Nt + 1, p, q] = accP
            Q[1:Nt + 1, p, q] = accQ
            V[1:Nt + 1, p, q] = accP + 2 * n1 / ((n1 + 1) * (2 * n1 + 3)) * accV
    return P, Q


def _f(X, n_index, K, scale):
    """f_k = scale 2^k sum_q X(n_index, k - q, q) (lambda = 1), k = 0..K."""
    return np.array([scale * 2.0 ** k * sum(X[n_index, k - q, q] for q in range(k + 1)) for k in range(K + 1)])


_memory = {}
CACHE_DIR = os.environ.get("FLDSIM_TWOBODY_CACHE", "")


def series_coefficients(K=200):
    """The series coefficients for K terms, computed once per process (and kept in CACHE_DIR,
    from the environment variable FLDSIM_TWOBODY_CACHE, if set: K = 200 takes many minutes)."""
    if K in _memory:
        return _memory[K]
    path = os.path.join(CACHE_DIR, f"jo_series_K{K}.pkl") if CACHE_DIR else ""
    if path and os.path.exists(path):
        with open(path, "rb") as f:
            _memory[K] = pickle.load(f)
        return _memory[K]
    _memory[K] = _compute_series(K)
    if path:
        os.makedirs(CACHE_DIR, exist_ok=True)
        with open(path, "wb") as f:
            pickle.dump(_memory[K], f)
    return _memory[K]


def _compute_series(K):
    """c[name] = (sign, parity, array over m of the y^m coefficient), y = 2/s, for lambda = 1.
    JO's series are f = (prefactor) sum_k f_k ((1 + lambda) s)^-k over even or odd k; at
    lambda = 1, (1 + lambda) s = 4/y, so the y^m coefficient is f_m / 4^m."""
    Pxa = axisymmetric(K, 1)
    Pya, Qya = transverse(K, 1.0, 0.0)
    Pyc, Qyc = transverse(K, 0.0, 1.0)
    f = {
        "A_X": _f(Pxa, 1, K, 1.0),
        "A_Y": _f(Pya, 1, K, 1.0),
        "B_Y": _f(Qya, 1, K, 2.0),
        "C_Y": _f(Qyc, 1, K, 1.0),
        "G_X": _f(Pxa, 2, K, 0.75),
        "G_Y": _f(Pya, 2, K, 0.75),
        "H_Y": _f(Pyc, 2, K, -0.375),
    }
    w = 0.25 ** np.arange(K + 1)
    # (function, series, parity of m, sign); the "12" prefactors 2/(1+lambda), 4/(1+lambda)^2,
    # 8/(1+lambda)^3 of JO are 1 at lambda = 1.
    table = {
        "XA11": ("A_X", 0, +1), "XA12": ("A_X", 1, -1),
        "YA11": ("A_Y", 0, +1), "YA12": ("A_Y", 1, -1),
        "YB11": ("B_Y", 1, +1), "YB12": ("B_Y", 0, -1),
        "YC11": ("C_Y", 0, +1), "YC12": ("C_Y", 1, +1),
        "XG11": ("G_X", 1, +1), "XG12": ("G_X", 0, -1),
        "YG11": ("G_Y", 1, +1), "YG12": ("G_Y", 0, -1),
        "YH11": ("H_Y", 0, +1), "YH12": ("H_Y", 1, +1),
    }
    out = {}
    for name, (key, parity, sign) in table.items():
        c = f[key] * w
        c[(np.arange(K + 1) % 2) != parity] = 0.0
        out[name] = (sign, parity, c)
    return out


def _singular_sums(y, parity):
    """Closed forms over m >= 1 of the given parity: S0 = sum y^m, S1 = sum y^m / m,
    S2 = sum y^m / (m (m + 2))."""
    if parity == 0:  # m = 2, 4, ...
        S0 = y * y / (1 - y * y)
        S1 = -0.5 * np.log1p(-y * y)
        S2 = 0.5 * S1 * (1 - 1 / (y * y)) + 0.25
    else:  # m = 1, 3, ...
        S0 = y / (1 - y * y)
        S1 = np.arctanh(y)
        S2 = 0.5 * S1 * (1 - 1 / (y * y)) + 0.5 / y
    return S0, S1, S2


def twist_functions(s):
    """X^C_11, X^C_12 (rotation about the line of centres) in closed form. The torsional problem
    separates in bispherical coordinates (Jeffery 1915, Proc. London Math. Soc. 14, 327); for equal
    spheres with cosh(alpha) = s/2 the torques of counter- and co-rotation are
        X^C_11 - X^C_12 = sinh^3(alpha) sum_n csch^3(n alpha)          -> zeta(3) at contact,
        X^C_11 + X^C_12 = sinh^3(alpha) sum_n (-1)^(n+1) csch^3(n alpha) -> 3 zeta(3)/4,
    (JO's contact values 7 zeta(3)/8 and -zeta(3)/8; section 2b of the reference file)."""
    alpha = np.arccosh(s / 2.0)
    n = np.arange(1, 200001)
    e = np.exp(-n * alpha)
    csch3 = (2 * e / (1 - e * e)) ** 3
    sh3 = np.sinh(alpha) ** 3
    counter = sh3 * csch3.sum()
    co = sh3 * (csch3 * np.where(n % 2 == 1, 1.0, -1.0)).sum()
    return 0.5 * (counter + co), 0.5 * (co - counter)


def evaluate(name, s, K=200, mmax=None):
    """Resistance function `name` (e.g. "XG11") at s = r/a > 2, lambda = 1, JO normalisation."""
    if name in ("XC11", "XC12"):
        return twist_functions(float(s))[0 if name == "XC11" else 1]
    sign, parity, c = series_coefficients(K)[name]
    g1, g2, g3 = SINGULAR[name]
    mmax = K if mmax is None else mmax
    m = np.arange(mmax + 1)
    y = 2.0 / np.asarray(s, dtype=float)
    # tail model of sign * c_m (m >= 1, right parity)
    a = np.zeros(mmax + 1)
    sel = (m >= 1) & (m % 2 == parity)
    a[sel] = g1 + 2 * g2 / m[sel] - 4 * g3 / (m[sel] * (m[sel] + 2))
    rem = sign * c[: mmax + 1] - a
    rem[~((m % 2 == parity))] = 0.0
    S0, S1, S2 = _singular_sums(y, parity)
    yy = np.power.outer(y, m) if np.ndim(y) else y ** m
    total = yy @ rem if np.ndim(y) else float(np.dot(yy, rem))
    return total + g1 * S0 + 2 * g2 * S1 - 4 * g3 * S2


def evaluate_direct(name, s, K=200):
    """Plain partial sum of the far-field series (a check away from contact)."""
    if name in ("XC11", "XC12"):
        return evaluate(name, s)
    sign, parity, c = series_coefficients(K)[name]
    y = 2.0 / s
    return sign * float(np.dot(c, y ** np.arange(K + 1)))


def all_functions(s, K=200):
    return {name: evaluate(name, s, K) for name in NAMES}


if __name__ == "__main__":
    import sys
    K = int(sys.argv[1]) if len(sys.argv) > 1 else 80
    print(f"K = {K}")
    for name in NAMES:
        vals = [evaluate(name, s, K) for s in (2.001, 2.1, 2.5, 3.0)]
        direct = evaluate_direct(name, 3.0, K)
        print(f"{name}: " + " ".join(f"{v: .6f}" for v in vals) + f"   direct(3.0) {direct: .6f}")
