#!/usr/bin/python3
"""Hard-sphere start for the LAMMPS parity reference: N = 4 n^3 unit spheres (a = 1) in a cubic box
of edge L = (N (4/3) pi / phi)^(1/3), melted from an fcc lattice by Metropolis Monte Carlo
(hard-sphere overlap rejection, periodic minimum image, step size tuned to ~40 % acceptance).
Writes a LAMMPS data file (atom_style sphere: id type diameter density x y z, triclinic box
[0, L)^3 with zero tilt so that fix deform xy can act on it).

Guards that make the comparison well posed: no overlap (r >= 2), and no pair within 1e-6 a of the
lubrication cutoff 2.5 a or the inner cutoff 2.01 a, where the two codes' last-bit differences in r
could put a pair on different sides.

Usage: make_start.py PHI SEED OUT.data [--cells 3] [--sweeps 3000]"""
import argparse
import math

import numpy as np

CUTOFF, CUT_INNER = 2.5, 2.01


def fcc(cells, L):
    base = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    cell = L / cells
    pts = [(np.array([i, j, k]) + b) * cell for i in range(cells) for j in range(cells) for k in range(cells)
           for b in base]
    return np.array(pts) + 0.25 * cell


def min_image(r, L):
    return r - L * np.round(r / L)


def pair_distances(x, L):
    d = min_image(x[:, None, :] - x[None, :, :], L)
    r = np.sqrt((d * d).sum(-1))
    iu = np.triu_indices(len(x), 1)
    return r[iu]


def melt(x, L, sweeps, rng):
    n = len(x)
    step = 0.1
    for sweep in range(sweeps):
        accepted = 0
        for i in rng.permutation(n):
            trial = (x[i] + rng.uniform(-step, step, 3)) % L
            d = min_image(x - trial, L)
            r2 = (d * d).sum(-1)
            r2[i] = np.inf
            if r2.min() >= 4.0:
                x[i] = trial
                accepted += 1
        rate = accepted / n
        if sweep < sweeps // 2:  # tune only in the first half
            step *= 1.05 if rate > 0.4 else 0.95
    return x


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("phi", type=float)
    ap.add_argument("seed", type=int)
    ap.add_argument("out")
    ap.add_argument("--cells", type=int, default=3)
    ap.add_argument("--sweeps", type=int, default=3000)
    args = ap.parse_args()
    n = 4 * args.cells ** 3
    L = (n * 4.0 / 3.0 * math.pi / args.phi) ** (1.0 / 3.0)
    rng = np.random.default_rng(args.seed)
    x = melt(fcc(args.cells, L), L, args.sweeps, rng)
    for _ in range(100):  # nudge a sphere that sits on a cutoff (rare)
        r = pair_distances(x, L)
        bad = (np.abs(r - CUTOFF) < 1e-6) | (np.abs(r - CUT_INNER) < 1e-6)
        if not bad.any():
            break
        x = melt(x, L, 1, rng)
    r = pair_distances(x, L)
    assert r.min() >= 2.0 and not ((np.abs(r - CUTOFF) < 1e-6) | (np.abs(r - CUT_INNER) < 1e-6)).any()
    with open(args.out, "w") as out:
        out.write(f"hard spheres for the lubricateU parity reference: N = {n}, phi = {args.phi}, seed {args.seed}, "
                  f"{args.sweeps} MC sweeps from fcc; min r = {r.min():.6f}, pairs r < 2.01: "
                  f"{int((r < CUT_INNER).sum())}, pairs r < 2.5: {int((r < CUTOFF).sum())}\n\n")
        out.write(f"{n} atoms\n1 atom types\n\n")
        for axis in ("x", "y", "z"):
            out.write(f"0.0 {L:.17g} {axis}lo {axis}hi\n")
        out.write("0.0 0.0 0.0 xy xz yz\n\nAtoms # sphere\n\n")
        for i, p in enumerate(x, start=1):
            out.write(f"{i} 1 2.0 1.0 {p[0]:.17g} {p[1]:.17g} {p[2]:.17g}\n")
    print(f"{args.out}: N = {n}, L = {L:.6f}, min r = {r.min():.6f}, pairs r < 2.01: {(r < CUT_INNER).sum()}, "
          f"r < 2.5: {(r < CUTOFF).sum()}")


if __name__ == "__main__":
    main()
