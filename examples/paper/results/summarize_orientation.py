#!/usr/bin/python3
"""Orientation and stress summary of a sweep's result files (issue 12's N = 1000 runs).

usage: summarize_orientation.py OUTPUT_DIR > table.csv

Per point: delta_theta_m, delta_phi_m, S_ii, the decorrelation time, eta_r, N1, N2 with their SE and
no-plateau flags (1: the blocking found no plateau, the SE is a lower bound), the averaging window,
and the 20-strain block means of delta_theta_m (sensitivity/table.py's blocks: a resumed run's time
series covers only the samples after its last resume, which the last column says).
"""
import glob, math, os, re, sys
import h5py, numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "sensitivity"))
import table
Q = ["orientation/delta_theta_m", "orientation/delta_phi_m", "orientation/S_xx", "orientation/S_yy",
     "orientation/S_zz", "orientation/decorrelation_time", "stress/eta_r", "stress/N1", "stress/N2"]
rows = []
for p in sorted(glob.glob(sys.argv[1] + "/*.h5")):
    if os.path.basename(p) == "study.h5":  # the sweep's table, not a point
        continue
    with h5py.File(p, "r") as h5:
        r = {"point": os.path.basename(p)[:-3]}
        for q in Q:
            d = h5.get("results/" + q)
            if d is None: continue
            r[q] = float(d[()]); r[q + "_se"] = float(d.attrs.get("stderr", math.nan))
            r[q + "_no_plateau"] = int("no plateau" in table.text(d.attrs.get("description", "")))
        w, spread, blocks = table.blocks(h5)
        r["window"] = w; r["blocks_20_strain"] = spread; r["block_means"] = blocks
        rows.append(r)
keys = ["point", "window"] + [k for q in Q for k in (q, q + "_se", q + "_no_plateau")] + ["blocks_20_strain", "block_means"]
print(",".join(keys))
for r in rows:
    print(",".join(str(r.get(k, "")) if not isinstance(r.get(k), float) else f"{r[k]:.5g}" for k in keys))
