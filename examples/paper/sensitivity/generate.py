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
  rk3          (Brownian) run.integrator: rk3, the paper's RK3 with the Brownian force frozen over
               its stages, instead of Euler-Maruyama with the midpoint drift: long-rk3 (two seeds),
               rk3-n1000-long, long-lammpslens-dmin1e-4-rk3
  n1000        N = 1000 (box 28.67 a), the paper's size (kT = 0 only: the Brownian run costs ~5x)
  fixeddt      fixed dt = 1e-3 instead of dt: auto with dt_max 0.01 (kT = 0 only: a step check)
  smoothvis    `hydro.visibility: smooth` (the node visibility rule as a C2 weight, docs/lubrication-taper.md)
  lammpslens-smoothvis  lammpslens with the smooth visibility (-replica: other seeds; 005, 02: width
               0.05 a, 0.2 a); lammps-smoothvis, lens-smoothvis: one of the two with it
  phiX, homo-phiX, phiX-r2, homo-phiX-r2, phiX-n1000
               the volume-fraction scan (kT = 0, tolerance 1e-4 a, strains 0-500 averaged over
               150-500): fused dumbbells (phiX) and homonuclear c/a 0.2 (homo-phiX) at phi X =
               0.1 ... 0.3, two seeds (-r2: Monte Carlo seed 2, noise seed 43), N = 1000 for the
               fused ones at 0.1-0.25; phi_scan.py summarises them
  nolog        hydro.conventions: lammps, log_terms: false: exactly LAMMPS pair lubricateU with
               flaglog 0 (the squeeze's 1/h alone, no tangential or rotational pair resistance;
               Kumar & Higdon's R_0 fit for it)
  squeeze      log_terms: false with fldsim's other forms (twist kept, smooth taper)
  nopump       pump: none (an ablation: no counter-rotation mode, the other forms fldsim's)
  dminX        repulsion delta_min X a (the paper's 1e-3 a; the force at the clamp scales with it, so a
               shorter range is also a weaker, overlapping contact); lammps-dmin1e-4: with LAMMPS's
               forms; dnum1e-3, dnum1e-2: hydro delta_num 1e-3 a, 1e-2 a (LAMMPS's documented inner
               cutoff 2.01): the contact model, which the paper fixes but which sets how close
               colliding dumbbells come
  peP-phi0.1   Brownian fused dumbbells at phi 0.1 and Pe P = 0.1 ... 1000 (-r2: other seeds)
  peP-phi0.5   Brownian fused dumbbells at phi 0.5 and Pe P = 1 ... 1000, strains 0-60 (a first look)
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
    "nolog": {"hydro": "conventions: lammps, log_terms: false"},
    "squeeze": {"hydro": "log_terms: false"},
    "nolog-replica": {"hydro": "conventions: lammps, log_terms: false", "seed": (2, 43)},
    "nopump": {"hydro": "pump: none"},
    "nopump-replica": {"hydro": "pump: none", "seed": (2, 43)},
    "smoothvis": {"hydro": "visibility: smooth"},
    "dmin1e-2": {"repulsion": "delta_min: 0.01"},
    "dmin1e-2-replica": {"repulsion": "delta_min: 0.01", "seed": (2, 43)},
    "dmin1e-4": {"repulsion": "delta_min: 0.0001"},
    "dmin1e-4-replica": {"repulsion": "delta_min: 0.0001", "seed": (2, 43)},
    "dmin3e-4": {"repulsion": "delta_min: 0.0003"},
    "dmin3e-5": {"repulsion": "delta_min: 3.0e-5"},
    "lammps-dmin1e-4": {"repulsion": "delta_min: 0.0001", "hydro": "conventions: lammps"},
    "lammpslens-dmin1e-4": {"repulsion": "delta_min: 0.0001", "hydro": "conventions: lammps", "phi": 0.2531},
    "lammpslens-dmin1e-4-replica": {"repulsion": "delta_min: 0.0001", "hydro": "conventions: lammps", "phi": 0.2531,
                                    "seed": (2, 43)},
    "dnum1e-3": {"hydro": "delta_num: 0.001"},
    "dnum1e-2": {"hydro": "delta_num: 0.01"},
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
# The volume-fraction scan at kT = 0 (tolerance 1e-4 a, the current default): where does each
# shape change from velocity-gradient to vorticity alignment? The companion non-Brownian study
# (kumar_jor) found velocity-gradient alignment at low phi for both shapes, vorticity alignment at
# high phi; the seed paper puts the fused dumbbells' change above phi = 0.3, the homonuclear one's
# below it.
# Strains 0-500 averaged over 150-500 (at phi 0.1 the homonuclear orientation still drifts after
# 100 strains), two seeds each; -r2: Monte Carlo seed 2, noise seed 43.
LONG = {"duration": 500.0, "start": 150.0}
for _phi in [0.1, 0.15, 0.2, 0.25, 0.3]:
    for _shape, _c in [("", 1), ("homo-", 0.2)]:
        for _rep, _seed in [("", (1, 42)), ("-r2", (2, 43))]:
            VARIANTS[f"{_shape}phi{_phi:g}{_rep}"] = dict(LONG, phi=_phi, c=_c, tolerance="1.0e-4", seed=_seed)
# At N = 216 two seeds differ by up to 0.03 at phi 0.15-0.2 (more than their blocking SEs): N = 1000
# for the fused dumbbells where the sign changes.
for _phi in [0.1, 0.15, 0.2, 0.25]:
    VARIANTS[f"phi{_phi:g}-n1000"] = dict(LONG, phi=_phi, tolerance="1.0e-4", count=1000)
# Does LAMMPS's lubricateU (its 3/160 pump halves the alignment at phi 0.3) move the crossover?
# Tolerance 1e-3 a, as the other kT = 0 rows of its forms: with their abrupt cutoff at 2.5 a the
# N 1000 runs at 1e-4 a advanced 15-25 frames/s against 60-120 with the default forms (1 h or more).
for _phi in [0.2, 0.25]:
    VARIANTS[f"lammps-phi{_phi:g}-n1000"] = dict(LONG, phi=_phi, tolerance="1.0e-3", count=1000,
                                                 hydro="conventions: lammps")
# LAMMPS's forms at phi 0.3, and with the smooth visibility rule too (the combination that came
# closest at phi 0.3, N 216; at phi 0.25 also the lens reading of the paper's 0.3); 15 min each at
# ~48-55 frames/s on a free core.
VARIANTS["lammps-phi0.3-n1000"] = dict(LONG, phi=0.3, tolerance="1.0e-3", count=1000, hydro="conventions: lammps")
for _phi in [0.25, 0.3]:
    VARIANTS[f"lammpssmooth-phi{_phi:g}-n1000"] = dict(LONG, phi=_phi, tolerance="1.0e-3", count=1000,
                                                       hydro="conventions: lammps, visibility: smooth")
# LAMMPS's flaglog 0 (squeeze only) at the paper's size, phi 0.3, the same tolerance.
VARIANTS["nolog-phi0.3-n1000"] = dict(LONG, phi=0.3, tolerance="1.0e-3", count=1000,
                                      hydro="conventions: lammps, log_terms: false")
# LAMMPS's forms (flaglog 1) at the paper's size with Brownian motion, Pe 1000, strains 0-500
# averaged over 150-500: lubricateU's model in the paper's setting.
VARIANTS["lammps-n1000-long"] = dict(LONG, count=1000, hydro="conventions: lammps")
# ... and the pump ablation at that size.
VARIANTS["nopump-phi0.3-n1000"] = dict(LONG, phi=0.3, tolerance="1.0e-3", count=1000, hydro="pump: none")
# ... with the repulsion's wall for overlapping nodes (instead of the clamp's plateau), so that
# Brownian kicks do not leave the short contact overlapped.
for _rep, _seed in [("", (1, 42)), ("-replica", (2, 43))]:
    VARIANTS[f"long-lammpslens-dmin1e-4{_rep}-wall"] = dict(LONG, phi=0.2531, hydro="conventions: lammps", seed=_seed,
                                                          repulsion="delta_min: 0.0001, overlap: wall")
# ... with the short range but the paper's force at the clamp (prefactor x 10: 12.5 C_p at delta_num as
# with delta_min 1e-3 a), a hard short contact rather than a weak one.
VARIANTS["long-lammpslens-dmin1e-4-rep100"] = dict(LONG, phi=0.2531, hydro="conventions: lammps", prefactor=100,
                                                   repulsion="delta_min: 0.0001")
# The combination that gives the paper's sign at N 216 (LAMMPS's forms, the lens reading of phi and a
# repulsion range of 1e-4 a instead of the paper's 1e-3 a; docs/paper-sensitivity.md, "The contact
# model") at the paper's size.
VARIANTS["lammpslens-dmin1e-4-n1000"] = dict(LONG, phi=0.2531, tolerance="1.0e-3", count=1000,
                                             hydro="conventions: lammps", repulsion="delta_min: 0.0001")
# ... and with Brownian motion at Pe 1000 (the paper's dt 1e-3 strain; about an hour on one core).
VARIANTS["lammpslens-dmin1e-4-n1000-long"] = dict(LONG, phi=0.2531, count=1000, hydro="conventions: lammps",
                                                      repulsion="delta_min: 0.0001")
# ... and the default forms at that tolerance, for a like-for-like pair at phi 0.2.
VARIANTS["phi0.2-n1000-t3"] = dict(LONG, phi=0.2, tolerance="1.0e-3", count=1000)
# The paper's Pe sweep (its Fig. 8f: delta_theta_m rising with Pe) at phi 0.1, where fldsim's
# fused dumbbells align with the velocity-gradient plane at kT = 0: Brownian, strains 0-500
# averaged over 150-500 (Pe 0.1: the paper's dt 1e-4 a^2/D0 over 0-200 a^2/D0, averaged over
# 50-200, about 150 rotational decorrelation times).
for _pe in [1, 10, 100, 1000]:
    VARIANTS[f"pe{_pe:g}-phi0.1"] = dict(LONG, phi=0.1, pe=_pe)
VARIANTS["pe1000-phi0.1-r2"] = dict(LONG, phi=0.1, pe=1000, seed=(2, 43))
VARIANTS["pe0.1-phi0.1"] = {"phi": 0.1, "pe": 0.1, "dt": 1e-4, "duration": 200.0, "start": 50.0}
# The paper's other fused-dumbbell statement (its Fig. 8f at phi 0.5): delta_theta_m rises up to
# Pe 1, then falls, turns negative and settles near zero. Brownian, N 216 (box 20.4 a), the step
# measured for fused dumbbells at phi 0.5 (4e-4 strain, examples/paper/sweep-measured-steps.yaml),
# strains 0-60 averaged over 10-60: a first look, about 10 min per point on one thread.
for _pe in [1, 10, 100, 1000]:
    VARIANTS[f"pe{_pe:g}-phi0.5"] = {"phi": 0.5, "pe": _pe, "dt": 4e-4, "duration": 60.0, "start": 10.0}
# ... and at the paper's N 1000 (box 34.1 a) at both ends, strains 0-40 averaged over 10-40 (about
# 25 min each).
for _pe in [1, 1000]:
    VARIANTS[f"pe{_pe:g}-phi0.5-n1000"] = {"phi": 0.5, "pe": _pe, "dt": 4e-4, "duration": 40.0, "start": 10.0,
                                           "count": 1000}
# The paper's integrator with Brownian motion: RK3 with the Brownian force frozen over its three
# stages (its section 2; fldsim's default is Euler-Maruyama with the midpoint drift). The kT = 0
# runs always use RK3, and the short contact (delta_min 1e-4 a with LAMMPS's forms and the lens
# reading) gave the paper's sign at kT = 0 but not with Brownian motion: does the integrator decide?
VARIANTS["long-rk3"] = dict(LONG, integrator="rk3")
VARIANTS["long-rk3-replica"] = dict(LONG, integrator="rk3", seed=(2, 43))
VARIANTS["long-lammpslens-dmin1e-4-rk3"] = dict(LONG, phi=0.2531, hydro="conventions: lammps", integrator="rk3",
                                                repulsion="delta_min: 0.0001")
VARIANTS["rk3-n1000-long"] = dict(LONG, count=1000, integrator="rk3")
# ... and at Pe 10 and 100, where RK3 leaves most frames with an overlapped pair (first 5 strains:
# 99 % and 57 % of frames against 5 % and 6 % with the midpoint scheme), with the midpoint pairs.
# (At Pe 1 and the paper's dt 1e-3 RK3 does not run: overlaps of 0.1 a and CG failing within 0.2 strain.)
for _pe in [10, 100]:
    VARIANTS[f"long-rk3-pe{_pe}"] = dict(LONG, pe=_pe, integrator="rk3")
    VARIANTS[f"long-pe{_pe}"] = dict(LONG, pe=_pe)
VARIANTS["long"] = dict(LONG)
VARIANTS["long-replica"] = dict(LONG, seed=(2, 43))
for _name in ["lammps", "lens", "lammpslens", "oldforms", "notaper", "lammpslens-smoothvis",
              "lammpslens-smoothvis-replica", "nolog", "squeeze", "nopump", "dmin1e-2", "dmin1e-4", "dnum1e-3",
              "dmin1e-4-replica", "dmin3e-4", "dmin3e-5", "lammps-dmin1e-4", "lammpslens-dmin1e-4", "lammpslens-dmin1e-4-replica"]:
    VARIANTS["long-" + _name] = dict(VARIANTS[_name], **LONG)
BROWNIAN = ["baseline", "lammps", "lens", "lammpslens", "notaper", "isobody", "rep100", "replica", "oldforms",
            "smoothvis", "lammpslens-smoothvis", "nolog", "squeeze", "lammps-n1000-long", "dmin1e-4", "lammps-dmin1e-4", "lammpslens-dmin1e-4",
            "long-lammpslens-dmin1e-4", "long-lammpslens-dmin1e-4-replica", "lammpslens-dmin1e-4-n1000-long",
            "long-lammpslens-dmin1e-4-wall", "long-lammpslens-dmin1e-4-replica-wall", "long-lammpslens-dmin1e-4-rep100",
            "long-rk3", "long-rk3-replica", "long-lammpslens-dmin1e-4-rk3", "rk3-n1000-long", "long", "long-replica",
            "long-rk3-pe10", "long-pe10", "long-rk3-pe100", "long-pe100"] + [v for v in VARIANTS if v.startswith("pe")]
NOBROWN = ["baseline", "replica", "lammps", "oldforms", "lens", "isobody", "rep100", "lammpslens", "notaper", "centrearm", "lever", "pump", "twist", "khfit", "long",
           "long-lammps", "long-lens", "long-lammpslens", "long-oldforms", "long-notaper", "n1000", "fixeddt",
           "smoothvis", "lammpslens-smoothvis", "lammpslens-smoothvis-replica", "lammps-smoothvis",
           "lens-smoothvis", "lammpslens-smoothvis005", "lammpslens-smoothvis02", "long-lammpslens-smoothvis",
           "long-lammpslens-smoothvis-replica", "nolog", "squeeze", "nolog-replica", "long-nolog",
           "long-squeeze", "nolog-phi0.3-n1000", "nopump", "nopump-replica", "long-nopump", "nopump-phi0.3-n1000", "dmin1e-2", "dmin1e-2-replica", "dnum1e-3", "dnum1e-2", "dmin1e-4", "long-dmin1e-2", "long-dmin1e-4",
           "long-dnum1e-3", "long-dmin1e-4-replica", "long-dmin3e-4", "long-dmin3e-5", "long-lammps-dmin1e-4",
           "long-lammpslens-dmin1e-4", "long-lammpslens-dmin1e-4-replica", "lammpslens-dmin1e-4-n1000",
           "long-lammpslens-dmin1e-4-wall", "long-lammpslens-dmin1e-4-rep100"] + [v for v in VARIANTS if "phi" in v and v[:3] in ("phi", "hom", "lam")]


def experiment(name, variant, brownian):
    v = VARIANTS[variant]
    mc_seed, noise_seed = v.get("seed", (1, 42))
    hydro = "{plugin: fld" + (", " + v["hydro"] if "hydro" in v else "") + "}"
    duration, start = v.get("duration", DURATION), v.get("start", START)
    if brownian:
        pe, dt = v.get("pe", 1000), v.get("dt", 0.001)
        flow = f"{{peclet: {pe:g}}}"
        integrator = f"integrator: {v['integrator']}, " if "integrator" in v else ""
        run = f"{{dt: {dt:g}, duration: {duration:g}, time_unit: paper, {integrator}seed: {noise_seed}, threads: 1, checkpoint_every: {CHECKPOINT:g}}}"
        every = int(round(SAMPLE / dt))
    elif "dt" in v:
        flow = "{peclet: 1000, brownian: false}"
        run = (f"{{dt: {v['dt']:g}, duration: {duration:g}, time_unit: paper, seed: {noise_seed}, threads: 1, "
               f"checkpoint_every: {CHECKPOINT:g}}}")
        every = int(round(SAMPLE / v["dt"]))
    else:
        flow = "{peclet: 1000, brownian: false}"
        run = (f"{{dt: auto, dt_max: 0.01, tolerance: {v.get('tolerance', '1.0e-3')}, duration: {duration:g}, time_unit: paper, "
               f"seed: {noise_seed}, threads: 1, checkpoint_every: {CHECKPOINT:g}}}")
        every = int(round(SAMPLE / 0.01))  # frames of dt_max
    return f"""# Issue 12 sensitivity study, variant {variant} ({f"Brownian, Pe = {v.get('pe', 1000):g}" if brownian else 'kT = 0'}).
# Generated by examples/paper/sensitivity/generate.py -- edit that script, not this file.
system:
  shape: {{plugin: dicolloid, a: 1.0, b: 1.0, c: {v.get('c', 1):g}}}
  count: {v.get('count', N)}
  volume_fraction: {v.get('phi', 0.3):g}
  init: {{method: monte_carlo, seed: {mc_seed}}}
flow: {flow}
hydro: {hydro}
forces:
  - {{plugin: repulsion, prefactor: {v.get('prefactor', 10):g}, unit: paper{", " + v["repulsion"] if "repulsion" in v else ""}}}
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
