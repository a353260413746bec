#!/usr/bin/python3
"""Read the runs of bench/lammps/run.sh and print the comparison as a markdown fragment.

CPU ms/step = (CPU of the WARMUP + STEPS run - CPU of the WARMUP run) / STEPS, both from
/usr/bin/time; the fastest of the REPEAT timed runs (and their range): other jobs on the machine
only ever add time, so the fastest run is the closest to each code's own cost.
eta_r = 1 + sigma_xy/(mu gammadot): LAMMPS from lubricateU's own stresslet and virial (no
Brownian stress), fldsim the stress observer's total (with the Brownian stress), averaged over the
samples after the warm-up; the error is the standard error of block means (5 blocks).
"""
import argparse
import datetime
import math
import os
import platform
import re
import subprocess

import h5py
import numpy as np

MU = 1.0 / (6.0 * math.pi)


def cpu_seconds(path):
    user, system, wall = open(path).read().split()[-3:]
    return float(user) + float(system), float(wall)


def mean_and_error(values, blocks=5):
    v = np.asarray(values, dtype=float)
    if len(v) == 0:
        return float("nan"), float("nan")
    if len(v) < 2 * blocks:
        return float(v.mean()), float(v.std(ddof=1) / math.sqrt(len(v))) if len(v) > 1 else float("nan")
    means = [b.mean() for b in np.array_split(v, blocks)]
    return float(v.mean()), float(np.std(means, ddof=1) / math.sqrt(blocks))


def lammps_stress(log, warmup, pe):
    """eta_r samples from the thermo lines (step time pxy) after the warm-up."""
    samples = {}
    in_table = False
    for line in open(log):
        if line.startswith("Step"):
            in_table = True
            continue
        if in_table:
            parts = line.split()
            if len(parts) == 3 and re.fullmatch(r"\d+", parts[0]):
                step = int(parts[0])
                if step > warmup:
                    samples[step] = 1.0 - float(parts[2]) / (MU * pe)
            else:
                in_table = False
    return [samples[k] for k in sorted(samples)]


def lammps_loop(log):
    """(loop seconds, steps, CPU use %) of the last run in a LAMMPS log."""
    loop = re.findall(r"Loop time of ([\d.eE+-]+) on \d+ procs for (\d+) steps", open(log).read())
    cpu = re.findall(r"([\d.]+)% CPU use", open(log).read())
    if not loop:
        return float("nan"), 0, float("nan")
    return float(loop[-1][0]), int(loop[-1][1]), float(cpu[-1]) if cpu else float("nan")


def fldsim_stress(h5):
    with h5py.File(h5, "r") as f:
        g = f["timeseries/stress/eta_r"] if "timeseries" in f else f["observables/stress/eta_r"]
        return list(g["value"][()])


def fldsim_log(log):
    m = re.search(r"done: (\d+) steps in [\d.]+ s \(([\d.]+) ms/step, ([\d.]+) CG iterations/step", open(log).read())
    return (int(m.group(1)), float(m.group(2)), float(m.group(3))) if m else (0, float("nan"), float("nan"))


def gdb_hits(path):
    """Hit counts of the breakpoints, in the order they were set (0 when never hit)."""
    if not os.path.exists(path):
        return None
    text = open(path).read()
    if "exited normally" not in text:
        return None
    hits = []
    for block in re.split(r"\n(?=\d+\s+breakpoint)", text.split("Num     Type")[-1])[1:]:
        m = re.search(r"already hit (\d+) times?", block)
        hits.append(int(m.group(1)) if m else 0)
    return hits


def per_step_cpu(d, name, repeat, steps):
    """Fastest and range of the per-step CPU ms of the repeats NAME.1 ... NAME.repeat."""
    short, _ = cpu_seconds(os.path.join(d, f"{name}-short.time"))
    values = [1000.0 * (cpu_seconds(os.path.join(d, f"{name}.{r}.time"))[0] - short) / steps
              for r in range(1, repeat + 1)]
    return min(values), min(values), max(values)


