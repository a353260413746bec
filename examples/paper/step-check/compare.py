#!/usr/bin/python3
"""Step-size check of a `fldsim sweep` whose axis is run.dt and whose points have `repeats`
(independent replicas): for each dt, the mean and SE over the replicas of each steady-state
result, and its difference from the smallest dt in units of the combined SE (z).

usage: compare.py RESULT_DIR [QUANTITY ...]
  RESULT_DIR  the sweep's output_dir (files dt-<dt>_..._rep<k>.h5)
  QUANTITY    a scalar under /results (e.g. stress/eta_r), or g@R for the g(r) bin centred
              nearest R (a); default: eta_r, Z_particle, N1, N2, S_ii, delta_theta_m,
              delta_phi_m, g@2.04, g@2.12
"""
import glob, re, sys, math, collections
import h5py, numpy as np

out = sys.argv[1]
names = sys.argv[2:] or ["stress/eta_r", "stress/Z_particle", "stress/N1", "stress/N2",
                         "orientation/S_xx", "orientation/S_yy", "orientation/S_zz",
                         "orientation/delta_theta_m", "orientation/delta_phi_m", "g@2.04", "g@2.12"]
groups = collections.defaultdict(list)
for f in sorted(glob.glob(out + "/dt-*.h5")):
    dt = float(re.search(r"dt-([0-9.e+-]+?)_", f).group(1))
    with h5py.File(f, "r") as h:
        row = {}
        for n in names:
            p = "results/" + n
            if n.startswith("g@"):  # the g(r) bin whose centre is at that r
                r = h["results/pair_distribution/r"][:]
                k = int(np.argmin(abs(r - float(n[2:]))))
                row[n] = float(h["results/pair_distribution/g_r"][k])
            elif p in h:
                row[n] = float(h[p][()])
        groups[dt].append(row)
dts = sorted(groups)
print("step  replicas  " + "  ".join(names))
ref = {}
for dt in dts:
    cells = []
    for n in names:
        v = np.array([r[n] for r in groups[dt] if n in r])
        if len(v) < 2:
            cells.append("n/a"); continue
        m, se = v.mean(), v.std(ddof=1) / math.sqrt(len(v))
        if dt == dts[0]: ref[n] = (m, se)
        z = (m - ref[n][0]) / math.hypot(se, ref[n][1]) if dt != dts[0] else 0.0
        cells.append(f"{m:.4g} ± {se:.2g} (z {z:+.1f})")
    print(f"{dt:g}  {len(groups[dt])}  " + "  |  ".join(cells))
