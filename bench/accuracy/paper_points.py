#!/usr/bin/python3
"""CPU time per unit physical time at equal error, fixed against adaptive steps, for paper points.

usage: paper_points.py BUILD OUTDIR [POINT ...]      (default: every point; see POINTS)

For each point (N = 1000 unless FLDSIM_POINTS_COUNT is set):
  1. a start: the paper's fixed step from the hard-body Monte Carlo configuration for `settle`
     time units; its last frame is the common start of every run below;
  2. from that start, with one noise seed and one frame F (= 16 x the paper's dt), runs over the
     horizon T: fixed steps F / 2^j (run.refine j; j = 4 is the paper's dt), adaptive steps
     (dt: auto, dt_max F) at several tolerances, and a reference F / 2^r. They all follow the same
     Brownian path (docs/time_steps.md), so the difference of a run's final positions from the
     reference's is its numerical (strong) error, not noise;
  3. error = RMS over bodies of that difference (Lees-Edwards minimum image), a; cost = CPU seconds
     (user + system, wait4) of the run less those of a run of one frame (start-up), per unit of
     physical time (the run's time unit);
  4. equal error: the adaptive cost at the error of the paper's dt, interpolated log-log between
     the two adaptive runs that bracket it; the speed-up is the paper dt's cost over that.

Writes OUTDIR/paper_points.md and OUTDIR/paper_points.json; every run's files in OUTDIR/runs/.
FLDSIM_BENCH_JOBS (default 2) runs at once, each on one thread.
"""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import errors  # noqa: E402
import runner  # noqa: E402

# name: shape block, phi, Pe, hydro, the paper's dt (examples/paper/generate.py: 1e-4 for Pe < 1
# or phi >= 0.5, else 1e-3, in the paper's unit), settle time, horizon, reference refinement,
# adaptive tolerances (a).
POINTS = {
    "homonuclear-phi0.5-pe0.1": dict(shape="{plugin: dicolloid, a: 1.0, b: 1.0, c: 0.2}", phi=0.5, pe=0.1,
                                     hydro="fld", paper_dt=1e-4, settle=0.2, horizon=0.05, reference=8,
                                     tolerances=[3e-3, 1e-3, 3e-4, 1e-4]),
    "fused_dumbbell-phi0.3-pe1": dict(shape="{plugin: dicolloid, a: 1.0, b: 1.0, c: 1.0}", phi=0.3, pe=1,
                                      hydro="fld", paper_dt=1e-3, settle=0.5, horizon=0.2, reference=8,
                                      tolerances=[1e-2, 3e-3, 1e-3, 3e-4]),
    "homonuclear-phi0.3-pe1000": dict(shape="{plugin: dicolloid, a: 1.0, b: 1.0, c: 0.2}", phi=0.3, pe=1000,
                                      hydro="fld", paper_dt=1e-3, settle=1.0, horizon=0.2, reference=8,
                                      tolerances=[3e-3, 1e-3, 3e-4, 1e-4]),
    "free_draining-spheres-phi0.3-pe0": dict(shape="{plugin: sphere}", phi=0.3, pe=0, hydro="free_draining",
                                             paper_dt=1e-4, settle=0.05, horizon=0.02, reference=10,
                                             tolerances=[3e-3, 1e-3, 3e-4, 1e-4]),
}
FIXED_REFINE = [0, 1, 2, 3, 4, 5, 6]  # F / 2^j; j = 4 is the paper's dt
PAPER_REFINE = 4
SEED = 42


def scene(point, count):
    p = POINTS[point]
    return f"""system:
  shape: {p['shape']}
  count: {count}
  volume_fraction: {p['phi']}
  init: {{method: monte_carlo, seed: 1}}
flow: {{peclet: {p['pe']}}}
hydro: {{plugin: {p['hydro']}}}
forces:
  - {{plugin: repulsion, prefactor: 10, unit: paper}}
run: {{dt: {p['paper_dt']}, duration: 1, time_unit: paper, seed: {SEED}, threads: 1}}
output: unused.h5
"""


def frames(duration, frame):
    return max(1, round(duration / frame))


def job(fldsim, yaml, workdir, name, run, duration, frame, start=None):
    out = os.path.join(workdir, name + ".h5")
    args = [fldsim, "run", yaml, "-o", out, "--overwrite", "--set", f"run.duration={duration!r}",
            "--set", f"observers=[{{plugin: trajectory, every: {frames(duration, frame)}}}]"]
    for key, value in run.items():
        args += ["--set", f"run.{key}={value}"]
    if start:
        args += ["--set", "system.init.method=file", "--set", f"system.init.file={start}"]
    return runner.Job(name, args, out, out + ".log", frames(duration, frame))


def interpolate_cost(rows, error):
    """log-log interpolation of cost at `error` between the rows (error, cost) that bracket it."""
    pts = sorted((r["error"], r["cost"]) for r in rows if r["error"] > 0 and math.isfinite(r["error"]))
    for (e1, c1), (e2, c2) in zip(pts, pts[1:]):
        if e1 <= error <= e2:
            if e2 == e1:
                return min(c1, c2)
            w = math.log(error / e1) / math.log(e2 / e1)
            return math.exp(math.log(c1) + w * (math.log(c2) - math.log(c1)))
    return math.nan