def fmt(x, digits=1):
    return "n/a" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{digits}f}"


def lammps_row(a, d, p):
    """The LAMMPS row: per-step CPU, loop time, CG iterations (gdb counts) and eta_r."""
    cpu, lo, hi = per_step_cpu(d, "lammps", a.repeat, a.steps)
    loop_s, loop_steps, loop_cpu = lammps_loop(p("lammps.1.log"))
    hits = gdb_hits(p("lammps.gdb"))
    cg = None
    if hits and len(hits) == 2:
        # compute_RU(): stage-one solve, compute_RU(double**): stage two; one call per iteration
        # plus one per solve for the initial residual.
        cg = (sum(hits) - 2 * a.count_steps) / a.count_steps
    eta, err = mean_and_error(lammps_stress(p("lammps.1.log"), a.warmup, a.pe))
    return {
        "code": "LAMMPS lubricateU + brownian", "forms": "LAMMPS (Ball-Melrose, pump 3/160, no twist)",
        "cpu": cpu, "range": (lo, hi),
        "wall": 1000.0 * loop_s / loop_steps if loop_steps else float("nan"),
        "cg": cg, "eta": eta, "err": err, "note": f"loop CPU use {fmt(loop_cpu, 0)}% (repeat 1)"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="clamp")
    ap.add_argument("--outdir", required=True)
    ap.add_argument("--steps", type=int, required=True)
    ap.add_argument("--warmup", type=int, required=True)
    ap.add_argument("--every", type=int, required=True)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--count-steps", type=int, required=True)
    ap.add_argument("--dt", type=float, required=True)
    ap.add_argument("--pe", type=float, required=True)
    ap.add_argument("--phi", type=float, default=0.45)
    ap.add_argument("--before", default="", help="name of the BEFORE build (run.sh): adds its row")
    ap.add_argument("--lammps-version", default="unknown")
    ap.add_argument("--brownian-stress", default="",
                    help="fldsim's run.brownian_stress in the timed runs (empty: the build's default)")
    a = ap.parse_args()
    d = a.outdir
    p = lambda name: os.path.join(d, name)

    rows = []
    # LAMMPS (a run that failed is reported as such; fldsim's rows stand alone)
    failed = open(p("lammps.failed")).read().strip() if os.path.exists(p("lammps.failed")) else ""
    if failed:
        nan = float("nan")
        rows.append({"code": "LAMMPS lubricateU + brownian", "forms": "LAMMPS (Ball-Melrose, pump 3/160, no twist)",
                     "cpu": nan, "range": (nan, nan), "wall": nan, "cg": None, "eta": nan, "err": nan,
                     "note": f"**did not run**: {failed}"})
    else:
        rows.append(lammps_row(a, d, p))
    # fldsim
    variants = [("lammps", "LAMMPS forms (conventions: lammps)"),
                ("default", "fldsim defaults (Jeffrey-Onishi pump, twist, fldsim R_0 fit)")]
    if a.before:
        variants.append(("before", f"LAMMPS forms, **before** ({a.before})"))
    for variant, forms in variants:
        cpu, lo, hi = per_step_cpu(d, f"fldsim-{variant}", a.repeat, a.steps)
        _, ms_long, cg_last = fldsim_log(p(f"fldsim-{variant}.1.log"))
        hits = gdb_hits(p(f"fldsim-{variant}.gdb"))
        cg = None
        if hits and len(hits) == 2 and hits[0] > 0:
            solves, products = hits
            cg = (products - solves) / a.count_steps  # minus each solve's initial residual
        eta, err = mean_and_error(fldsim_stress(p(f"fldsim-{variant}.1.h5")))
        rows.append({
            "code": "fldsim fld", "forms": forms, "cpu": cpu, "range": (lo, hi),
            "wall": ms_long, "cg": cg if cg is not None else cg_last, "eta": eta, "err": err,
            "note": f"its log: {fmt(cg_last)} CG it./step, all solves ({a.warmup + a.steps} steps)"})

    lmp = rows[0]["cpu"]
    commit = subprocess.run(["git", "-C", os.path.dirname(os.path.abspath(__file__)), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    n_samples = a.steps // a.every
    out = []
    scene = {
        "documented": "LAMMPS's documented settings: inner cutoff 2.01 a (fldsim delta_num 0.01), yukawa/colloid "
                      "repulsion A = 100 (6 pi mu a^2 gammadot), kappa = 100/a in both codes (fldsim plugin yukawa)",
        "paper": "the paper's settings: gap floor 1e-5 a; fldsim the paper's repulsion (C_p* = 10), LAMMPS a "
                 "yukawa/colloid of the same range (A = 90 kT/a, kappa = 1000/a: the paper force at h = 2e-4 a; the "
                 "two-point fit kappa = 6106/a loses atoms in LAMMPS at this dt)",
        "clamp": "no interparticle force in either code, gap floor 1e-5 a (the bench's original scene)",
    }[a.scene]
    out.append(f"## Scene '{a.scene}': fldsim against LAMMPS FLD (N = 1000 spheres, phi = {a.phi:g}, Pe = 10, one thread)\n")
    out.append(f"{datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC, {platform.node()}, commit {commit}, "
               f"LAMMPS {a.lammps_version}. Scene: {scene}. Same start (fldsim hard-sphere MC, written to a LAMMPS data file), "
               f"dt = {a.dt:g} a^2/D0, CG relative residual 1e-4, lubrication cutoff 2.5 a, "
               f"Brownian (kT = 1) with midpoint thermal drift in both. "
               f"{a.warmup} warm-up steps, then {a.steps} timed steps; OMP_NUM_THREADS=1.\n")
    out.append("| code | forms | CPU ms/step, fastest (range) | wall ms/step | LAMMPS/this (CPU) | CG it./step (both solves) | "
               "eta_r | note |")
    out.append("| --- | --- | ---: | ---: | ---: | ---: | ---: | --- |")
    for r in rows:
        ratio = lmp / r["cpu"] if r["cpu"] > 0 else float("nan")  # NaN when LAMMPS did not run
        out.append(f"| {r['code']} | {r['forms']} | {fmt(r['cpu'])} ({fmt(r['range'][0])}-{fmt(r['range'][1])}) | "
                   f"{fmt(r['wall'])} | {fmt(ratio, 2)} | "
                   f"{fmt(r['cg'])} | {fmt(r['eta'], 2)} ± {fmt(r['err'], 2)} | {r['note']} |")
    out.append("")
    out.append(f"- CPU ms/step: (CPU time of a {a.warmup}+{a.steps}-step run - CPU time of a {a.warmup}-step run)"
               f" / {a.steps}, user + system from /usr/bin/time, fastest (range) of {a.repeat} runs taking turns "
               "(other jobs only add time); the ratio is of the fastest runs. Wall ms/step is each code's own loop timer in its first run "
               "(LAMMPS: the timed steps; fldsim: all steps) and is inflated on a shared machine.")
    out.append(f"- CG it./step: matrix-vector products minus one per solve, counted with gdb breakpoints "
               f"in separate {a.count_steps}-step runs from the same start (LAMMPS: PairLubricateU::compute_RU, "
               "unpreconditioned, zero start); fldsim: its run log (every solve of a step, IC(0)-preconditioned, "
               "warm start).")
    out.append(f"- eta_r = 1 + sigma_xy/(mu gammadot), mean of {n_samples} samples (every {a.every} steps) after "
               "the warm-up, error = standard error of 5 block means. LAMMPS: -P_xy of `compute pressure NULL "
               "pair/hybrid lubricateU` (its R_S0 stresslet plus lubrication pair virial, no Brownian stress); fldsim: "
               "stress observer (isotropic and lubrication stresslets plus the Brownian stress, estimated by "
               f"`run.brownian_stress: {a.brownian_stress or 'the build default'}`). Over such a short window both mostly reflect the start "
               "configuration; they are not steady-state values.")
    print("\n".join(out))


if __name__ == "__main__":
    main()
