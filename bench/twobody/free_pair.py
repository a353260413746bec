"""Free-pair functions of two equal spheres from a two-sphere resistance description.

Units: sphere radius a = 1 and viscosity mu = 1/(6 pi), so 6 pi mu a = 1, 8 pi mu a^3 = 4/3 and
4 pi mu a^2 = 2/3. Sphere 1 sits at the origin, sphere 2 at r d; d = (x2 - x1)/r.

A resistance description is a pair (R, RE): R is the 12 x 12 resistance acting on
v = (U1 - U_inf(x1), W1 - Omega_inf, U2 - U_inf(x2), W2 - Omega_inf), and RE maps a rate of strain
E (3 x 3, symmetric, traceless) to the hydrodynamic forces and torques on the spheres held at
v = 0, so that the hydrodynamic wrench is  F^H = -R v + RE(E)  (Kim & Karrila 1991 ch. 7, 11).

Free-pair functions (all -> 1 or 0 far apart):
  G, H   Batchelor (1976): spheres pushed apart by F2 = -F1 = F, torque-free; the relative
         velocity is V = U2 - U1 = F.[G dd + H (I - dd)]/(3 pi mu a).
  A, B   Batchelor & Green (1972): force- and torque-free spheres in a pure strain E; relative
         velocity V = E.r - [A dd + B (I - dd)].E.r.
  C      rotation of each force- and torque-free sphere in the same strain, relative to the
         fluid: W_a - Omega_inf = C (d x E.d) (equal for both spheres by symmetry); -> 0 far apart.
  Xr, Yr counter-rotation mobility: torques L2 = -L1 = L, force-free; relative angular velocity
         W2 - W1 = L.[Xr dd + Yr (I - dd)]/(4 pi mu a^3) (isolated spheres: 1).
"""
import numpy as np

import jeffrey_onishi as jo

MU = 1.0 / (6.0 * np.pi)
SA, SB, SC = 1.0, 2.0 / 3.0, 4.0 / 3.0  # 6 pi mu a, 4 pi mu a^2, 8 pi mu a^3 with a = 1

EPS = np.zeros((3, 3, 3))
EPS[0, 1, 2] = EPS[1, 2, 0] = EPS[2, 0, 1] = 1.0
EPS[0, 2, 1] = EPS[2, 1, 0] = EPS[1, 0, 2] = -1.0


def _g_tensor(X, Y, d):
    """G_ijk = X (d_i d_j - delta_ij/3) d_k + Y (d_i delta_jk + d_j delta_ik - 2 d_i d_j d_k)."""
    I = np.eye(3)
    dd = np.outer(d, d)
    return (X * np.einsum("ij,k->ijk", dd - I / 3, d)
            + Y * (np.einsum("i,jk->ijk", d, I) + np.einsum("j,ik->ijk", d, I) - 2 * np.einsum("ij,k->ijk", dd, d)))


def _h_tensor(Y, d):
    """H_ijk = Y (eps_ikl d_l d_j + eps_jkl d_l d_i)."""
    e = np.einsum("ikl,l->ik", EPS, d)
    return Y * (np.einsum("ik,j->ijk", e, d) + np.einsum("jk,i->ijk", e, d))


