#!/usr/bin/python3
"""The N = 1000 orientation results against Pe (issue 12): delta_theta_m, delta_phi_m and S_zz of
fused dumbbells (c/a 1) and homonuclear dicolloids (c/a 0.2) at phi = 0.3, averages over the paper's
window (t* 150-500) with their standard errors (open markers: the blocking found no plateau, so the
bar is a lower bound). The paper's figures (Kumar & Higdon, Figs. 8c/8f and 10) give no numbers,
only the trends its text states, which the panel titles repeat.

usage: plot_n1000.py [OUT.png]   (default: n1000-orientation.png next to this script)

Reads n1000-fused-sweep-orientation.csv, n1000-homonuclear-sweep-orientation.csv and, for Pe = 1,
n1000-fused-pe1-step-orientation.csv (the run at dt 2.5e-4 a^2/D0, which the step checks call for;
docs/paper.md), all written by summarize_orientation.py.
"""
import csv
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
QUANTITIES = [
    ("orientation/delta_theta_m", r"$\Delta\theta_m$",
     "paper: fused dumbbells rise with Pe\n(no vorticity alignment), homonuclear fall"),
    ("orientation/delta_phi_m", r"$\Delta\varphi_m$", "paper: > 0 under shear (flow alignment)"),
    ("orientation/S_zz", r"$S_{zz}$", "paper: fused dumbbells fall with Pe,\nhomonuclear rise"),
]


def rows(name):
    path = os.path.join(HERE, name)
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def peclet(point):
    return float(re.search(r"peclet-([0-9.eE+-]+)", point).group(1))


def series(table, replace=None):
    """{Pe: row}, the rows of `replace` taking the place of those with the same Pe."""
    out = {peclet(r["point"]): r for r in table}
    for r in replace or []:
        out[peclet(r["point"])] = r
    return dict(sorted(out.items()))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "n1000-orientation.png")
    fused = series(rows("n1000-fused-sweep-orientation.csv"), rows("n1000-fused-pe1-step-orientation.csv"))
    homo = series(rows("n1000-homonuclear-sweep-orientation.csv"))
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    for ax, (key, label, paper) in zip(axes, QUANTITIES):
        for data, name, colour, marker in ((fused, "fused dumbbells, c/a = 1", "C3", "o"),
                                           (homo, "homonuclear, c/a = 0.2", "C0", "s")):
            pe = list(data)
            value = [float(data[p][key]) for p in pe]
            se = [float(data[p][key + "_se"]) for p in pe]
            lower_bound = [data[p].get(key + "_no_plateau") == "1" for p in pe]
            ax.errorbar(pe, value, yerr=se, color=colour, lw=1, capsize=3, label=name, fmt="-")
            for p, v, open_marker in zip(pe, value, lower_bound):
                ax.plot([p], [v], marker=marker, color=colour, mfc="white" if open_marker else colour, ms=6)
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.set_xscale("log")
        ax.set_xlabel("Pe")
        ax.set_ylabel(label)
        ax.set_title(paper, fontsize=8)
    axes[0].legend(fontsize=8, loc="lower left")
    fig.suptitle("fldsim, N = 1000, phi = 0.3, averages over t* = 150-500 (open markers: no blocking plateau)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
