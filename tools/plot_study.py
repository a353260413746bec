#!/usr/bin/python3
"""Figures of a parameter study, after Kumar & Higdon (orientation and microstructure of sheared
Brownian dicolloids), from a set of fldsim result files. Each run is placed by the /parameters
attributes peclet, volume_fraction, shape and shape_c. Writes into OUT:

  gxy_<shape>.png                 front-view g(x,y) maps, rows phi, columns Pe   (paper Figs. 6, 7)
  P_theta_<shape>.png             P(theta) at every Pe, one panel per phi        (Fig. 8 a,b,d,e)
  P_phi_<shape>.png               P(phi) at every Pe, one panel per phi          (Fig. 9 a,b,d,e)
  delta_theta_m_vs_pe.png         delta theta_m against Pe, one curve per (shape, phi)  (Fig. 8 c,f)
  delta_phi_m_vs_pe.png           delta phi_m against Pe                         (Fig. 9 c,f)
  S_ii_<shape>.png                S_xx, S_yy, S_zz against Pe, one panel per phi (Fig. 10)
  S_xx/S_yy/S_zz/eta_r/N1/N2/Pi/g_anisotropy _vs_pe.png   one curve per (shape, phi)
  study.csv                       every value with its standard error

g_anisotropy = <g>_compressional / <g>_extensional - 1 over the contact shell 1.8 < r/a < 3 of
the g(x,y) map: positive when pairs pile up in the compressional quadrants (x y < 0) and are
depleted in the extensional ones, as the paper describes from Pe = 1 on.
f_ext = (1/pi) * integral of P(phi) over 0 < phi < pi/2: the fraction of directors whose x-y
projection lies in the extensional quadrant (0.5 isotropic; the paper: > 0.5 from Pe = 1 on).
Maps are shown coarsened 2 x 2 and P(theta), P(phi) rebinned by 2 (--coarsen) to tame the noise
of small runs; the numbers use the full resolution.

usage: plot_study.py RUN1.h5 RUN2.h5 ... -o DIR [--table]
Runs missing a quantity are left out of that panel only.
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
import numpy as np  # noqa: E402
from matplotlib.colors import TwoSlopeNorm  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fldsim_results as fr  # noqa: E402

OR = "results/orientation/"
PD = "results/pair_distribution/"
ST = "results/stress/"
QUANTITIES = [
    (OR + "delta_theta_m", r"$\Delta\theta_m$ (rad)", "delta_theta_m"),
    (OR + "delta_phi_m", r"$\Delta\phi_m$ (rad)", "delta_phi_m"),
    (OR + "S_xx", r"$S_{xx}$", "S_xx"),
    (OR + "S_yy", r"$S_{yy}$", "S_yy"),
    (OR + "S_zz", r"$S_{zz}$", "S_zz"),
    (ST + "eta_r", r"$\eta_r$", "eta_r"),
    (ST + "N1", r"$N_1/(\mu\dot\gamma)$", "N1"),
    (ST + "N2", r"$N_2/(\mu\dot\gamma)$", "N2"),
    (ST + "Pi", r"$\Pi/(\mu\dot\gamma)$", "Pi"),
    (None, r"g anisotropy $\langle g\rangle_c/\langle g\rangle_e - 1$", "g_anisotropy"),
    (None, r"$f_{ext}$ (directors in the extensional quadrant)", "f_ext"),
]
SHELL = (1.8, 3.0)  # contact shell of the anisotropy measure, in a


def g_anisotropy(g, edges):
    """(<g>_compressional / <g>_extensional - 1, its SE from the cell counts' spread) of a g(x,y) map."""
    c = 0.5 * (edges[1:] + edges[:-1])
    x, y = np.meshgrid(c, c, indexing="ij")  # rows: x, columns: y (as stored)
    r = np.hypot(x, y)
    shell = (r > SHELL[0]) & (r < SHELL[1])
    comp, ext = g[shell & (x * y < 0)], g[shell & (x * y > 0)]
    if comp.size == 0 or ext.size == 0 or ext.mean() <= 0:
        return None
    ratio = comp.mean() / ext.mean()
    err = ratio * math.hypot(comp.std(ddof=1) / math.sqrt(comp.size) / comp.mean(),
                             ext.std(ddof=1) / math.sqrt(ext.size) / ext.mean())
    return ratio - 1.0, err


def f_ext(p, edges, err):
    """Fraction of directors in the extensional quadrant 0 < phi < pi/2, with its naive SE."""
    width = np.diff(edges) / math.pi
    pos = 0.5 * (edges[1:] + edges[:-1]) > 0
    value = float(np.sum(p[pos] * width[pos]))
    se = float(np.sqrt(np.sum((err[pos] * width[pos]) ** 2))) if err is not None else math.nan
    return value, se


def coarsen(a, k):
    """Mean over k-blocks along every axis (equal cells, so g and P average exactly); trims a remainder."""
    if k <= 1:
        return a
    if a.ndim == 1:
        n = a.size // k * k
        return a[:n].reshape(-1, k).mean(axis=1)
    n0, n1 = a.shape[0] // k * k, a.shape[1] // k * k
    return a[:n0, :n1].reshape(n0 // k, k, n1 // k, k).mean(axis=(1, 3))


def load(paths):
    rows = []
    for path in paths:
        try:
            with h5py.File(path, "r") as h5:
                if "parameters" not in h5:  # e.g. a sweep's study.h5 next to its runs
                    print(f"plot_study.py: {path}: not a run's result file (no /parameters), skipped",
                          file=sys.stderr)
                    continue
                row = {"file": path, "shape": fr.shape_label(h5), "phi": round(fr.number(h5, "volume_fraction"), 3),
                       "pe": fr.number(h5, "peclet")}
                for h5path, _, key in QUANTITIES:
                    if h5path:
                        row[key] = fr.scalar(h5, h5path)
                for key in ("theta_edges", "P_theta", "phi_edges", "P_phi", "P_phi_stderr"):
                    row[key] = fr.array(h5, OR + key)
                row["f_ext"] = (f_ext(row["P_phi"], row["phi_edges"], row["P_phi_stderr"])
                                if row["P_phi"] is not None and row["phi_edges"] is not None else None)
                row["g_xy"], row["map_edges"] = fr.array(h5, PD + "g_xy"), fr.array(h5, PD + "map_edges")
                row["g_anisotropy"] = (g_anisotropy(row["g_xy"], row["map_edges"])
                                       if row["g_xy"] is not None and row["map_edges"] is not None else None)
                rows.append(row)
        except OSError as e:
            print(f"skipped {path}: {e}", file=sys.stderr)
    return rows


def safe(name):
    """A file-name part: 'homonuclear (c/a=0.2)' -> 'homonuclear_c_a_0.2'."""
    out = "".join(ch if ch.isalnum() or ch == "." else "_" for ch in name)
    return "_".join(part for part in out.split("_") if part)


def save(fig, out, name):
    path = os.path.join(out, name)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path


def pe_axis(ax, pes):
    # Pe spans decades and may include 0 (quiescent): symmetric log keeps Pe = 0 on the axis.
    positive = [p for p in pes if p > 0]
    ax.set_xscale("symlog", linthresh=min(positive) if positive else 1.0)
    ax.set_xlabel("Pe")


def plot_quantity(rows, key, label, out):
    groups = defaultdict(list)
    for r in rows:
        if r[key] is not None and not math.isnan(r["pe"]):
            groups[(r["shape"], r["phi"])].append((r["pe"], *r[key]))
    if not groups:
        return None
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for (shape, phi), pts in sorted(groups.items()):
        pts.sort()
        pe, v, e = zip(*pts)
        ax.errorbar(pe, v, yerr=[0 if math.isnan(x) else x for x in e], marker="o", ms=4, capsize=2,
                    label=f"{shape}, phi={phi:g}")
    pe_axis(ax, [p for pts in groups.values() for p, _, _ in pts])
    if key.startswith("delta") or key.startswith("S_") or key in ("N1", "N2", "g_anisotropy"):
        ax.axhline(0.0, color="grey", lw=0.5)
    if key == "f_ext":
        ax.axhline(0.5, color="grey", lw=0.5)
    ax.set_ylabel(label)
    ax.legend(fontsize=7)
    return save(fig, out, f"{key}_vs_pe.png")


def by_shape(rows):
    shapes = defaultdict(list)
    for r in rows:
        shapes[r["shape"]].append(r)
    return shapes


def plot_order_parameters(rows, out):
    """S_xx, S_yy, S_zz against Pe in one panel per volume fraction (the paper's Fig. 10)."""
    written = []
    for shape, rs in sorted(by_shape(rows).items()):
        phis = sorted({r["phi"] for r in rs if r["S_zz"] is not None})
        if not phis:
            continue
        fig, axes = plt.subplots(1, len(phis), figsize=(4.2 * len(phis), 3.6), squeeze=False, sharey=True)
        for ax, phi in zip(axes[0], phis):
            pts = sorted((r for r in rs if r["phi"] == phi and r["S_zz"] is not None), key=lambda r: r["pe"])
            for key, marker in (("S_xx", "o"), ("S_yy", "s"), ("S_zz", "^")):
                ax.errorbar([r["pe"] for r in pts], [r[key][0] for r in pts], yerr=[r[key][1] for r in pts],
                            marker=marker, ms=4, capsize=2, label=key)
            pe_axis(ax, [r["pe"] for r in pts])
            ax.axhline(0.0, color="grey", lw=0.5)
            ax.set_title(f"{shape}, phi={phi:g}", fontsize=9)
            ax.legend(fontsize=7)
        axes[0][0].set_ylabel(r"$S_{ii}$")
        written.append(save(fig, out, f"S_ii_{safe(shape)}.png"))
    return written


def plot_distributions(rows, key, xlabel, out, k=1):
    """P(theta) or P(phi) at every Pe, one panel per volume fraction (the paper's Figs. 8, 9)."""
    written = []
    for shape, rs in sorted(by_shape(rows).items()):
        phis = sorted({r["phi"] for r in rs if r["P_" + key] is not None})
        if not phis:
            continue
        fig, axes = plt.subplots(1, len(phis), figsize=(4.2 * len(phis), 3.6), squeeze=False, sharey=True)
        for ax, phi in zip(axes[0], phis):
            pts = sorted((r for r in rs if r["phi"] == phi and r["P_" + key] is not None), key=lambda r: r["pe"])
            colours = plt.cm.viridis(np.linspace(0, 0.9, max(1, len(pts))))
            for r, col in zip(pts, colours):
                edges = r[key + "_edges"]
                centres = coarsen(0.5 * (edges[1:] + edges[:-1]), k)
                ax.plot(centres / math.pi, coarsen(r["P_" + key], k), color=col, lw=1.2, marker=".",
                        label=f"Pe={r['pe']:g}")
            ax.axhline(1.0, color="grey", lw=0.5)
            ax.set_xlabel(xlabel)
            ax.set_title(f"{shape}, phi={phi:g}", fontsize=9)
            ax.legend(fontsize=7)
        axes[0][0].set_ylabel(f"P({key})")
        written.append(save(fig, out, f"P_{key}_{safe(shape)}.png"))
    return written


def plot_gxy(rows, out, k=1):
    """Front-view g(x,y) maps: rows volume fraction, columns Pe (the paper's Figs. 6, 7)."""
    written = []
    for shape, rs in sorted(by_shape(rows).items()):
        rs = [r for r in rs if r["g_xy"] is not None]
        phis, pes = sorted({r["phi"] for r in rs}), sorted({r["pe"] for r in rs})
        if not rs:
            continue
        fig, axes = plt.subplots(len(phis), len(pes), figsize=(2.6 * len(pes) + 0.8, 2.6 * len(phis)),
                                 squeeze=False)
        # Colours centred on 1 and clipped at 0 and 2, to show small departures from 1 (as the paper).
        norm = TwoSlopeNorm(vmin=0.0, vcenter=1.0, vmax=2.0)
        mesh = None
        for i, phi in enumerate(phis):
            for j, pe in enumerate(pes):
                ax = axes[i][j]
                match = [r for r in rs if r["phi"] == phi and r["pe"] == pe]
                ax.set_aspect("equal")
                ax.set_xticks([])
                ax.set_yticks([])
                if not match:
                    ax.axis("off")
                    continue
                r = match[0]
                e = r["map_edges"][:: max(1, k)]
                g = coarsen(r["g_xy"], k)[: e.size - 1, : e.size - 1]
                mesh = ax.pcolormesh(e[: g.shape[0] + 1], e[: g.shape[1] + 1], g.T, cmap="RdBu_r", norm=norm,
                                     shading="flat")
                ax.set_title(f"phi={phi:g}, Pe={pe:g}", fontsize=8)
        if mesh is not None:
            fig.colorbar(mesh, ax=axes, shrink=0.8, label="g(x,y)  (x flow, y gradient)")
        fig.suptitle(f"{shape}: front view g(x,y), |z| < slab_half", fontsize=9)
        path = os.path.join(out, f"gxy_{safe(shape)}.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written


def write_csv(rows, out):
    path = os.path.join(out, "study.csv")
    keys = [k for _, _, k in QUANTITIES]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["file", "shape", "volume_fraction", "peclet"] + [x for k in keys for x in (k, k + "_stderr")])
        for r in sorted(rows, key=lambda r: (r["shape"], r["phi"], r["pe"])):
            vals = []
            for k in keys:
                vals += list(r[k]) if r[k] is not None else ["", ""]
            w.writerow([r["file"], r["shape"], r["phi"], r["pe"]] + vals)
    return path


def print_table(rows):
    cols = [("delta_theta_m", 4), ("delta_phi_m", 4), ("S_xx", 3), ("S_yy", 3), ("S_zz", 3), ("eta_r", 2),
            ("N1", 2), ("N2", 2), ("g_anisotropy", 2), ("f_ext", 3)]

    def cell(v, d):
        if v is None:
            return "-"
        return f"{v[0]:.{d}f}({v[1]:.{d}f})" if not math.isnan(v[1]) else f"{v[0]:.{d}f}"

    head = ["shape", "phi", "Pe"] + [c for c, _ in cols]
    body = [[r["shape"], f"{r['phi']:g}", f"{r['pe']:g}"] + [cell(r[c], d) for c, d in cols]
            for r in sorted(rows, key=lambda r: (r["shape"], r["phi"], r["pe"]))]
    widths = [max(len(x) for x in col) for col in zip(head, *body)]
    print("steady-state values, (standard error); N1, N2 in mu*gammadot; eta_r without Brownian stress")
    for line in [head] + body:
        print("  ".join(x.rjust(w) for x, w in zip(line, widths)))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="result files")
    ap.add_argument("-o", "--out", required=True, help="output directory")
    ap.add_argument("--table", action="store_true", help="print the summary table")
    ap.add_argument("--coarsen", type=int, default=2, help="display: map cells / histogram bins merged (2)")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    rows = load(args.runs)
    if not rows:
        print("no readable result files", file=sys.stderr)
        return 1
    k = max(1, args.coarsen)
    written = plot_gxy(rows, args.out, k)
    written += plot_distributions(rows, "theta", r"$\theta/\pi$ (from vorticity z)", args.out, k)
    written += plot_distributions(rows, "phi", r"$\phi/\pi$ (from gradient y; 0.5 = flow x)", args.out, k)
    written += plot_order_parameters(rows, args.out)
    for _, label, key in QUANTITIES:
        path = plot_quantity(rows, key, label, args.out)
        if path:
            written.append(path)
        else:
            print(f"skipped {key} (no run has it)")
    written.append(write_csv(rows, args.out))
    print(f"wrote {len(written)} files into {args.out}")
    if args.table:
        print_table(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
