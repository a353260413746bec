#!/usr/bin/python3
"""Figures of a parameter study (Kumar & Higdon Figs. of delta_theta_m, delta_phi_m and S_ii
against Pe): one curve per (shape, volume fraction), read from the /parameters attributes
peclet, volume_fraction, shape (and shape_c) of each run, plus eta_r, N1, N2 against Pe when
the stress observer ran. Runs missing a quantity are left out of that panel only. Also writes
study.csv with every value and its standard error.

usage: plot_study.py RUN1.h5 RUN2.h5 ... -o DIR
"""
import argparse
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fldsim_results as fr  # noqa: E402

QUANTITIES = [
    ("results/orientation/delta_theta_m", r"$\Delta\theta_m$ (rad)", "delta_theta_m"),
    ("results/orientation/delta_phi_m", r"$\Delta\phi_m$ (rad)", "delta_phi_m"),
    ("results/orientation/S_xx", r"$S_{xx}$", "S_xx"),
    ("results/orientation/S_yy", r"$S_{yy}$", "S_yy"),
    ("results/orientation/S_zz", r"$S_{zz}$", "S_zz"),
    ("results/stress/eta_r", r"$\eta_r$", "eta_r"),
    ("results/stress/N1", r"$N_1/(\mu\dot\gamma)$", "N1"),
    ("results/stress/N2", r"$N_2/(\mu\dot\gamma)$", "N2"),
    ("results/stress/Pi", r"$\Pi/(\mu\dot\gamma)$", "Pi"),
]


def load(paths):
    rows = []
    for path in paths:
        try:
            with h5py.File(path, "r") as h5:
                row = {"file": path, "shape": fr.shape_label(h5), "phi": fr.number(h5, "volume_fraction"),
                       "pe": fr.number(h5, "peclet")}
                for h5path, _, key in QUANTITIES:
                    row[key] = fr.scalar(h5, h5path)
                rows.append(row)
        except OSError as e:
            print(f"skipped {path}: {e}", file=sys.stderr)
    return rows


def plot_quantity(rows, key, label, out):
    groups = defaultdict(list)
    for r in rows:
        if r[key] is not None and not math.isnan(r["pe"]):
            groups[(r["shape"], round(r["phi"], 3))].append((r["pe"], *r[key]))
    if not groups:
        return None
    fig, ax = plt.subplots(figsize=(5.5, 4))
    positive = [pe for pts in groups.values() for pe, _, _ in pts if pe > 0]
    for (shape, phi), pts in sorted(groups.items()):
        pts.sort()
        pe, v, e = zip(*pts)
        ax.errorbar(pe, v, yerr=[0 if math.isnan(x) else x for x in e], marker="o", ms=4, capsize=2,
                    label=f"{shape}, phi={phi:g}")
    # Pe spans decades and may include 0 (quiescent): symmetric log keeps Pe = 0 on the axis.
    ax.set_xscale("symlog", linthresh=min(positive) if positive else 1.0)
    if key.startswith("delta") or key.startswith("S_") or key in ("N1", "N2"):
        ax.axhline(0.0, color="grey", lw=0.5)
    ax.set_xlabel("Pe")
    ax.set_ylabel(label)
    ax.legend(fontsize=7)
    path = os.path.join(out, f"{key}_vs_pe.png")
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path


def write_csv(rows, out):
    path = os.path.join(out, "study.csv")
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        keys = [k for _, _, k in QUANTITIES]
        w.writerow(["file", "shape", "volume_fraction", "peclet"] + [x for k in keys for x in (k, k + "_stderr")])
        for r in sorted(rows, key=lambda r: (r["shape"], r["phi"], r["pe"])):
            vals = []
            for k in keys:
                vals += list(r[k]) if r[k] is not None else ["", ""]
            w.writerow([r["file"], r["shape"], r["phi"], r["pe"]] + vals)
    return path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="result files")
    ap.add_argument("-o", "--out", required=True, help="output directory")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    rows = load(args.runs)
    if not rows:
        print("no readable result files", file=sys.stderr)
        return 1
    for _, label, key in QUANTITIES:
        path = plot_quantity(rows, key, label, args.out)
        print("wrote" if path else "skipped", path or f"{key} (no run has it)")
    print("wrote", write_csv(rows, args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
