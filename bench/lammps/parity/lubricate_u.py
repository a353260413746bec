"""The linear system that LAMMPS pair lubricateU (FLD package, flaglog = 1 or 0, flagVF = 1, monodisperse
spheres of radius a) solves each stage, as read from its documentation and source, written out
here with numpy so that its CG answer can be checked against a direct solve.

Unknowns: v_i = U_i - U_inf(x_i), w_i = W_i - Omega_inf. For every pair i < j with r < cutoff
(d = (x_j - x_i)/r, minimum image), with h = max(r - 2a, cut_inner - 2a)/a:
  a_sq = 6 pi mu a (1/(4h) + 9/40 ln(1/h)),  a_sh = 6 pi mu a (1/6) ln(1/h),
  a_pu = 8 pi mu a^3 (3/160) ln(1/h);
  contact-point relative velocity  g = v_i - v_j + a (w_i + w_j) x d   (lever a for both spheres),
  force on i  f = -(a_sq dd + a_sh (I - dd)) g,  on j  -f;  torques  a d x f  on both;
  pump torque -a_pu (I - dd)(w_i - w_j) on i and the opposite on j.
The ambient strain enters as the fluid's relative velocity across the gap, -2a E.d at i's contact
point relative to j's (contact distance 2a), i.e. the right-hand side is the wrench of the modes
for g = 2a E.d. Isolated part: R_0 = 6 pi mu a f_t(phi), R_T0 = 8 pi mu a^3 f_r(phi) with
phi = N (4/3) pi a^3 / V (Kumar & Higdon's fits, reference section 1a). Lab velocities are
v + gammadot y e_x and w - gammadot/2 e_z.
With flaglog = 0 the pair has the squeeze's 1/(4h) alone (a_sh = a_pu = 0, no pair torques) and
R_0 = 6 pi mu a (1 + 2.16 phi), R_T0 = 8 pi mu a^3 (pair_lubricateU.cpp, init_style)."""
import math

import numpy as np


def solve(x, L, gdot=1.0, mu=1.0 / (6.0 * math.pi), a=1.0, cut_inner=2.01, cutoff=2.5, flaglog=1):
    n = len(x)
    phi = n * 4.0 / 3.0 * math.pi * a ** 3 / L ** 3
    if flaglog:
        R0 = 6 * math.pi * mu * a * (1 + 2.725 * phi - 6.583 * phi * phi)
        RT0 = 8 * math.pi * mu * a ** 3 * (1 + 0.749 * phi - 2.469 * phi * phi)
    else:
        R0 = 6 * math.pi * mu * a * (1 + 2.16 * phi)
        RT0 = 8 * math.pi * mu * a ** 3
    E = np.array([[0, 0.5 * gdot, 0], [0.5 * gdot, 0, 0], [0, 0, 0]])
    R = np.zeros((6 * n, 6 * n))
    b = np.zeros(6 * n)
    for i in range(n):
        R[6 * i:6 * i + 3, 6 * i:6 * i + 3] += R0 * np.eye(3)
        R[6 * i + 3:6 * i + 6, 6 * i + 3:6 * i + 6] += RT0 * np.eye(3)
    pairs = 0
    for i in range(n):
        for j in range(i + 1, n):
            rv = x[j] - x[i]
            rv -= L * np.round(rv / L)
            r = np.linalg.norm(rv)
            if r >= cutoff:
                continue
            pairs += 1
            d = rv / r
            h = max(r, cut_inner) - 2 * a
            h /= a
            L1 = math.log(1 / h) if flaglog else 0.0
            a_sq = 6 * math.pi * mu * a * (1 / (4 * h) + 9 / 40 * L1)
            a_sh = 6 * math.pi * mu * a * L1 / 6
            a_pu = 8 * math.pi * mu * a ** 3 * 3 / 160 * L1
            dd = np.outer(d, d)
            P = np.eye(3) - dd
            K = a_sq * dd + a_sh * P
            D = np.array([[0, -d[2], d[1]], [d[2], 0, -d[0]], [-d[1], d[0], 0]])  # D w = d x w
            # g = G v with G = [I, -a D, -I, -a D] on (v_i, w_i, v_j, w_j): (w x d) = -D w.
            G = np.zeros((3, 12))
            G[:, 0:3], G[:, 3:6], G[:, 6:9], G[:, 9:12] = np.eye(3), -a * D, -np.eye(3), -a * D
            Rp = G.T @ K @ G
            Pu = np.zeros((3, 12))
            Pu[:, 3:6], Pu[:, 9:12] = P, -P
            Rp += a_pu * Pu.T @ P @ Pu
            idx = np.r_[6 * i:6 * i + 6, 6 * j:6 * j + 6]
            R[np.ix_(idx, idx)] += Rp
            b[idx] += G.T @ K @ (2 * a * (E @ d))
    v = np.linalg.solve(R, b)
    return v.reshape(n, 6), R, b, phi, pairs
