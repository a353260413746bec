#!/usr/bin/python3
"""Orientation and stress summary of a sweep's result files (issue 12's N = 1000 runs).

usage: summarize_orientation.py OUTPUT_DIR > table.csv

Per point: delta_theta_m, delta_phi_m, S_ii, the decorrelation time, eta_r, N1, N2 with their SE and
no-plateau flags (1: the blocking found no plateau, the SE is a lower bound), the averaging window,
and the 20-strain block means of delta_theta_m (sensitivity/table.py's blocks). A resumed run's time
series covers only the samples after its last resume; the sweep keeps what a signal interrupted as
LABEL.h5.interrupted, .interrupted.2, ..., so the blocks are taken over those series and the final
one joined in time (the last column says when samples are still missing).
"""
import csv, glob, math, os, re, sys
import h5py, numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "sensitivity"))
import table
Q = ["orientation/delta_theta_m", "orientation/delta_phi_m", "orientation/S_xx", "orientation/S_yy",
     "orientation/S_zz", "orientation/decorrelation_time", "stress/eta_r", "stress/N1", "stress/N2"]


def stitched_blocks(path, h5):
    """table.blocks over the interrupted parts' series and the final one, joined in time."""
    t, v = table.theta_series(h5)
    # Newest part first (.interrupted is the oldest, then .2, .3, ...): each part keeps only the
    # samples before the series joined so far. Sorting the names as text went oldest first, so
    # every part after the first was dropped (232 of 586 samples of the Pe 0.1 point).
    def age(part):
        m = re.search(r"\.interrupted(?:\.(\d+))?$", part)
        return int(m.group(1) or 1) if m else 0
    for part in sorted(glob.glob(path + ".interrupted*"), key=age, reverse=True):
        with h5py.File(part, "r") as f:
            tp, vp = table.theta_series(f)
        keep = tp < (t[0] if len(t) else math.inf) - 1e-6
        t, v = np.concatenate([tp[keep], t]), np.concatenate([vp[keep], v])
    order = np.argsort(t, kind="stable")
    return table.block_summary(h5, t[order], v[order], lambda t, n, samples:
                               f"samples missing: series over {t[0]:g}–{t[-1]:g}, {n} of {samples}")


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
        w, spread, blocks = stitched_blocks(p, h5)
        r["window"] = w; r["blocks_20_strain"] = spread; r["block_means"] = blocks
        rows.append(r)
keys = ["point", "window"] + [k for q in Q for k in (q, q + "_se", q + "_no_plateau")] + ["blocks_20_strain", "block_means"]
# csv quotes the fields that hold commas (the "samples missing" note of block_means).
out = csv.writer(sys.stdout, lineterminator="\n")
out.writerow(keys)
for r in rows:
    out.writerow(str(r.get(k, "")) if not isinstance(r.get(k), float) else f"{r[k]:.5g}" for k in keys)
