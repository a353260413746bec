#!/usr/bin/python3
"""Write tests/data/two_sphere_exact.csv: the exact resistance functions of two equal spheres
(jeffrey_onishi.py) and the free-pair functions built from them (free_pair.py) on a grid of
centre distances s = r/a from 2.001 to 3.

The truncation error is estimated by repeating the evaluation with 3/4 of the series terms and is
written into the header (largest change of any column). The recurrences take minutes for
K = 200 terms; set FLDSIM_TWOBODY_CACHE=DIR to keep the coefficients between runs.

Usage: make_reference.py [--terms 200] [--out tests/data/two_sphere_exact.csv]"""
import argparse
import os

import numpy as np

import free_pair
import jeffrey_onishi as jo

GRID = [2.001, 2.002, 2.005, 2.01, 2.02, 2.03, 2.05, 2.075, 2.1, 2.15, 2.2, 2.25, 2.3, 2.35, 2.4, 2.45, 2.49,
        2.5, 2.55, 2.6, 2.7, 2.8, 2.9, 3.0]
FREE = ["G", "H", "A", "B", "C", "Xr", "Yr"]


def table(K):
    rows = []
    for s in GRID:
        funcs = {name: jo.evaluate(name, s, K) for name in jo.NAMES}
        free = free_pair.free_pair_functions(lambda s_, d_: free_pair.exact(s_, d_, K), s)
        rows.append([s] + [funcs[n] for n in jo.NAMES] + [free[n] for n in FREE])
    return np.array(rows)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--terms", type=int, default=200)
    ap.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "../../tests/data/two_sphere_exact.csv"))
    args = ap.parse_args()
    K = args.terms
    K2 = 3 * K // 4
    full, short = table(K), table(K2)
    change = np.abs(full - short)[:, 1:].max(axis=0)
    rel = (np.abs(full - short) / np.maximum(np.abs(full), 1e-300))[:, 1:].max(axis=0)
    cols = jo.NAMES + FREE
    worst = sorted(zip(rel, cols), reverse=True)[:3]
    with open(args.out, "w") as out:
        out.write("# Exact two-sphere hydrodynamics, equal spheres (lambda = 1), s = r/a. Made by\n"
                  f"# bench/twobody/make_reference.py --terms {K} (fldsim's own implementation).\n"
                  "# XA11 ... YH12: resistance functions in Jeffrey & Onishi's normalisation and signs (A by\n"
                  "# 6 pi mu a, B and G by 4 pi mu a^2, C and H by 8 pi mu a^3), from the twin-multipole recurrences\n"
                  "# of Jeffrey & Onishi (1984) and Jeffrey (1992) as corrected by Townsend (2018), summed with the\n"
                  "# near-contact singular part in closed form; X^C from the bispherical solution (Jeffery 1915).\n"
                  "# G, H: Batchelor (1976) relative mobility along / across the line of centres; A, B: Batchelor &\n"
                  "# Green (1972) relative velocity of a force- and torque-free pair in a pure strain; C: rotation of\n"
                  "# each sphere of that pair, W - Omega_inf = C d x (E.d); Xr, Yr: relative rotation under\n"
                  "# torques L2 = -L1 along / across d, in units of L/(4 pi mu a^3) (definitions: free_pair.py).\n"
                  f"# Truncation: changing the number of series terms from {K2} to {K} changes no entry by more than\n"
                  f"# {rel.max():.1e} (relative; largest: " + ", ".join(f"{c} {r:.1e}" for r, c in worst) + ").\n"
                  "# Validation: bench/twobody/validate.py (section 2b/2c of physics-reference-values.md).\n")
        out.write(",".join(["s"] + cols) + "\n")
        for row in full:
            out.write(",".join([f"{row[0]:.3f}"] + [f"{v:.10g}" for v in row[1:]]) + "\n")
    print(f"wrote {args.out}: {len(GRID)} distances, K = {K}, max relative change K {K2} -> {K}: {rel.max():.1e}")
    for c, r, a in zip(cols, rel, change):
        print(f"  {c}: {r:.1e} (abs {a:.1e})")


if __name__ == "__main__":
    main()
