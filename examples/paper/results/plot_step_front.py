#!/usr/bin/python3
"""Fixed against adaptive steps at the paper's dt = 1e-4 points, N = 1000, at rest (issue 13, item 5).

x: CPU seconds per a^2/D0 (step-cost-n1000.csv); y: -log10 of the chi-square p of g(r) against
the exact hard-core Monte Carlo oracle over the 50 bins of 0.02 a from 2 to 3 a, bins' correlation
taken into account (step-oracle-n1000.csv, 16 independent runs each; every seed set of a setting
is a point of its own, marked "seeds 17+" or "33+"). Open markers fail the
comparison (its chi-square or its Bonferroni test over bins); the dashed line is the chi-square's
bound, p = 0.005. A setting is on the front when no setting is both cheaper and more accurate.

    /usr/bin/python3 examples/paper/results/plot_step_front.py [OUT.png]
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def rows(name):
    with open(os.path.join(HERE, name)) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def key(r):
    """A setting: phi (without the seed-set mark " s17" / " s33" of the oracle rows), mode, step, L/tol."""
    return (r["phi"].split()[0], r["mode"], float(r["dt_or_dtmax"]), r["tolerance"] and float(r["tolerance"]))


def seed_set(r):
    parts = r["phi"].split()
    return parts[1] if len(parts) > 1 else ""


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "step-front-n1000.png")
    cost = {key(r): float(r["cpu_s_per_a2_d0"]) for r in rows("step-cost-n1000.csv")}
    # Homonuclear rows only (a "fused" mark is another particle); every seed set of a setting is drawn.
    oracle = [r for r in rows("step-oracle-n1000.csv")
              if r["N"] == "1000" and "fused" not in r["phi"] and key(r) in cost]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, phi in zip(axes, ["0.5", "0.3"]):
        for r in oracle:
            if key(r)[0] != phi:
                continue
            mode = r["mode"]
            label = {"auto": f"auto, tol {r['tolerance']}, frame {r['dt_or_dtmax']}",
                     "bound": f"bound {r['tolerance']} a, frame {r['dt_or_dtmax']}",
                     "pieces": f"bound {r['tolerance']} a, equal pieces",
                     "gap": f"gap bound {r['tolerance']} a",
                     "both": f"both bounds, gap {r['tolerance']} a"}.get(
                         mode, f"fixed {r['dt_or_dtmax']}")
            if seed_set(r):
                label += f" (seeds {seed_set(r)[1:]}+)"
            marker, colour = {"auto": ("v", "C1"), "bound": ("s", "C2"), "pieces": ("D", "C3"),
                              "gap": ("*", "C4"), "both": ("P", "C5")}.get(mode, ("o", "C0"))
            passed = r["verdict"] == "pass"
            ax.scatter(cost[key(r)], -math.log10(float(r["chi2_p"])), s=60, marker=marker,
                       facecolors=colour if passed else "none", edgecolors=colour, zorder=3)
            ax.annotate(label, (cost[key(r)], -math.log10(float(r["chi2_p"]))), textcoords="offset points",
                        xytext=(5, 4), fontsize=7)
        ax.axhline(-math.log10(0.005), ls="--", color="0.5", lw=1)
        ax.set_yscale("symlog", linthresh=1)
        ax.set_xscale("log")
        ax.set_xlabel("CPU s per a²/D0 (N = 1000, one thread, Pe 0.1 runs)")
        ax.set_title(f"homonuclear c/a 0.2, φ {phi}, Pe 0: g(r) against the oracle")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("-log10 chi-square p, g(r) vs oracle (16 runs)")
    fig.text(0.01, 0.01, "circles fixed steps, triangles dt: auto with a tolerance, squares dt: auto with "
             "run.displacement (dyadic pieces), diamonds the same with equal pieces, stars run.gap_step,\nplus signs both "
             "(displacement 0.028 and gap_step); filled: passes "
             "the oracle; dashed: p = 0.005",
             fontsize=7)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(out, dpi=130)
    print(out)


if __name__ == "__main__":
    main()
