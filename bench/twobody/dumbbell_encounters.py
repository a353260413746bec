#!/usr/bin/python3
"""Two free fused dumbbells (c = a) passing each other in simple shear, kT = 0, no repulsion, RK3:
the smallest node-node gap of each encounter, for both strain arms and two time steps
(docs/two-body.md, "Touching nodes of free bodies stop approaching"). A model whose touching
nodes kept approaching at a finite speed would reach contact (gap <= 0) here.

usage: dumbbell_encounters.py [FLDSIM] [WORKDIR]   (defaults: build/bin/fldsim, /tmp/dumbbell_encounters)
"""
import os
import subprocess
import sys

import h5py
import numpy as np

FLDSIM = sys.argv[1] if len(sys.argv) > 1 else "build/bin/fldsim"
WORK = sys.argv[2] if len(sys.argv) > 2 else "/tmp/dumbbell_encounters"


def smallest_gap(name, p1, d0, d1, dt, arm):
    """(smallest gap, its time) over 14 strains; body 0 at the box centre, body 1 at p1 upstream."""
    text = f"""system:
  shape: {{plugin: dicolloid, a: 1.0, b: 1.0, c: 1}}
  count: 2
  box_edge: 30
  volume_fraction: 0.01
  init: {{method: explicit, positions: [[15, 15, 15], [{p1[0]}, {p1[1]}, {p1[2]}]], orientations: [[{d0[0]}, {d0[1]}, {d0[2]}], [{d1[0]}, {d1[1]}, {d1[2]}]]}}
flow: {{peclet: 1, brownian: false}}
hydro: {{plugin: fld, strain_arm: {arm}}}
run: {{dt: {dt}, duration: 14, time_unit: strain, seed: 1, threads: 1}}
observers:
  - {{plugin: trajectory, every: 1, nodes: true}}
output: {name}.h5
"""
    path = os.path.join(WORK, name)
    with open(path + ".yaml", "w") as f:
        f.write(text)
    subprocess.run([FLDSIM, "run", path + ".yaml", "--overwrite", "-q"], check=True)
    with h5py.File(path + ".h5", "r") as f:
        nodes = np.asarray(f["particles/nodes/position/value"])
        t = np.asarray(f["particles/nodes/position/time"])
    gaps = np.array([min(np.linalg.norm(x[2 + b] - x[a]) for a in range(2) for b in range(2)) - 2.0 for x in nodes])
    k = int(np.argmin(gaps))
    return gaps[k], t[k]


def main():
    os.makedirs(WORK, exist_ok=True)
    rng = np.random.default_rng(4)
    print("encounter | dy, dz | " + " | ".join(f"{arm} arm dt {dt}" for arm in ("contact", "centre") for dt in (0.01, 0.002)))
    for k in range(8):
        d0, d1 = rng.normal(size=3), rng.normal(size=3)
        d0, d1 = d0 / np.linalg.norm(d0), d1 / np.linalg.norm(d1)
        dy, dz = rng.uniform(0.2, 2.0), rng.uniform(-1, 1)
        p1 = (9.0, 15 + dy, 15 + dz)
        cells = []
        for arm in ("contact", "centre"):
            for dt in (0.01, 0.002):
                gap, when = smallest_gap(f"e{k}", p1, d0, d1, dt, arm)
                cells.append(f"{gap:.3e} a at strain {when:.2f}")
        print(f"{k} | {dy:.2f}, {dz:.2f} | " + " | ".join(cells), flush=True)


if __name__ == "__main__":
    main()
