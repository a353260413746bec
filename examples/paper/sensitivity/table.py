#!/usr/bin/python3
"""Table of the issue-12 sensitivity study (docs/paper-sensitivity.md) from its result files.

usage: table.py [RESULTS_DIR]   (default: results/sensitivity of the repository)

Per run: delta_theta_m, delta_phi_m, S_xx, S_yy, S_zz and N2 (mean +- the observers' blocking SE;
'(np)' marks a value whose blocking found no plateau, so the SE is a lower bound), the averaging
window in strains, the orientation decorrelation time, and the means of delta_theta_m over
consecutive 20-strain blocks of the window (from the theta_m time series) to show whether the sign
holds throughout the run, with the standard error of their mean (blocks longer than the
decorrelation time are nearly independent, so this SE does not need the blocking plateau).
"""
import glob
import math
import os
import re
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import generate  # noqa: E402

QUANTITIES = [("orientation/delta_theta_m", "Δθ_m"), ("orientation/delta_phi_m", "Δφ_m"),
              ("orientation/S_xx", "S_xx"), ("orientation/S_yy", "S_yy"), ("orientation/S_zz", "S_zz"),
              ("stress/N2", "N2 (μγ̇)")]
BLOCK = 20.0


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def cell(h5, path):
    d = h5.get("results/" + path)
    if d is None:
        return "–"
    value, se = float(d[()]), float(d.attrs.get("stderr", math.nan))
    flag = " (np)" if "no plateau" in text(d.attrs.get("description", "")) else ""
    return f"{value:+.3f} ± {se:.3f}{flag}"


def theta_series(h5):
    """The orientation observer's (time, theta_m - 1) series; empty arrays when it has none."""
    g = h5.get("timeseries/orientation/theta_m")
    if g is None:
        return np.empty(0), np.empty(0)
    return np.asarray(g["time"]), np.asarray(g["value"]) - 1.0


def block_means(t, v):
    """Means of the series v(t) over consecutive BLOCK-strain blocks from its first sample, and
    their standard error (nan for fewer than two blocks)."""
    edges = np.arange(t[0], t[-1] + 1e-9, BLOCK)
    means = [v[(t >= a) & (t < a + BLOCK)].mean() for a in edges[:-1]]
    se = float(np.std(means, ddof=1) / math.sqrt(len(means))) if len(means) > 1 else math.nan
    return means, se


def block_summary(h5, t, v, missing):
    """(window, mean +- SE of the BLOCK-strain block means, the block means) of the series t, v.

    The window is that of the averages, which cover every sample the observer took (its state
    survives --resume); when the series holds fewer samples, missing(t, n, samples) says so."""
    if len(t) == 0:
        return "", "", ""
    d = h5["results/orientation/delta_theta_m"]
    match = re.search(r"mean over (\d+) samples", text(d.attrs.get("description", "")))
    samples = int(match.group(1)) if match else len(t)
    window = f"{t[-1] - (samples - 1) * generate.SAMPLE:g}–{t[-1]:g}"
    means, se = block_means(t, v)
    spread = f"{np.mean(means):+.3f} ± {se:.3f}" if len(means) > 1 else "–"
    listed = " ".join(f"{m:+.3f}" for m in means)
    if samples != len(t):
        listed += f" ({missing(t, len(t), samples)})"
    return window, spread, listed


def blocks(h5):
    # A resumed run's time series holds only the samples after the resume.
    t, v = theta_series(h5)
    return block_summary(h5, t, v, lambda t, n, samples: f"resumed run: blocks over {t[0]:g}–{t[-1]:g} only")


def row(path):
    name = os.path.basename(path)[:-3]
    with h5py.File(path, "r") as h5:
        window, spread, block_means = blocks(h5)
        d = h5.get("results/orientation/decorrelation_time")
        tau = f"{float(d[()]):.1f}" if d is not None else "–"
        return [name, window] + [cell(h5, q) for q, _ in QUANTITIES] + [tau, spread, block_means]


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "..", "..", "results", "sensitivity")
    order = ["brownian-" + v for v in generate.BROWNIAN] + ["nobrown-" + v for v in generate.NOBROWN]
    files = {os.path.basename(p)[:-3]: p for p in glob.glob(os.path.join(root, "*.h5"))}
    head = ["run", "strains averaged"] + [label for _, label in QUANTITIES] + \
        ["decorrelation (strains)", f"Δθ_m ± SE of {BLOCK:g}-strain blocks", f"Δθ_m per {BLOCK:g}-strain block"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for name in order:
        if name in files:
            print("| " + " | ".join(row(files[name])) + " |")


if __name__ == "__main__":
    main()
