#!/usr/bin/python3
"""Weighing the shear-mode lever arm (centre: l = r/2, contact: l = a) with numbers.

1. A sphere pair rotating rigidly (Omega perpendicular to d, about the midpoint) in a quiescent
   fluid. Exact: the pair interaction is not zero, it is the exact wrench minus the isolated-sphere
   drag. Model: the lubrication pair gives zero with l = r/2 (it annihilates rigid motions) and
   c_sh (r - 2a) Omega x d-type forces with l = a.
2. Two dicolloids (nodes of radius a at +-c/2 on the body axis) touching node to node, rotating
   rigidly as one doublet about the vorticity-like axis through its centre: the contact lever's
   spurious torque on the doublet against its isolated (node-sum) rotational drag, for c/a = 0.2
   and 1, end-to-end and side-by-side.
Units a = 1, 6 pi mu a = 1 (free_pair.py)."""
import numpy as np

import fld_pair
import free_pair

CONV = {"strain_arm": "contact", "pump": "jeffrey_onishi", "twist": True}


def cross_matrix(x):
    return np.array([[0, -x[2], x[1]], [x[2], 0, -x[0]], [-x[1], x[0], 0]])


def rigid_sphere_pair(s, K=200):
    d = np.array([1.0, 0.0, 0.0])
    Om = np.array([0.0, 0.0, 1.0])
    x1, x2 = -0.5 * s * d, 0.5 * s * d
    v = np.concatenate([np.cross(Om, x1), Om, np.cross(Om, x2), Om])
    R_ex, _ = free_pair.exact(s, d, K)
    iso = np.diag([free_pair.SA] * 3 + [free_pair.SC] * 3 + [free_pair.SA] * 3 + [free_pair.SC] * 3)
    out = {}
    pair_exact = -(R_ex - iso) @ v
    out["exact"] = pair_exact
    for lever in ("centre", "contact"):
        R_m, _ = fld_pair.model(dict(CONV, lever=lever))(s, d)
        out[lever] = -(R_m - iso) @ v
    # torque about the midpoint of the whole pair, isolated drag and the pair parts
    def torque(w):
        return (np.cross(x1, w[0:3]) + w[3:6] + np.cross(x2, w[6:9]) + w[9:12])[2]
    iso_torque = torque(-iso @ v)
    return {k: (w[7], w[11], torque(w)) for k, w in out.items()}, iso_torque


def doublet(c, xi, side_by_side, lever):
    """Spurious torque of the contact / centre lever on a rigidly rotating doublet of two
    dicolloids, against the doublet's isolated node-sum drag. Bodies along x."""
    a = 1.0
    axis = np.array([1.0, 0.0, 0.0])
    if side_by_side:
        centres = [np.zeros(3), np.array([0.0, 2 * a + xi, 0.0])]
    else:
        centres = [np.zeros(3), np.array([c + 2 * a + xi, 0.0, 0.0])]
    mid = 0.5 * (centres[0] + centres[1])
    nodes = [[x + sgn * 0.5 * c * axis for sgn in (-1, 1)] for x in centres]
    Om = np.array([0.0, 0.0, 1.0])
    conv = dict(CONV, lever=lever)
    torque = 0.0
    iso = 0.0
    for b in range(2):
        for n in nodes[b]:
            u = np.cross(Om, n - mid)
            iso += (np.cross(n - mid, -free_pair.SA * u) - free_pair.SC * Om)[2]
    for na in nodes[0]:
        for nb in nodes[1]:
            rv = nb - na
            r = np.linalg.norm(rv)
            if r >= 2.5:
                continue
            S = fld_pair.rows(r, rv / r, conv)
            v = np.concatenate([np.cross(Om, na - mid), Om, np.cross(Om, nb - mid), Om])
            w = -S.T @ (S @ v)
            torque += (np.cross(na - mid, w[0:3]) + w[3:6] + np.cross(nb - mid, w[6:9]) + w[9:12])[2]
    return torque, iso


def main():
    print("1. Sphere pair in rigid rotation (Omega = e_z, d = e_x, quiescent fluid): pair part of the\n"
          "   wrench (total minus isolated drag) on sphere 2: force F_y in 6 pi mu a Omega a, torque T_z in\n"
          "   6 pi mu a^3 Omega; 'total': the pair part of the pair's torque about its midpoint, against the\n"
          "   isolated drag's (last column).")
    print("| r/a | exact F_y | exact T_z | exact total | centre lever | contact F_y | contact T_z | contact total | isolated total |")
    print("|---|---|---|---|---|---|---|---|---|")
    for s in (2.001, 2.01, 2.05, 2.1, 2.2, 2.3, 2.4, 2.49):
        res, iso = rigid_sphere_pair(s)
        e, k = res["exact"], res["contact"]
        assert max(abs(x) for x in res["centre"]) < 1e-12
        print(f"| {s:.3f} | {e[0]:+.4f} | {e[1]:+.4f} | {e[2]:+.4f} | 0 | {k[0]:+.4f} | {k[1]:+.4f} | {k[2]:+.4f} | {iso:+.4f} |")
    print("\n2. Rigidly rotating doublet of two dicolloids touching node to node (Omega = e_z, bodies along x):\n"
          "   lubrication torque about the doublet centre with each lever, as a fraction of the doublet's\n"
          "   isolated node-sum rotational drag.")
    print("| c/a | arrangement | gap xi | centre lever | contact lever |")
    print("|---|---|---|---|---|")
    for c in (0.2, 1.0):
        for side in (False, True):
            for xi in (0.01, 0.1, 0.3, 0.49):
                t_c, iso = doublet(c, xi, side, "centre")
                t_k, _ = doublet(c, xi, side, "contact")
                centre = "0" if abs(t_c / iso) < 1e-12 else f"{t_c / iso:+.2e}"
                print(f"| {c} | {'side by side' if side else 'end to end'} | {xi} | {centre} | {t_k / iso:+.2e} |")


if __name__ == "__main__":
    main()
