"""Time against error for one fixed scene: usage `accuracy.py BUILD OUTDIR`.

Runs bench/accuracy/scene.yaml with `BUILD/bin/fldsim run` for every setting of sweep.py, measures
each run's cost and its error against a tight reference (errors.py), and writes
OUTDIR/accuracy.md (tables), OUTDIR/time_vs_error.png (also copied next to this script),
OUTDIR/accuracy.json (the raw numbers). FLDSIM_BENCH_QUICK=1 runs the short plan;
FLDSIM_BENCH_JOBS (default 2) runs that many simulations at once; FLDSIM_ACCURACY_CLOCK=cpu|wall
picks the cost that ranks settings (default cpu; see runner.py).
"""
import datetime
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import errors  # noqa: E402
import report  # noqa: E402
import runner  # noqa: E402
import sweep  # noqa: E402

SCENE = os.path.join(HERE, "scene.yaml")
# Brownian observers sample at fixed strain intervals, whatever dt is, so that every setting
# averages the same number of samples (comparable standard errors).
SAMPLE_STRAIN = {"stress": 0.02, "orientation": 0.1, "pair_distribution": 0.2}


def steps(duration, dt):
    return max(1, round(duration / dt))


def start_job(fldsim, workdir):
    """One non-Brownian step of 1e-9 from the Monte Carlo start: its last frame is the common start
    of every run (system.init.method=file), so no run pays for the Monte Carlo in its cost."""
    out = os.path.join(workdir, "start.h5")
    args = [fldsim, "run", SCENE, "-o", out, "--overwrite", "--set", "flow.brownian=false",
            "--set", "run.time_unit=strain", "--set", "run.dt=1e-9", "--set", "run.duration=1e-9",
            "--set", "observers=[{plugin: trajectory, every: 1}]"]
    return runner.Job("start", args, out, out + ".log", 1)


def from_start(start):
    return ["--set", "system.init.method=file", "--set", f"system.init.file={start}"]


def deterministic_job(fldsim, setting, plan, workdir):
    out = os.path.join(workdir, f"det_{setting.key}.h5")
    n = steps(plan.strain, setting.dt)
    args = [fldsim, "run", SCENE, "-o", out, "--overwrite", "--set", "flow.brownian=false",
            "--set", f"run.duration={plan.strain!r}", "--set", "run.time_unit=strain",
            "--set", f"observers=[{{plugin: trajectory, every: {n}}}]"]
    for o in setting.overrides():
        args += ["--set", o]
    args += from_start(os.path.join(workdir, "start.h5"))
    return runner.Job(f"det_{setting.key}", args, out, out + ".log", n)


def brownian_job(fldsim, setting, plan, workdir):
    out = os.path.join(workdir, f"brown_{setting.key}.h5")
    observers = ", ".join(
        f"{{plugin: {name}, every: {steps(interval, setting.dt)}, start: {plan.brownian_start!r}}}"
        for name, interval in SAMPLE_STRAIN.items())
    args = [fldsim, "run", SCENE, "-o", out, "--overwrite",
            "--set", f"run.duration={plan.brownian_duration!r}", "--set", f"observers=[{observers}]"]
    for o in setting.overrides():
        args += ["--set", o]
    args += from_start(os.path.join(workdir, "start.h5"))
    return runner.Job(f"brown_{setting.key}", args, out, out + ".log",
                      steps(plan.brownian_duration, setting.dt))


