#!/usr/bin/python3
"""The volume-fraction scan of the issue-12 study (docs/paper-sensitivity.md, "Where the sign
changes"): delta_theta_m and S_zz of fused dumbbells (c/a 1) and homonuclear dicolloids (c/a 0.2)
at kT = 0 against phi, and of fused dumbbells at phi 0.1 against Pe (Brownian).

usage: phi_scan.py [RESULTS_DIR [OUT_PREFIX]]
  RESULTS_DIR  the study's result files (default: results/sensitivity of the repository)
  OUT_PREFIX   writes OUT_PREFIX.csv and OUT_PREFIX.png (default:
               examples/paper/results/sensitivity-phi-scan)

Every value is the mean over the run's averaging window (strains 150-500; Pe 0.1: 50-200 a^2/D0)
with two errors: the observer's blocking SE ("plateau" says whether the blocking reached one; if
not, that SE is a lower bound) and the SE of the means of 20-strain blocks, which are longer than
the decorrelation time (6-17 strains) and so nearly independent. The plot shows the second.
The runs with LAMMPS's lubricateU forms (lammps-phiX-n1000, tolerance 1e-3 a) are plotted; the
default forms at that tolerance (phiX-n1000-t3, their like-for-like pair) are in the CSV only.
"""
import csv
import math
import os
import re
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, HERE)
import generate  # noqa: E402
import table  # noqa: E402

SCAN = re.compile(r"^nobrown-(homo-|lammps-|lammpssmooth-)?phi([0-9.]+)(-r2|-n1000)?(-t3)?$")
PECLET = re.compile(r"^brownian-pe([0-9.]+)-phi([0-9.]+)(-r2|-n1000)?$")
COLUMNS = ["run", "shape", "forms", "tolerance", "phi", "N", "seeds", "Pe", "window", "delta_theta_m", "se_blocking",
           "plateau", "se_20_strain_blocks", "S_zz", "S_zz_se", "decorrelation_strains"]


def value(h5, path):
    d = h5["results/" + path]
    plateau = "no plateau" not in table.text(d.attrs.get("description", ""))
    return float(d[()]), float(d.attrs.get("stderr", math.nan)), plateau


def row(path, name, shape, phi, pe, variant):
    with h5py.File(path, "r") as h5:
        window, _, _ = table.blocks(h5)
        _, block_se = table.block_means(*table.theta_series(h5))
        theta, se, plateau = value(h5, "orientation/delta_theta_m")
        szz, szz_se, _ = value(h5, "orientation/S_zz")
        tau = float(h5["results/orientation/decorrelation_time"][()])
    v = generate.VARIANTS[variant]
    hydro = v.get("hydro", "")
    forms = ("lammps" if "conventions: lammps" in hydro else "fldsim") + \
        ("+smooth" if "visibility: smooth" in hydro else "")
    return {"run": name, "shape": shape, "forms": forms, "tolerance": v.get("tolerance", "1.0e-3"), "phi": phi, "N": v.get("count", generate.N),
            "seeds": "{}/{}".format(*v.get("seed", (1, 42))), "Pe": pe, "window": window,
            "delta_theta_m": theta, "se_blocking": se, "plateau": plateau,
            "se_20_strain_blocks": block_se, "S_zz": szz, "S_zz_se": szz_se,
            "decorrelation_strains": tau}


def collect(root):
    rows = []
    for f in sorted(os.listdir(root)):
        if not f.endswith(".h5"):
            continue
        name = f[:-3]
        m = SCAN.match(name)
        if m:
            rows.append(row(os.path.join(root, f), name, "homonuclear" if m.group(1) == "homo-" else "fused",
                            float(m.group(2)), math.inf, name[len("nobrown-"):]))
            continue
        m = PECLET.match(name)
        if m:
            rows.append(row(os.path.join(root, f), name, "fused", float(m.group(2)), float(m.group(1)),
                            name[len("brownian-"):]))
    return rows


def pe_error(r):
    """The error bar of a Pe point: the SE of 20-strain block means over a long window (100 strains or
    more), else the observer's blocking SE (the phi 0.5 first look averages 50 strains)."""
    first, last = (float(x) for x in r["window"].split("–"))
    return r["se_20_strain_blocks"] if last - first >= 100 else r["se_blocking"]