def measure(point, fldsim, outdir, count, parallel):
    p = POINTS[point]
    workdir = os.path.join(outdir, "runs", point)
    os.makedirs(workdir, exist_ok=True)
    yaml = os.path.join(workdir, "scene.yaml")
    with open(yaml, "w") as f:
        f.write(scene(point, count))
    frame = p["paper_dt"] * 2 ** PAPER_REFINE
    start = os.path.join(workdir, "start.h5")
    if not os.path.exists(start):
        runner.run_all([job(fldsim, yaml, workdir, "start", {"dt": p["paper_dt"]}, p["settle"], p["paper_dt"])])
    T = p["horizon"]
    runs = {"startup": ({"dt": frame}, frame),
            "reference": ({"dt": frame, "refine": p["reference"]}, None)}
    for j in FIXED_REFINE:
        runs[f"fixed_{j}"] = ({"dt": frame, "refine": j}, frame / 2 ** j)
    for tol in p["tolerances"]:
        runs[f"auto_{tol:g}"] = ({"dt": "auto", "dt_max": frame, "tolerance": tol}, None)
    jobs = {name: job(fldsim, yaml, workdir, name, run, frame if name == "startup" else T, frame, start)
            for name, (run, _) in runs.items()}
    jobs["reference"].steps *= 2 ** p["reference"]  # the longest first
    for name in runs:  # a step the guard cannot rescue stops a run: a result of the setting, recorded
        jobs[name].may_fail = name not in ("startup", "reference")
    print(f"{point}: {len(jobs)} runs in {workdir}", flush=True)
    timings = runner.run_all(list(jobs.values()), parallel, on_done=lambda j, t: print(
        f"  {j.name}: {t.cpu:.1f} s cpu" + (f"; stopped: {t.failure}" if t.failure else ""), flush=True))
    startup = timings["startup"].cpu
    rows = []
    for name, (run, dt) in runs.items():
        if name in ("startup", "reference"):
            continue
        if timings[name].failure:
            rows.append({"name": name, "run": run, "dt": dt, "error": math.nan, "orientation_error": math.nan,
                         "cost": math.nan, "cpu": timings[name].cpu, "steps": {}, "failure": timings[name].failure})
            continue
        position, orientation = errors.trajectory_error(jobs[name].output, jobs["reference"].output)
        steps = errors.step_statistics(jobs[name].output)
        rows.append({"name": name, "run": run, "dt": dt, "error": position, "orientation_error": orientation,
                     "cost": max(timings[name].cpu - startup, 1e-9) / T, "cpu": timings[name].cpu,
                     "steps": steps})
    paper = next(r for r in rows if r["name"] == f"fixed_{PAPER_REFINE}")
    adaptive = [r for r in rows if r["name"].startswith("auto_")]
    fixed = [r for r in rows if r["name"].startswith("fixed_")]
    equal = interpolate_cost(adaptive, paper["error"])
    return {"point": point, "count": count, "frame": frame, "horizon": T, "reference_refine": p["reference"],
            "reference_cpu": timings["reference"].cpu, "startup_cpu": startup, "rows": rows,
            "paper_error": paper["error"], "paper_cost": paper["cost"], "adaptive_cost_at_paper_error": equal,
            "speedup": paper["cost"] / equal if equal > 0 else math.nan,
            "fixed_cost_at": {r["name"]: interpolate_cost(fixed, r["error"]) for r in adaptive}}


def table(result):
    lines = [f"### {result['point']} (N = {result['count']}, frame F = {result['frame']:g}, horizon "
             f"{result['horizon']:g}, reference F/2^{result['reference_refine']})\n",
             "| run | dt (mean) | error (a) | CPU s per unit time | rejected | dt 5/50/95 % |",
             "| --- | --- | --- | --- | --- | --- |"]
    for r in result["rows"]:
        s = r["steps"]
        mean_dt = s.get("dt_mean", math.nan)
        q = "/".join(f"{s.get(k, math.nan):.2g}" for k in ("dt_p05", "dt_p50", "dt_p95"))
        name = r["name"] + (" (paper dt)" if r["name"] == f"fixed_{PAPER_REFINE}" else "")
        if r.get("failure"):
            lines.append(f"| {name} | - | stopped | - | - | {r['failure'][:120]} |")
            continue
        lines.append(f"| {name} | {mean_dt:.3g} | {r['error']:.3g} | {r['cost']:.4g} | "
                     f"{int(s.get('rejected', 0))} | {q} |")
    lines.append("")
    lines.append(f"Paper dt: error {result['paper_error']:.3g} a at {result['paper_cost']:.4g} CPU s per unit time; "
                 f"adaptive at that error: {result['adaptive_cost_at_paper_error']:.4g} "
                 f"(interpolated); speed-up {result['speedup']:.2f}x.\n")
    return "\n".join(lines)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    build, outdir = (os.path.abspath(a) for a in sys.argv[1:3])
    points = sys.argv[3:] or list(POINTS)
    fldsim = os.path.join(build, "bin", "fldsim")
    count = int(os.environ.get("FLDSIM_POINTS_COUNT", "1000"))
    parallel = int(os.environ.get("FLDSIM_BENCH_JOBS", "2"))
    results = []
    for point in points:
        results.append(measure(point, fldsim, outdir, count, parallel))
        with open(os.path.join(outdir, "paper_points.json"), "w") as f:
            json.dump(results, f, indent=1)
        with open(os.path.join(outdir, "paper_points.md"), "w") as f:
            f.write("\n".join(table(r) for r in results))
        print(table(results[-1]), flush=True)


if __name__ == "__main__":
    main()