def commit_of(repo):
    try:
        return subprocess.run(["git", "-C", repo, "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def _dominating(rows, default, error):
    """The cheapest row of the front that is at most as costly and at most as wrong as `default`."""
    better = [r for r in rows if r is not default and r["cost"] <= default["cost"] and error(r) <= error(default)]
    return min(better, key=lambda r: r["cost"]) if better else None


def verdict(det_rows, brown_rows, reference_cutoff):
    """Sentences on whether the default is on each Pareto front and, if not, what beats it."""
    default = next(r for r in det_rows if r["setting"].is_default)
    name = "The current defaults ({})".format(default["setting"].label)
    lines = []
    # The same-model (numerical) front first: dt and the CG tolerance are numerical parameters.
    for key, flag, what in (("numerical_position", "numerical_pareto",
                             "against the same-cutoff numerical reference (dt and CG tolerance, one model)"),
                            ("position", "pareto", f"against the tight reference (cutoff {reference_cutoff})")):
        if default.get(flag):
            lines.append(f"{name} are on the Pareto front {what}.")
            continue
        rows = [r for r in det_rows if r.get(flag)]
        best = _dominating(rows, default, lambda r: r[key])
        text = f"{name} are not on the Pareto front {what}"
        if best:
            text += (": {} costs {:.2f} s against {:.2f} s with position error {:.3g} a against {:.3g} a"
                     ).format(best["setting"].label, best["cost"], default["cost"], best[key], default[key])
        lines.append(text + ".")
    if not default.get("pareto") and default.get("numerical_pareto"):
        lines.append(f"Against the cutoff-{reference_cutoff} reference every setting at the default cutoff has the "
                     "same error, so only the cheapest of them is on that front: the error is the difference "
                     "between two models, not numerical error. The cutoff decides which pairs get the pair "
                     "lubrication on top of R_0(phi), and R_0(phi) is fitted at cutoff 2.5 a to "
                     "Stokesian-Dynamics diffusivities (docs/fld-r0-fit.md), so the cutoff is a model choice "
                     "(and the cutoff family shows how much it matters); for dt and the CG tolerance the "
                     "numerical front applies, and the defaults are on it.")
    consistent = {r["setting"]: all(c for _, _, c in r["compared"].values())
                  for r in brown_rows if "compared" in r}
    bad = [s.label for s, ok in consistent.items() if not ok]
    lines.append(f"Brownian runs inconsistent with the (cutoff-{reference_cutoff}) reference at 2 SE: "
                 + "; ".join(bad) + "." if bad else "Every Brownian setting agrees with the reference within 2 SE.")
    same = {r["setting"]: all(c for _, _, c in r["numerical_compared"].values())
            for r in brown_rows if "numerical_compared" in r}
    bad_same = [s.label for s, ok in same.items() if not ok]
    brown_default = next((r for r in brown_rows if r["setting"].is_default and "numerical_compared" in r), None)
    if brown_default:
        worst = max(err / comb if comb > 0 else math.inf
                    for err, comb, _ in brown_default["numerical_compared"].values())
        agree = "agree" if same[brown_default["setting"]] else "do NOT agree"
        lines.append(f"{name} {agree} with the same-cutoff Brownian numerical reference (largest difference "
                     f"{worst:.1f} combined SE over eta_r, delta_theta_m and g near contact).")
    if same:
        lines.append("Brownian runs at the default cutoff inconsistent with the same-cutoff numerical reference at "
                     "2 SE: " + "; ".join(bad_same) + "." if bad_same else
                     "Every Brownian run at the default cutoff agrees with the same-cutoff numerical reference "
                     "within 2 SE (eta_r, delta_theta_m and g near contact): at this run length dt and the CG "
                     "tolerance make no difference that sampling can see.")
    return "\n".join(f"- {x}" for x in lines)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: accuracy.py BUILD OUTDIR")
    build, outdir = (os.path.abspath(a) for a in sys.argv[1:])
    fldsim = os.path.join(build, "bin", "fldsim")
    if not os.access(fldsim, os.X_OK):
        sys.exit(f"accuracy.py: {fldsim}: no fldsim executable (build the `fldsim` target first)")
    quick = os.environ.get("FLDSIM_BENCH_QUICK", "0") not in ("", "0")
    parallel = int(os.environ.get("FLDSIM_BENCH_JOBS", "2"))
    clock = os.environ.get("FLDSIM_ACCURACY_CLOCK", "cpu")
    if clock not in ("cpu", "wall"):
        sys.exit(f"accuracy.py: FLDSIM_ACCURACY_CLOCK: expected cpu or wall, got {clock}")
    plan = sweep.quick_plan() if quick else sweep.full_plan()
    workdir = os.path.join(outdir, "accuracy_runs")
    os.makedirs(workdir, exist_ok=True)

    det_settings = [plan.reference, plan.numerical_reference] + plan.deterministic
    brown_settings = [plan.brownian_reference, plan.brownian_numerical_reference] + plan.brownian
    det_jobs = {s: deterministic_job(fldsim, s, plan, workdir) for s in det_settings}
    brown_jobs = {s: brownian_job(fldsim, s, plan, workdir) for s in brown_settings}
    jobs = list(det_jobs.values()) + list(brown_jobs.values())
    started = time.monotonic()
    runner.run_all([start_job(fldsim, workdir)])
    print(f"accuracy: {len(jobs)} runs ({'quick' if quick else 'full'} plan, {parallel} at a time) in {workdir}",
          flush=True)
    timings = runner.run_all(jobs, parallel, on_done=lambda job, t: print(
        f"  {job.name}: {t.wall:.1f} s wall, {t.cpu:.1f} s cpu, {t.cg_per_step:.1f} CG it/step", flush=True))
    elapsed = time.monotonic() - started

    def cost(t):
        return t.cpu if clock == "cpu" else t.wall

    det_rows = []
    for s, job in det_jobs.items():
        t = timings[job.name]
        row = {"setting": s, "timing": t, "cost": cost(t)}
        row["position"], row["orientation"] = errors.trajectory_error(
            job.output, det_jobs[plan.reference].output)
        if s.cutoff == plan.numerical_reference.cutoff:
            row["numerical_position"], row["numerical_orientation"] = errors.trajectory_error(
                job.output, det_jobs[plan.numerical_reference].output)
        det_rows.append(row)
    candidates = [r for r in det_rows if r["setting"] in plan.deterministic]
    for i in report.pareto_front(candidates, lambda r: r["cost"], lambda r: r["position"]):
        candidates[i]["pareto"] = True
    same_cutoff = [r for r in candidates if "numerical_position" in r]
    for i in report.pareto_front(same_cutoff, lambda r: r["cost"], lambda r: r["numerical_position"]):
        same_cutoff[i]["numerical_pareto"] = True

    brown_rows = []
    ref_obs = errors.brownian_observables(brown_jobs[plan.brownian_reference].output)
    num_ref = plan.brownian_numerical_reference
    num_obs = errors.brownian_observables(brown_jobs[num_ref].output)
    for s, job in brown_jobs.items():
        t = timings[job.name]
        row = {"setting": s, "timing": t, "cost": cost(t), "observed": errors.brownian_observables(job.output)}
        if s != plan.brownian_reference:
            row["compared"] = errors.compare(row["observed"], ref_obs)
        if s.cutoff == num_ref.cutoff and s != num_ref:
            row["numerical_compared"] = errors.compare(row["observed"], num_obs)
        brown_rows.append(row)

    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    commit = commit_of(os.path.join(HERE, "..", ".."))
    machine = f"{platform.node()} ({platform.machine()}, {os.cpu_count()} cores)"
    title = f"fldsim time against error: 64 dicolloids c/a=0.2, phi=0.3, FLD; {date}, commit {commit}"
    png = os.path.join(outdir, "time_vs_error.png")
    report.plot(det_rows, brown_rows, clock, png, title, plan)
    shutil.copyfile(png, os.path.join(HERE, "time_vs_error.png"))

    reference, ref_b = plan.reference, plan.brownian_reference
    md = [
        "## Time against error\n",
        f"{date}, commit {commit}, {machine}; {'quick' if quick else 'full'} plan, {len(jobs)} runs "
        f"({parallel} at a time) in {elapsed:.0f} s wall. Scene: `bench/accuracy/scene.yaml` "
        "(64 homonuclear dicolloids c/a = 0.2, phi = 0.3, FLD + repulsion C_p* = 10, one thread). "
        f"Cost = {clock} seconds of the whole `fldsim run` (start-up included); steps/s = steps / cost. "
        "Method: `bench/accuracy/README.md`.\n",
        "![time against error](accuracy/time_vs_error.png)\n",
        f"**Deterministic** (kT = 0, RK3, same start), error after strain {plan.strain:g} against "
        f"{reference.label}: RMS Lees-Edwards minimum-image centre distance and RMS rotation angle. "
        f"Second error pair: against the numerical reference {plan.numerical_reference.label} "
        "(same model, numerics tightened), for the settings at that cutoff. "
        "Pareto = not beaten in both cost and that position error by another setting.\n",
        report.deterministic_table(det_rows),
        f"**Brownian** (Pe = {10}, Euler-Maruyama with midpoint drift, noise seed 42), "
        f"{plan.brownian_duration:g} strain units averaged from {plan.brownian_start:g}, against "
        f"{ref_b.label}; value ± SE (blocking SE for eta_r and delta_theta_m, Poisson SE for g); "
        "Δ in units of the combined SE. Last column: the settings at the default cutoff against the "
        f"numerical reference {plan.brownian_numerical_reference.label} (same model), largest Δ in SE.\n",
        report.brownian_table(brown_rows),
        verdict(det_rows, brown_rows, plan.reference.cutoff) + "\n",
    ]
    with open(os.path.join(outdir, "accuracy.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(md))
    raw = {"date": date, "commit": commit, "machine": machine, "clock": clock, "plan": "quick" if quick else "full",
           "elapsed_wall_s": elapsed,
           "deterministic": [{"setting": r["setting"].__dict__, "timing": r["timing"].__dict__,
                              "position_error": r["position"], "orientation_error": r["orientation"],
                              "numerical_position_error": r.get("numerical_position"),
                              "numerical_orientation_error": r.get("numerical_orientation"),
                              "pareto": bool(r.get("pareto")),
                              "numerical_pareto": bool(r.get("numerical_pareto"))} for r in det_rows],
           "brownian": [{"setting": r["setting"].__dict__, "timing": r["timing"].__dict__,
                         "observed": r["observed"], "compared": r.get("compared"),
                         "numerical_compared": r.get("numerical_compared")} for r in brown_rows]}
    with open(os.path.join(outdir, "accuracy.json"), "w", encoding="utf-8") as f:
        json.dump(raw, f, indent=1)
    print(f"accuracy: wrote {outdir}/accuracy.md, {png} ({elapsed:.0f} s)")


if __name__ == "__main__":
    main()
