#!/usr/bin/python3
"""Step-size check: the mean and SE over independent replicas of each steady-state result, and
each group's difference from the first group in units of the combined SE (z).

usage: compare.py RESULT_DIR [QUANTITY ...]
       compare.py LABEL=GLOB [LABEL=GLOB ...] [-- QUANTITY ...]
  RESULT_DIR  a `fldsim sweep` output_dir whose axis is run.dt and whose points have `repeats`
              (files dt-<dt>_..._rep<k>.h5): one group per dt, the smallest first
  LABEL=GLOB  one group per argument, its replicas the result files GLOB matches (e.g. the
              fixed-step and the `dt: auto` sweeps of a scene: fixed=out-fixed/*.h5
              auto=out-auto/tolerance-3.0e-2_rep*.h5); the first group is the reference (a sweep's
              study.h5 table is skipped)
  QUANTITY    a scalar under /results (e.g. stress/eta_r), or g@R for the g(r) bin centred
              nearest R (a); default: eta_r, Z_particle, N1, N2, S_ii, delta_theta_m,
              delta_phi_m, g@2.04, g@2.12
Each group also gets its replicas' mean steps and mean step (the logs' `steps:` line) and the
time loop's seconds per replica (`done:` line; wall time, so compare groups run alike).
"""
import glob, re, sys, math, os
import h5py, numpy as np

DEFAULT = ["stress/eta_r", "stress/Z_particle", "stress/N1", "stress/N2",
           "orientation/S_xx", "orientation/S_yy", "orientation/S_zz",
           "orientation/delta_theta_m", "orientation/delta_phi_m", "g@2.04", "g@2.12"]


def read_row(path, names):
    with h5py.File(path, "r") as h:
        row = {}
        for n in names:
            p = "results/" + n
            if n.startswith("g@"):  # the g(r) bin whose centre is at that r
                r = h["results/pair_distribution/r"][:]
                k = int(np.argmin(abs(r - float(n[2:]))))
                row[n] = float(h["results/pair_distribution/g_r"][k])
            elif p in h:
                row[n] = float(h[p][()])
    log = path[:-3] + ".log"
    if os.path.exists(log):
        text = open(log).read()
        m = re.search(r"^done: \d+ steps in ([0-9.]+) s", text, re.M)
        if m: row["loop_s"] = float(m.group(1))
        m = re.search(r"^steps: (\d+) steps, dt mean ([0-9.e+-]+)", text, re.M)
        if m: row["steps"], row["dt_mean"] = int(m.group(1)), float(m.group(2))
    return row


def groups_of(args, names):
    if len(args) == 1 and "=" not in args[0]:
        by_dt = {}
        for f in sorted(glob.glob(args[0] + "/dt-*.h5")):
            dt = float(re.search(r"dt-([0-9.e+-]+?)_", f).group(1))
            by_dt.setdefault(dt, []).append(read_row(f, names))
        return [(f"{dt:g}", by_dt[dt]) for dt in sorted(by_dt)]
    out = []
    for a in args:
        label, pattern = a.split("=", 1)
        files = [f for f in sorted(glob.glob(pattern)) if f.endswith(".h5") and os.path.basename(f) != "study.h5"]
        if not files:
            sys.exit(f"compare.py: {a} matches no result file")
        out.append((label, [read_row(f, names) for f in files]))
    return out


def main():
    args = sys.argv[1:]
    if not args or args[0] in ("-h", "--help"):
        sys.exit(__doc__)
    if "--" in args:
        k = args.index("--")
        args, names = args[:k], args[k + 1:]
    elif args and "=" not in args[0]:
        args, names = args[:1], args[1:]
    else:
        names = []
    names = names or DEFAULT
    groups = groups_of(args, names)
    print("group  replicas  " + "  ".join(names) + "  mean steps, mean step  loop s per replica")
    ref = {}
    for gi, (label, rows) in enumerate(groups):
        cells = []
        for n in names:
            v = np.array([r[n] for r in rows if n in r])
            if len(v) < 2:
                cells.append("n/a"); continue
            m, se = v.mean(), v.std(ddof=1) / math.sqrt(len(v))
            if gi == 0: ref[n] = (m, se)
            z = (m - ref[n][0]) / math.hypot(se, ref[n][1]) if gi > 0 and n in ref else 0.0
            cells.append(f"{m:.4g} ± {se:.2g} (z {z:+.1f})")
        steps = [r["steps"] for r in rows if "steps" in r]
        dts = [r["dt_mean"] for r in rows if "dt_mean" in r]
        loop = [r["loop_s"] for r in rows if "loop_s" in r]
        cells.append(f"{np.mean(steps):.0f}, {np.mean(dts):.3g}" if steps else "n/a")
        cells.append(f"{np.mean(loop):.1f}" if loop else "n/a")
        print(f"{label}  {len(rows)}  " + "  |  ".join(cells))


main()
