#!/usr/bin/python3
"""Turn the last frame of a parity.lmp dump into fldsim's test reference
(tests/data/lammps_lubricateU_phi*.txt) and check LAMMPS's answer against a direct solve of the
same linear system (lubricate_u.py): the difference is LAMMPS's conjugate-gradient error, which
sets the parity test's tolerance.

Usage: write_reference.py DUMP OUT.txt "how it was made" [FLAGLOG (1, default, or 0)]"""
import subprocess
import sys

import numpy as np

import lubricate_u


def read_frames(path):
    """The frames of a dump: (box bounds, column names, rows) each."""
    lines = open(path).read().split("\n")
    frames = []
    for start in [k for k, line in enumerate(lines) if line.startswith("ITEM: TIMESTEP")]:
        n = int(lines[start + 3])
        bounds = [[float(t) for t in lines[start + 5 + k].split()] for k in range(3)]
        columns = lines[start + 8].split()[2:]
        rows = np.array([[float(t) for t in line.split()] for line in lines[start + 9:start + 9 + n]])
        frames.append((bounds, columns, rows))
    return frames


def read_solution(path):
    """Box edge, positions and LAMMPS's velocities: the set-up frame (step 0) has the untilted box
    the pair style saw; fix deform tilts it by gammadot dt L = 1e-9 only at the end of step 1, whose
    frame holds the velocities. The spheres do not move in between (checked)."""
    (bounds, columns, first), (_, _, last) = read_frames(path)[0], read_frames(path)[-1]
    if any(b[0] != 0.0 or b[2] != 0.0 for b in bounds) or len({b[1] for b in bounds}) != 1:
        sys.exit(f"{path}: expected a cubic box [0, L)^3 with zero tilt at step 0")
    if columns != ["id", "x", "y", "z", "vx", "vy", "vz", "omegax", "omegay", "omegaz"]:
        sys.exit(f"{path}: unexpected dump columns {columns}")
    if not np.array_equal(first[:, 0:4], last[:, 0:4]):
        sys.exit(f"{path}: the spheres moved during the step")
    return bounds[0][1], last


def relative(data, gdot=1.0):
    rel = data[:, 4:10].copy()
    rel[:, 0] -= gdot * data[:, 2]
    rel[:, 5] += 0.5 * gdot
    return rel


def main():
    dump, out, how = sys.argv[1], sys.argv[2], sys.argv[3]
    flaglog = int(sys.argv[4]) if len(sys.argv) > 4 else 1
    L, data = read_solution(dump)
    x = data[:, 1:4]
    lam = relative(data)
    sol, R, b, phi, pairs = lubricate_u.solve(x, L, flaglog=flaglog)
    stats = []
    for name, sl in (("U", slice(0, 3)), ("W", slice(3, 6))):
        rms = np.sqrt((sol[:, sl] ** 2).sum(1).mean())
        err = np.sqrt(((lam[:, sl] - sol[:, sl]) ** 2).sum(1))
        if rms < 1e-12:  # flaglog 0: no pair torques, every sphere turns with the flow
            stats.append(f"{name}: zero in the direct solve, max |LAMMPS| {np.abs(lam[:, sl]).max():.1e}")
            continue
        stats.append(f"{name}: rms {rms:.6g}, max |LAMMPS - direct|/rms {err.max() / rms:.2e}, "
                     f"rms {np.sqrt((err ** 2).mean()) / rms:.2e}")
    residual = np.linalg.norm(R @ lam.reshape(-1) - b) / np.linalg.norm(b)
    version = subprocess.run(["lmp", "-h"], capture_output=True, text=True).stdout
    version = next((line.split(" - ", 1)[1] for line in version.splitlines() if "Simulator - " in line), "?")
    package = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "lammps"], capture_output=True, text=True).stdout
    with open(out, "w") as f:
        f.write("# LAMMPS pair lubricateU velocities of spheres at fixed positions: reference of fldsim's\n"
                f"# tests/hydro/LammpsParityTest.cpp (conventions: lammps, delta_num: 0.01{'' if flaglog else ', log_terms: false'}).\n")
        f.write(f"# Made by bench/lammps/parity/run.sh: {how}\n")
        f.write(f"# LAMMPS {version} (Debian package lammps {package or '?'}), one MPI task.\n")
        f.write(f"# pair_style lubricateU mu = 1/(6 pi), flaglog {flaglog}, cutinner 2.01, cutoff 2.5, gdot 1, flagHI 1, flagVF 1;\n"
                "# a = 1 (diameter 2), no Brownian or other forces; fix deform xy erate 1 remap v; timestep 1e-10.\n")
        f.write("# Columns are LAMMPS's lab velocities: relative ones are U - gdot y e_x and W + gdot/2 e_z.\n")
        f.write(f"# phi = N (4/3) pi a^3 / L^3 = {phi:.12f}; {pairs} pairs with r < 2.5 a.\n")
        f.write(f"# LAMMPS's CG stops at |r|/|b| < 1e-4 from zero; a direct solve of the same system\n"
                f"# (bench/lammps/parity/lubricate_u.py) gives residual {residual:.2e} for these velocities and\n"
                f"# {stats[0]}; {stats[1]}.\n")
        f.write(f"N {len(x)}\nL {L:.17g}\n")
        f.write("id x y z vx vy vz wx wy wz\n")
        for row in data:
            f.write(f"{int(row[0])} " + " ".join(f"{v:.17g}" for v in row[1:]) + "\n")
    print(f"{out}: N = {len(x)}, phi = {phi:.6f}, pairs {pairs}, residual {residual:.2e}; {stats[0]}; {stats[1]}")


if __name__ == "__main__":
    main()
