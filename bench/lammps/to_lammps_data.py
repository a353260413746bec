#!/usr/bin/python3
"""Write the last trajectory frame of an fldsim result file as a LAMMPS data file (atom_style
sphere: id type diameter density x y z) in a triclinic box [0, L)^3 with zero tilt, so that
fix deform xy can shear it. Usage: to_lammps_data.py START.h5 OUT.data"""
import sys

import h5py


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: to_lammps_data.py START.h5 OUT.data")
    src, dst = sys.argv[1], sys.argv[2]
    with h5py.File(src, "r") as f:
        pos = f["/particles/bodies/position/value"][-1]
        edge = float(f["/particles/bodies/box/edges/value"][-1].flat[0])  # 3x3 cell or 3 lengths
        strain = float(f["/particles/bodies/lees_edwards/strain/value"][-1])
        radius = float(f["/particles/nodes/radius"][0]) if "/particles/nodes/radius" in f else 1.0
    if strain % 1.0 != 0.0:
        sys.exit(f"{src}: the start frame has Lees-Edwards strain {strain}; expected 0 (a fresh start)")
    with open(dst, "w") as out:
        out.write(f"fldsim start frame from {src}: {len(pos)} spheres of radius {radius}\n\n")
        out.write(f"{len(pos)} atoms\n1 atom types\n\n")
        for axis in ("x", "y", "z"):
            out.write(f"0.0 {edge:.17g} {axis}lo {axis}hi\n")
        out.write("0.0 0.0 0.0 xy xz yz\n\nAtoms # sphere\n\n")
        for i, (x, y, z) in enumerate(pos, start=1):
            out.write(f"{i} 1 {2.0 * radius:.17g} 1.0 {x:.17g} {y:.17g} {z:.17g}\n")


if __name__ == "__main__":
    main()
