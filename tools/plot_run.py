#!/usr/bin/python3
"""Figures of one fldsim run: g(x,y) front view (colour scale centred on 1), other g maps,
g(r), P(theta), P(phi), P(theta,phi), MSD and director autocorrelation, and time series.

usage: plot_run.py RUN.h5 [-o DIR]
Panels whose observer did not run are skipped (and listed). Uses the Debian python3 with
python3-matplotlib, python3-h5py, python3-numpy; headless (Agg).
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import TwoSlopeNorm  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fldsim_results as fr  # noqa: E402

PD = "results/pair_distribution/"
OR = "results/orientation/"
DF = "results/diffusion/"


def save(fig, out, name, written):
    path = os.path.join(out, name)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
    written.append(path)


def plot_maps(h5, title, out, written, skipped):
    edges = fr.array(h5, PD + "map_edges")
    found = False
    for proj, (xl, yl) in {"xy": ("x/a (flow)", "y/a (gradient)"), "xz": ("x/a (flow)", "z/a (vorticity)"),
                           "yz": ("y/a (gradient)", "z/a (vorticity)")}.items():
        g = fr.array(h5, PD + "g_" + proj)
        if g is None or edges is None:
            continue
        found = True
        fig, ax = plt.subplots(figsize=(5.2, 4.5))
        # Rows of the stored map are the first axis: transpose so it runs horizontally.
        vmax = max(float(np.nanmax(g)), 1.0 + 1e-6)
        norm = TwoSlopeNorm(vmin=0.0, vcenter=1.0, vmax=max(vmax, 2.0))
        mesh = ax.pcolormesh(edges, edges, g.T, cmap="RdBu_r", norm=norm, shading="flat")
        fig.colorbar(mesh, ax=ax, label="g (uncorrelated = 1)")
        ax.set_aspect("equal")
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        ax.set_title(f"g({proj[0]},{proj[1]})  {title}", fontsize=9)
        save(fig, out, f"g_{proj}.png", written)
    if not found:
        skipped.append("g maps (no pair_distribution results)")
    r, g, e = fr.array(h5, PD + "r"), fr.array(h5, PD + "g_r"), fr.array(h5, PD + "g_r_stderr")
    if r is not None and g is not None:
        fig, ax = plt.subplots(figsize=(5, 3.5))
        ax.errorbar(r, g, yerr=e, lw=1, elinewidth=0.5)
        ax.axhline(1.0, color="grey", lw=0.5)
        ax.set_xlabel("r/a")
        ax.set_ylabel("g(r)")
        ax.set_title(title, fontsize=9)
        save(fig, out, "g_r.png", written)


def plot_angles(h5, title, out, written, skipped):
    panels = [("theta", r"$\theta$ (rad, from vorticity z)"), ("phi", r"$\phi$ (rad, from gradient y; +x = flow)")]
    any_found = False
    for key, label in panels:
        edges, p, e = fr.array(h5, OR + key + "_edges"), fr.array(h5, OR + "P_" + key), fr.array(
            h5, OR + "P_" + key + "_stderr")
        if edges is None or p is None:
            continue
        any_found = True
        fig, ax = plt.subplots(figsize=(5, 3.5))
        centres = 0.5 * (edges[1:] + edges[:-1])
        ax.stairs(p, edges, color="C0")
        if e is not None:
            ax.errorbar(centres, p, yerr=e, fmt="none", ecolor="C0", elinewidth=0.7)
        ax.axhline(1.0, color="grey", lw=0.5, label="isotropic")
        ax.set_xlabel(label)
        ax.set_ylabel(f"P({key})")
        m = fr.scalar(h5, OR + key + "_m")
        extra = f"  {key}_m = {m[0]:.4f} ± {m[1]:.4f}" if m else ""
        ax.set_title(title + extra, fontsize=9)
        save(fig, out, f"P_{key}.png", written)
    pm, te, pe = fr.array(h5, OR + "P_theta_phi"), fr.array(h5, OR + "theta_edges"), fr.array(h5, OR + "phi_edges")
    if pm is not None and te is not None and pe is not None:
        fig, ax = plt.subplots(figsize=(5.5, 3.8))
        norm = TwoSlopeNorm(vmin=0.0, vcenter=1.0, vmax=max(2.0, float(np.nanmax(pm))))
        mesh = ax.pcolormesh(pe, te, pm, cmap="RdBu_r", norm=norm)
        fig.colorbar(mesh, ax=ax, label=r"P($\theta,\phi$)")
        ax.set_xlabel(r"$\phi$ (rad)")
        ax.set_ylabel(r"$\theta$ (rad)")
        ax.set_title(title, fontsize=9)
        save(fig, out, "P_theta_phi.png", written)
    if not any_found:
        skipped.append("P(theta), P(phi) (no orientation results)")


def plot_diffusion(h5, title, out, written, skipped):
    t, msd, err = fr.array(h5, DF + "lag_time"), fr.array(h5, DF + "msd_nonaffine"), fr.array(
        h5, DF + "msd_nonaffine_stderr")
    if t is None or msd is None:
        skipped.append("MSD (no diffusion results)")
        return
    # Lag times are in the run's time unit (a^2/D0 or 1/gammadot), as the unit attribute says.
    unit = fr.text(h5[DF + "lag_time"].attrs.get("unit", "a^2/D0"))
    fig, ax = plt.subplots(figsize=(5, 3.8))
    for a, name in enumerate("xyz"):
        ax.errorbar(t, msd[:, a], yerr=None if err is None else err[:, a], marker="o", ms=3, lw=1,
                    label=f"{name} (shear-corrected)")
    tot = fr.array(h5, DF + "msd_total")
    if tot is not None:
        ax.plot(t, tot[:, 0], "k--", lw=0.8, label="x total")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(f"lag t ({unit})")
    ax.set_ylabel(r"MSD ($a^2$)")
    ax.legend(fontsize=7)
    ax.set_title(title, fontsize=9)
    save(fig, out, "msd.png", written)
    c1, c2 = fr.array(h5, DF + "C1"), fr.array(h5, DF + "C2")
    if c1 is not None:
        fig, ax = plt.subplots(figsize=(5, 3.5))
        ax.plot(t, c1, "o-", ms=3, label=r"$\langle n(t)\cdot n(0)\rangle$")
        if c2 is not None:
            ax.plot(t, c2, "s-", ms=3, label=r"$\langle P_2\rangle$")
        ax.set_xscale("log")
        ax.set_xlabel(f"lag t ({unit})")
        ax.legend(fontsize=8)
        dr = fr.scalar(h5, DF + "D_r")
        ax.set_title(title + (f"  D_r = {dr[0]:.4g} ± {dr[1]:.2g}" if dr else ""), fontsize=9)
        save(fig, out, "director_autocorrelation.png", written)


def plot_series(h5, title, out, written):
    wanted = [("timeseries/orientation/theta_m", r"$\theta_m$ (rad)"),
              ("timeseries/orientation/phi_m", r"$\phi_m$ (rad)"),
              ("timeseries/stress/eta_r", r"$\eta_r$")]
    found = [(p, l, fr.series(h5, p)) for p, l in wanted]
    found = [(p, l, s) for p, l, s in found if s is not None and len(s[0]) > 0]
    if not found:
        return
    fig, axes = plt.subplots(len(found), 1, figsize=(6, 2.2 * len(found)), sharex=True, squeeze=False)
    for ax, (_, label, (t, v)) in zip(axes[:, 0], found):
        ax.plot(t, v, lw=0.8)
        ax.set_ylabel(label)
    axes[-1, 0].set_xlabel(f"t ({fr.series_time_unit(h5, found[0][0])})")
    axes[0, 0].set_title(title, fontsize=9)
    save(fig, out, "time_series.png", written)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", help="result file RUN.h5")
    ap.add_argument("-o", "--out", help="output directory (default: RUN_plots next to the file)")
    args = ap.parse_args(argv)
    out = args.out or os.path.splitext(args.run)[0] + "_plots"
    os.makedirs(out, exist_ok=True)
    written, skipped = [], []
    with h5py.File(args.run, "r") as h5:
        title = f"{fr.shape_label(h5)}, phi={fr.number(h5, 'volume_fraction'):.3g}, Pe={fr.number(h5, 'peclet'):g}"
        plot_maps(h5, title, out, written, skipped)
        plot_angles(h5, title, out, written, skipped)
        plot_diffusion(h5, title, out, written, skipped)
        plot_series(h5, title, out, written)
    for p in written:
        print("wrote", p)
    for s in skipped:
        print("skipped", s)
    return 0


if __name__ == "__main__":
    sys.exit(main())