def exact(s, d, K=200):
    """Exact (R, RE) of two equal spheres at centre distance s (units of a), JO functions."""
    f = {name: jo.evaluate(name, s, K) for name in jo.NAMES}
    I = np.eye(3)
    dd = np.outer(d, d)
    P = I - dd
    ed = np.einsum("ijk,k->ij", EPS, d)  # (eps . d)_ij = eps_ijk d_k
    A = {(0, 0): SA * (f["XA11"] * dd + f["YA11"] * P), (0, 1): SA * (f["XA12"] * dd + f["YA12"] * P)}
    A[(1, 1)], A[(1, 0)] = A[(0, 0)], A[(0, 1)]
    C = {(0, 0): SC * (f["XC11"] * dd + f["YC11"] * P), (0, 1): SC * (f["XC12"] * dd + f["YC12"] * P)}
    C[(1, 1)], C[(1, 0)] = C[(0, 0)], C[(0, 1)]
    # B is odd in d: in the fixed-d representation B22 = -B11, B21 = -B12.
    B = {(0, 0): SB * f["YB11"] * ed, (0, 1): SB * f["YB12"] * ed}
    B[(1, 1)], B[(1, 0)] = -B[(0, 0)], -B[(0, 1)]
    R = np.zeros((12, 12))
    for a in range(2):
        for b in range(2):
            R[6 * a:6 * a + 3, 6 * b:6 * b + 3] = A[(a, b)]
            R[6 * a:6 * a + 3, 6 * b + 3:6 * b + 6] = B[(b, a)].T
            R[6 * a + 3:6 * a + 6, 6 * b:6 * b + 3] = B[(a, b)]
            R[6 * a + 3:6 * a + 6, 6 * b + 3:6 * b + 6] = C[(a, b)]
    # G (odd in d) and H (even): G_ab, H_ab, stresslet on a from the motion of b.
    G = {(0, 0): SB * _g_tensor(f["XG11"], f["YG11"], d), (0, 1): SB * _g_tensor(f["XG12"], f["YG12"], d)}
    G[(1, 1)], G[(1, 0)] = -G[(0, 0)], -G[(0, 1)]
    H = {(0, 0): SC * _h_tensor(f["YH11"], d), (0, 1): SC * _h_tensor(f["YH12"], d)}
    H[(1, 1)], H[(1, 0)] = H[(0, 0)], H[(0, 1)]

    def RE(E):
        out = np.zeros(12)
        for a in range(2):
            for b in range(2):
                # force on a: sum_b G_ba,ijk E_ij (R_FE = R_SU^T)
                out[6 * a:6 * a + 3] += np.einsum("ijk,ij->k", G[(b, a)], E)
                out[6 * a + 3:6 * a + 6] += np.einsum("ijk,ij->k", H[(b, a)], E)
        return out

    return R, RE


def _unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def free_pair_functions(description, s):
    """G, H, A, B, C, Xr, Yr for a function description(s, d) -> (R, RE)."""
    out = {}
    # Along the line of centres d = x: G, Xr; across: H, Yr.
    d = np.array([1.0, 0.0, 0.0])
    t = np.array([0.0, 1.0, 0.0])
    R, RE = description(s, d)
    Rinv = np.linalg.inv(R)
    for name, axis in (("G", d), ("H", t)):
        F = np.zeros(12)
        F[0:3], F[6:9] = -axis, axis
        v = Rinv @ F
        out[name] = (v[6:9] - v[0:3]) @ axis / 2.0  # / (F/(3 pi mu a)), 3 pi mu a = 1/2
    for name, axis in (("Xr", d), ("Yr", t)):
        L = np.zeros(12)
        L[3:6], L[9:12] = -axis, axis
        v = Rinv @ L
        out[name] = (v[9:12] - v[3:6]) @ axis * (2.0 / 3.0)  # / (L/(4 pi mu a^3))
    # Pure strain with d an eigen-direction (A) and with E.d perpendicular to d (B, C).
    E = np.array([[0.0, 0.5, 0.0], [0.5, 0.0, 0.0], [0.0, 0.0, 0.0]])
    for name, dvec in (("A", _unit([1.0, 1.0, 0.0])), ("B", np.array([1.0, 0.0, 0.0]))):
        R, RE = description(s, dvec)
        v = np.linalg.solve(R, RE(E))  # velocities relative to the ambient flow
        Er = E @ (s * dvec)
        rel = v[6:9] - v[0:3]  # V - E.r
        out[name] = -(rel @ Er) / (Er @ Er)
        if name == "B":
            axis = np.cross(dvec, E @ dvec)
            out["C"] = v[3:6] @ axis / (axis @ axis)
            out["C_check"] = v[9:12] @ axis / (axis @ axis)
    return out


if __name__ == "__main__":
    import sys
    K = int(sys.argv[1]) if len(sys.argv) > 1 else 60
    for s in (2.001, 2.01, 2.1, 2.5, 3.0, 5.0, 10.0, 20.0):
        f = free_pair_functions(lambda s_, d_: exact(s_, d_, K), s)
        print(f"s = {s:6.3f}: " + "  ".join(f"{k} {v: .6f}" for k, v in f.items()))
