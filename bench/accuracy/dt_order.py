"""The observed order of the deterministic whole-scene time-step error (issue 11 part 5).

    /usr/bin/python3 bench/accuracy/dt_order.py BUILD OUTDIR [TAPER ...] [--set KEY=VALUE ...]

Runs the scene of the time-against-error harness (scene.yaml: 64 dicolloids c/a = 0.2, phi = 0.3,
FLD + repulsion) without Brownian motion (RK3, gammadot = 1) to strain 1 from the common Monte Carlo
start, at dt = 8e-3 ... 5e-4 and at the reference dt = 1.25e-4, all with CG tolerance 1e-10 (so that
the solver's error is far below the step's), for each hydro `taper` given (default: smooth none).
Prints, per taper, the RMS position and orientation errors against that taper's reference and the
observed orders log2(e(dt) / e(dt/2)). One run at a time, one thread each. `--set` passes further
overrides to every run (e.g. `--set forces=[]` to take the repulsion out).
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import accuracy  # noqa: E402
import errors  # noqa: E402
import runner  # noqa: E402

DTS = [8e-3, 4e-3, 2e-3, 1e-3, 5e-4]
REFERENCE_DT = 1.25e-4
CG_TOLERANCE = 1e-10
STRAIN = 1.0


def job(fldsim, start, workdir, taper, dt, extra, tag):
    name = f"order{tag}_{taper}_dt{dt:g}"
    out = os.path.join(workdir, name + ".h5")
    n = accuracy.steps(STRAIN, dt)
    args = [fldsim, "run", accuracy.SCENE, "-o", out, "--overwrite", "--set", "flow.brownian=false",
            "--set", f"run.duration={STRAIN!r}", "--set", "run.time_unit=strain", "--set", f"run.dt={dt!r}",
            "--set", f"hydro.tolerance={CG_TOLERANCE!r}", "--set", f"hydro.taper={taper}",
            "--set", f"observers=[{{plugin: trajectory, every: {n}}}]"] + accuracy.from_start(start)
    for e in extra:
        args += ["--set", e]
    return runner.Job(name, args, out, out + ".log", n)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    build, outdir = sys.argv[1], sys.argv[2]
    rest = sys.argv[3:]
    extra = [rest[k + 1] for k in range(len(rest) - 1) if rest[k] == "--set"]
    tapers = [a for k, a in enumerate(rest) if a != "--set" and (k == 0 or rest[k - 1] != "--set")]
    tapers = tapers or ["smooth", "none"]
    tag = "_" + "_".join("".join(c if c.isalnum() else "-" for c in e) for e in extra) if extra else ""
    fldsim = os.path.join(build, "bin", "fldsim")
    workdir = os.path.join(outdir, "order_runs")
    os.makedirs(workdir, exist_ok=True)
    runner.run_all([accuracy.start_job(fldsim, workdir)])
    start = os.path.join(workdir, "start.h5")
    lines = []
    for taper in tapers:
        jobs = {dt: job(fldsim, start, workdir, taper, dt, extra, tag) for dt in [REFERENCE_DT] + DTS}
        runner.run_all(list(jobs.values()), 1, on_done=lambda j, t: print(
            f"  {j.name}: {t.cpu:.1f} s cpu, {t.cg_per_step:.1f} CG it/step", flush=True))
        ref = jobs[REFERENCE_DT].output
        rows = [(dt,) + errors.trajectory_error(jobs[dt].output, ref) for dt in DTS]
        lines.append(f"taper: {taper} {' '.join(extra)} (reference dt {REFERENCE_DT:g}, CG tolerance "
                     f"{CG_TOLERANCE:g}, strain {STRAIN:g})")
        lines.append("| dt | position error (a) | order | orientation error (rad) | order |")
        lines.append("| --- | --- | --- | --- | --- |")
        for k, (dt, pos, ang) in enumerate(rows):
            if k == 0:
                op = oa = ""
            else:
                op = f"{math.log2(rows[k - 1][1] / pos):.2f}" if pos > 0 else "n/a"
                oa = f"{math.log2(rows[k - 1][2] / ang):.2f}" if ang > 0 else "n/a"
            lines.append(f"| {dt:g} | {pos:.3e} | {op} | {ang:.3e} | {oa} |")
        lines.append("")
        print("\n".join(lines[-len(rows) - 4:]), flush=True)
    with open(os.path.join(outdir, f"dt_order{tag}.md"), "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
