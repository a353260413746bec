#!/usr/bin/python3
"""Plots a sweep's study table (study.csv, written by `fldsim sweep`): each result against one
axis, one curve per combination of the other axes, with standard-error bars. Points whose
blocking found no plateau (the SE is a lower bound) are drawn hollow. Use it to put hydro
models side by side on the same axes (a sweep with a `hydro.plugin` axis) or any other
comparison; tools/plot_study.py draws the paper's figures from the result files themselves.

usage: plot_sweep.py STUDY.csv --x flow.peclet [--y orientation/delta_theta_m stress/eta_r ...]
                     [-o DIR] [--logx]
Without --y, every result with a standard error is plotted. Writes DIR/<result>.png (DIR
defaults to the folder of STUDY.csv + /figures) and prints the files written.
"""
import argparse
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("study")
    ap.add_argument("--x", required=True, help="the axis key to put on the x axis, e.g. flow.peclet")
    ap.add_argument("--y", nargs="*", help="results to plot (default: every result with an SE)")
    ap.add_argument("-o", "--out", help="output folder (default: next to the study, figures/)")
    ap.add_argument("--logx", action="store_true", help="logarithmic x axis (x = 0 left out)")
    args = ap.parse_args()

    with open(args.study, newline="") as f:
        reader = csv.DictReader(f)
        rows = [r for r in reader if r["status"] == "done"]
        columns = reader.fieldnames
    if not rows:
        sys.exit(f"plot_sweep.py: {args.study}: no finished points")
    results = [c[:-3] for c in columns if c.endswith("_se")]
    first_result = columns.index(results[0]) if results else len(columns)
    axes = [c for c in columns[3:first_result]]
    if args.x not in axes:
        sys.exit(f"plot_sweep.py: --x {args.x}: not an axis of {args.study} (axes: {', '.join(axes)})")
    wanted = args.y or [r for r in results if any(row[r + "_se"] for row in rows)]
    missing = [y for y in wanted if y not in results]
    if missing:
        sys.exit(f"plot_sweep.py: no result named {', '.join(missing)} (results: {', '.join(results)})")
    others = [a for a in axes if a != args.x]
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.study)), "figures")
    os.makedirs(out, exist_ok=True)

    for y in wanted:
        curves = defaultdict(list)
        for r in rows:
            x, v = number(r[args.x]), number(r[y])
            if x is None or v is None or (args.logx and x <= 0):
                continue
            se = number(r[y + "_se"]) or 0.0
            key = ", ".join(f"{a} = {r[a]}" for a in others) + (f", repeat {r['repeat']}" if r["repeat"] != "0" else "")
            curves[key].append((x, v, se if math.isfinite(se) else 0.0, r[y + "_no_plateau"] == "1"))
        if not curves:
            continue
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        for key, pts in sorted(curves.items()):
            pts.sort()
            xs, vs, ses, flags = zip(*pts)
            line = ax.errorbar(xs, vs, yerr=ses, marker="o", capsize=3, label=key or y)[0]
            hollow = [(x, v) for x, v, f in zip(xs, vs, flags) if f]
            if hollow:
                ax.plot(*zip(*hollow), "o", mfc="white", mec=line.get_color())
        if args.logx:
            ax.set_xscale("log")
        ax.set_xlabel(args.x)
        ax.set_ylabel(y)
        ax.legend(fontsize=7)
        ax.set_title("hollow: no plateau in the blocking (SE is a lower bound)", fontsize=8)
        fig.tight_layout()
        path = os.path.join(out, y.replace("/", "_") + ".png")
        fig.savefig(path, dpi=120)
        plt.close(fig)
        print(path)


if __name__ == "__main__":
    main()
