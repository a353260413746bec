#!/usr/bin/python3
"""Writes the experiment files of the Pe = 1000 sensitivity study of issue 12 (fused dumbbells,
c/a = 1, phi = 0.3): does a model choice the paper leaves open flip the sign of delta_theta_m?
docs/paper-sensitivity.md holds the table; `run.sh BUILD` runs the files one at a time (skipping
finished ones, resuming from checkpoints), `table.py` reads the results and prints the table.

Every file: N = 216 (box 17.20 a at phi 0.3), strains 0-160 with the orientation and stress
observers from strain 20 (every 0.5 strain), checkpoints every 20 strains, one thread.
  brownian-*   Pe = 1000, Euler-Maruyama, dt = 1e-3 strain (the paper example's step)
  nobrown-*    flow.brownian: false (kT = 0, the Pe -> infinity limit with the same repulsion
               relative to the shear), RK3 with dt: auto (dt_max 0.01, tolerance 1e-3 a)
Variants (one change each against the current defaults):
  baseline     current defaults (fld: r0_fit fldsim, strain_arm contact, lever centre, pump
               jeffrey_onishi, twist, taper smooth; isotropic sphere; repulsion C_p* = 10)
  replica      baseline with another Monte Carlo start and noise seed
  lammps       hydro.conventions: lammps (exactly LAMMPS pair lubricateU; r0_fit kumar_higdon)
  oldforms     strain_arm centre, taper none: the defaults of commit 7961f32, where the sign was
               first measured (issue 12)
  lens         volume_fraction 0.2531: the paper's phi = 0.3 read as N 2 V_sphere / V_box (lens of the
               two nodes counted twice), i.e. the same box with V = 1.6875 sphere volumes per body;
               R_0(phi) then also sees 0.2531
  isobody      hydro.isotropic: body (R_0 = the body's node-sum free-draining resistance scaled by
               the fit, with its strain forcing: an isolated dumbbell then has a Jeffery orbit)
               instead of the paper's sphere-like R_0 per body
  rep100       repulsion prefactor 100 (C_p* x 10)
  centrearm    strain_arm: centre alone (kT = 0 only)
  lever, pump, twist, khfit
               one LAMMPS form each: lever: contact; pump: lammps; twist: false; r0_fit: kumar_higdon
               (kT = 0 only: which part of `lammps` moves delta_theta_m)
  notaper      taper: none only (the abrupt cutoff; r0_fit fldsim then uses its abrupt-cutoff fit)
  lammpslens   lammps and lens together (LAMMPS's forms with the lens counted twice)
  long-X       variant X (long = baseline) over strains 0-500, averages from 150 as the paper's
               (kT = 0 only)
  n1000        N = 1000 (box 28.67 a), the paper's size (kT = 0 only: the Brownian run costs ~5x)
  fixeddt      fixed dt = 1e-3 instead of dt: auto with dt_max 0.01 (kT = 0 only: a step check)
  smoothvis    `hydro.visibility: smooth` (the node visibility rule as a C2 weight, docs/lubrication-taper.md)
  lammpslens-smoothvis  lammpslens with the smooth visibility (-replica: other seeds; 005, 02: width
               0.05 a, 0.2 a); lammps-smoothvis, lens-smoothvis: one of the two with it
"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))
N = 216
DURATION, START, SAMPLE, CHECKPOINT = 160.0, 20.0, 0.5, 20.0

VARIANTS = {
    "baseline": {},
    "replica": {"seed": (2, 43)},
    "lammps": {"hydro": "conventions: lammps"},
    "oldforms": {"hydro": "strain_arm: centre, taper: none"},
    "lens": {"phi": 0.2531},
    "isobody": {"hydro": "isotropic: body"},
    "rep100": {"prefactor": 100},
    "n1000": {"count": 1000},
    "notaper": {"hydro": "taper: none"},
    "centrearm": {"hydro": "strain_arm: centre"},
    "lever": {"hydro": "lever: contact"},
    "pump": {"hydro": "pump: lammps"},
    "twist": {"hydro": "twist: false"},
    "khfit": {"hydro": "r0_fit: kumar_higdon"},
    "lammpslens": {"hydro": "conventions: lammps", "phi": 0.2531},
    "fixeddt": {"dt": 0.001},
    "smoothvis": {"hydro": "visibility: smooth"},
    "lammpslens-smoothvis": {"hydro": "conventions: lammps, visibility: smooth", "phi": 0.2531},
    "lammpslens-smoothvis-replica": {"hydro": "conventions: lammps, visibility: smooth", "phi": 0.2531,
                                     "seed": (2, 43)},
    "lammps-smoothvis": {"hydro": "conventions: lammps, visibility: smooth"},
    "lens-smoothvis": {"hydro": "visibility: smooth", "phi": 0.2531},
    "lammpslens-smoothvis005": {"hydro": "conventions: lammps, visibility: smooth, visibility_width: 0.05",
                                "phi": 0.2531},
    "lammpslens-smoothvis02": {"hydro": "conventions: lammps, visibility: smooth, visibility_width: 0.2",
                               "phi": 0.2531},
}
LONG = {"duration": 500.0, "start": 150.0}
VARIANTS["long"] = dict(LONG)
for _name in ["lammps", "lens", "lammpslens", "oldforms", "notaper", "lammpslens-smoothvis",
              "lammpslens-smoothvis-replica"]:
    VARIANTS["long-" + _name] = dict(VARIANTS[_name], **LONG)
BROWNIAN = ["baseline", "lammps", "lens", "lammpslens", "notaper", "isobody", "rep100", "replica", "oldforms",
            "smoothvis", "lammpslens-smoothvis"]
NOBROWN = ["baseline", "replica", "lammps", "oldforms", "lens", "isobody", "rep100", "lammpslens", "notaper", "centrearm", "lever", "pump", "twist", "khfit", "long",
           "long-lammps", "long-lens", "long-lammpslens", "long-oldforms", "long-notaper", "n1000", "fixeddt",
           "smoothvis", "lammpslens-smoothvis", "lammpslens-smoothvis-replica", "lammps-smoothvis",
           "lens-smoothvis", "lammpslens-smoothvis005", "lammpslens-smoothvis02", "long-lammpslens-smoothvis",
           "long-lammpslens-smoothvis-replica"]


def experiment(name, variant, brownian):
    v = VARIANTS[variant]
    mc_seed, noise_seed = v.get("seed", (1, 42))
    hydro = "{plugin: fld" + (", " + v["hydro"] if "hydro" in v else "") + "}"
    duration, start = v.get("duration", DURATION), v.get("start", START)
    if brownian:
        flow = "{peclet: 1000}"
        run = f"{{dt: 0.001, duration: {duration:g}, time_unit: paper, seed: {noise_seed}, threads: 1, checkpoint_every: {CHECKPOINT:g}}}"
        every = int(round(SAMPLE / 0.001))
    elif "dt" in v:
        flow = "{peclet: 1000, brownian: false}"
        run = (f"{{dt: {v['dt']:g}, duration: {duration:g}, time_unit: paper, seed: {noise_seed}, threads: 1, "
               f"checkpoint_every: {CHECKPOINT:g}}}")
        every = int(round(SAMPLE / v["dt"]))
    else:
        flow = "{peclet: 1000, brownian: false}"
        run = (f"{{dt: auto, dt_max: 0.01, tolerance: 1.0e-3, duration: {duration:g}, time_unit: paper, "
               f"seed: {noise_seed}, threads: 1, checkpoint_every: {CHECKPOINT:g}}}")
        every = int(round(SAMPLE / 0.01))  # frames of dt_max
    return f"""# Issue 12 sensitivity study, variant {variant} ({'Brownian, Pe = 1000' if brownian else 'kT = 0'}).
# Generated by examples/paper/sensitivity/generate.py -- edit that script, not this file.
system:
  shape: {{plugin: dicolloid, a: 1.0, b: 1.0, c: 1}}
  count: {v.get('count', N)}
  volume_fraction: {v.get('phi', 0.3):g}
  init: {{method: monte_carlo, seed: {mc_seed}}}
flow: {flow}
hydro: {hydro}
forces:
  - {{plugin: repulsion, prefactor: {v.get('prefactor', 10):g}, unit: paper}}
run: {run}
observers:
  - {{plugin: orientation, every: {every}, start: {start:g}}}
  - {{plugin: stress, every: {every}, start: {start:g}}}
output: ../../../results/sensitivity/{name}.h5
"""


def main():
    names = [("brownian-" + v, v, True) for v in BROWNIAN] + [("nobrown-" + v, v, False) for v in NOBROWN]
    for name, variant, brownian in names:
        with open(os.path.join(HERE, name + ".yaml"), "w") as f:
            f.write(experiment(name, variant, brownian))
        print(name + ".yaml")


if __name__ == "__main__":
    main()