def plot(rows, out):
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    styles = {("fused", 216, "fldsim"): ("C0", "o", "fused c/a 1, N 216"),
              ("fused", 1000, "fldsim"): ("C2", "s", "fused c/a 1, N 1000"),
              ("fused", 1000, "lammps"): ("C3", "D", "fused, LAMMPS forms, N 1000, tol 1e-3"),
              ("fused", 1000, "lammps+smooth"): ("C4", "v", "same + smooth visibility"),
              ("homonuclear", 216, "fldsim"): ("C1", "^", "homonuclear c/a 0.2, N 216")}
    for (shape, n, forms), (colour, marker, label) in styles.items():
        pts = [r for r in rows
               if r["shape"] == shape and r["N"] == n and r["forms"] == forms and math.isinf(r["Pe"])
               and not r["run"].endswith("-t3")]
        if not pts:
            continue
        shift = {"fused": -0.002, "homonuclear": 0.002}[shape] + (0.004 if n == 1000 else 0.0) + \
            {"fldsim": 0.0, "lammps": 0.003, "lammps+smooth": 0.006}[forms]
        left.errorbar([r["phi"] + shift for r in pts], [r["delta_theta_m"] for r in pts],
                      yerr=[r["se_20_strain_blocks"] for r in pts], fmt=marker, color=colour,
                      label=label, capsize=2)
    left.axhline(0.0, color="grey", lw=0.8)
    left.set_xlabel(r"$\phi$")
    left.set_ylabel(r"$\Delta\theta_m$ (kT = 0, Pe $\to\infty$)")
    left.set_title("kT = 0, strains 150-500; > 0: away from the vorticity", fontsize=9)
    left.legend(fontsize=8)
    pts = sorted((r for r in rows if not math.isinf(r["Pe"])), key=lambda r: r["Pe"])
    if pts:
        for phi, colour in [(0.1, "C0"), (0.5, "C5")]:
            for replica, fmt, label in [("1/42", "o-", rf"fused c/a 1, $\phi$ {phi:g}, N 216"),
                                        ("2/43", "o", "other seeds")]:
                sel = [r for r in pts if r["seeds"] == replica and r["phi"] == phi and r["N"] == 216]
                if sel:
                    right.errorbar([r["Pe"] for r in sel], [r["delta_theta_m"] for r in sel],
                                   yerr=[pe_error(r) for r in sel], fmt=fmt, color=colour,
                                   mfc=colour if replica == "1/42" else "none", capsize=2, label=label)
        big = [r for r in pts if r["N"] == 1000]
        if big:
            right.errorbar([r["Pe"] * 1.15 for r in big], [r["delta_theta_m"] for r in big],
                           yerr=[pe_error(r) for r in big], fmt="s", color="C5", mfc="none", capsize=2,
                           label=r"$\phi$ 0.5, N 1000 (strains 10-40)")
        kt0 = [r for r in rows if r["shape"] == "fused" and r["phi"] == 0.1 and math.isinf(r["Pe"])]
        for r in kt0:
            right.axhline(r["delta_theta_m"], color="C0", ls=":", lw=0.8)
        right.set_xscale("log")
        right.axhline(0.0, color="grey", lw=0.8)
        right.set_xlabel("Pe")
        right.set_ylabel(r"$\Delta\theta_m$")
        right.set_title("Brownian, fused dumbbells (dotted: phi 0.1 at kT = 0)", fontsize=9)
        right.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "results", "sensitivity")
    prefix = sys.argv[2] if len(sys.argv) > 2 else os.path.normpath(
        os.path.join(ROOT, "examples", "paper", "results", "sensitivity-phi-scan"))
    rows = collect(root)
    if not rows:
        sys.exit(f"phi_scan.py: no scan results (nobrown-phi*.h5, brownian-pe*-phi*.h5) in {root}")
    rows.sort(key=lambda r: (r["shape"], r["forms"], r["Pe"], r["phi"], r["N"], r["seeds"]))
    with open(prefix + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{r[k]:.5g}" if isinstance(r[k], float) else r[k]) for k in COLUMNS})
    plot(rows, prefix + ".png")
    print(prefix + ".csv", prefix + ".png", sep="\n")


if __name__ == "__main__":
    main()
