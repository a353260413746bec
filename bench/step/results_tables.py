"""Markdown tables for bench/RESULTS.md from fldsim_bench_step's CSV and fldsim_bench_parts'
Google Benchmark JSON:  results_tables.py STEP.csv PARTS.json > fldsim.md"""
import csv
import json
import os
import sys


def f(x, digits=1):
    return f"{x:.{digits}f}"


def shape_name(r):
    if r["shape"] == "sphere":
        return "sphere"
    return "dicolloid c/a=" + r["c"]


def step_tables(rows):
    out = []
    table = [r for r in rows if r["label"] == "table"]
    if table:
        out += ["## Whole step, N = 1000 (FLD + repulsion C_p* = 10, Euler-Maruyama + midpoint drift)", "",
                "dt = 1e-3 (paper unit: 1/gammadot); observers as in examples/quickstart.yaml (orientation/100, "
                "pair_distribution/200, stress/20). CG it/step counts both solves of the midpoint step. "
                "CPU ms/step is the process CPU time (the steady figure on a loaded machine); wall ms/step is inflated "
                "by the other jobs sharing the 2 cores. 2-thread speed-up = wall ms/step on 1 thread / wall ms/step on "
                "2 threads (2 threads with GOMP_SPINCOUNT=10000, as `fldsim run` sets it).", "",
                "| bodies | phi | Pe | CPU ms/step (1 thread) | wall ms/step (1 thread) | wall ms/step (2 threads) | "
                "2-thread speed-up | CG it/step | lub. pairs | peak RSS MB |",
                "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        keys = []
        for r in table:
            k = (shape_name(r), r["phi"], r["pe"])
            if k not in keys:
                keys.append(k)
        for k in keys:
            one = [r for r in table if (shape_name(r), r["phi"], r["pe"]) == k and r["threads"] == "1"]
            two = [r for r in table if (shape_name(r), r["phi"], r["pe"]) == k and r["threads"] == "2"]
            r1 = one[0] if one else None
            r2 = two[0] if two else None
            ms1 = float(r1["ms_per_step"]) if r1 else None
            ms2 = float(r2["ms_per_step"]) if r2 else None
            speed = f(ms1 / ms2, 2) if ms1 and ms2 else "-"
            ref = r1 or r2
            cpu1 = f(float(r1["cpu_ms_per_step"])) if r1 else "-"
            out.append(f"| {k[0]} | {k[1]} | {k[2]} | {cpu1} | {f(ms1) if ms1 else '-'} | {f(ms2) if ms2 else '-'} | {speed} | "
                       f"{ref['cg_per_step']} | {ref['pairs']} | {ref['rss_mb']} |")
        out += ["", "### Where a step's time goes (one thread, wall ms/step and share of the step)", "",
                "| bodies | phi | Pe | step | assembly | Brownian forces | PCG solves | observers | "
                "neighbours + forces + moves |", "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        for r in table:
            if r["threads"] != "1":
                continue
            tot = float(r["ms_per_step"])
            cells = []
            for c in ("assemble_ms", "brownian_ms", "solve_ms", "observers_ms", "rest_ms"):
                v = float(r[c])
                cells.append(f"{f(v)} ({100 * v / tot:.0f} %)")
            out.append(f"| {shape_name(r)} | {r['phi']} | {r['pe']} | {f(tot)} | " + " | ".join(cells) + " |")
        out.append("")

    scaling = [r for r in rows if r["label"] == "scaling"]
    if scaling:
        out += ["## Scaling with N (spheres, Pe = 10, no observers)", "",
                "Lattice start + 50 MC sweeps for every N (see README); no observers, three warm-up steps and "
                "the same timed steps (4-33; 4-13 in the quick plan) at every N, so that every N times the same "
                "work. CPU time on one thread, the mean over those steps (not the fastest of several blocks: "
                "that picked the block with the fewest CG iterations, which at N = 1000 fluctuate most; "
                "bench/README.md, \"The scaling table's protocol\"); the 2-thread "
                "speed-up is wall ms/step on 1 thread / wall ms/step on 2 threads, measured back to back. "
                "PCG per iteration = time in the PCG solves / CG iterations, per 1000 bodies: the cost of one "
                "iteration, apart from how many a step needs.", "",
                "| phi | N | steps timed | CPU ms/step | CPU ms/step per 1000 bodies | relative to N = 1000 | CG it/step | "
                "PCG ms per iteration per 1000 bodies | relative to N = 1000 | "
                "peak RSS MB | wall ms/step (1 thread) | wall ms/step (2 threads) | 2-thread speed-up |",
                "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        for phi in sorted({r["phi"] for r in scaling}):
            one = sorted([r for r in scaling if r["phi"] == phi and r["threads"] == "1"], key=lambda r: int(r["n"]))
            two = {r["n"]: r for r in scaling if r["phi"] == phi and r["threads"] == "2"}
            if not one:
                continue
            base = float(one[0]["cpu_ms_per_step"]) / int(one[0]["n"]) * 1000

            def per_iteration(r):
                return float(r["solve_ms"]) / max(float(r["cg_per_step"]), 1e-9) / int(r["n"]) * 1000

            base_it = per_iteration(one[0])
            for r in one:
                per = float(r["cpu_ms_per_step"]) / int(r["n"]) * 1000
                it = per_iteration(r)
                w1 = float(r["ms_per_step"])
                r2 = two.get(r["n"])
                w2 = f(float(r2["ms_per_step"])) if r2 else "-"
                speed = f(w1 / float(r2["ms_per_step"]), 2) if r2 else "-"
                out.append(f"| {phi} | {r['n']} | {r['steps']} | {f(float(r['cpu_ms_per_step']))} | {f(per, 2)} | "
                           f"{f(per / base, 2)} | {r['cg_per_step']} | {f(it, 3)} | {f(it / base_it, 2)} | "
                           f"{r['rss_mb']} | {f(w1)} | {w2} | {speed} |")
        out.append("")

    skips = [r for r in rows if r["label"].startswith("skip:")]
    if skips:
        what = {
            "brownian": ("kT > 0 vs kT = 0", "no Brownian forces, no midpoint drift stage"),
            "shear": ("Pe = 10 vs Pe = 0", "no R_FE:E_inf (strain coupling)"),
            "stress": ("stress observer every step vs none", "no stresslets, no virial"),
            "solve": ("fld vs free_draining", "no lubrication, no linear solve (6x6 per body)"),
            "observers": ("4 observers every step vs every 100", "observers only when due"),
            "rebuild": ("skin 0 vs skin 0.3", "neighbour rebuilds only when needed"),
            "precond": ("block Jacobi vs IC(0) (fld default)", "CG iterations saved by the IC(0) preconditioner"),
            "dilu": ("IC(0) vs D-ILU with Eisenstat's trick (an option)", "what the option saves (no product with R in an iteration)"),
            "order": ("bodies numbered at random vs along a Z-order curve", "nothing: IC(0) factorises in its own (reverse Cuthill-McKee) row order, so the ratio should be near 1 (the numbering still breaks the order's ties)"),
        }
        out += ["## What skipping saves (spheres, N = 1000, phi = 0.3, one thread, dt = 1e-4 a^2/D0)", "",
                "Each pair ran on, off, off, on; ratio = fastest CPU ms/step with the work / fastest CPU ms/step "
                "without it.", "",
                "| comparison | skipped work | CPU ms/step with | CPU ms/step without | ratio | CG it/step with / without |",
                "| --- | --- | --- | --- | --- | --- |"]
        for key, (name, note) in what.items():
            on = [r for r in skips if r["label"] == f"skip:{key}:on"]
            off = [r for r in skips if r["label"] == f"skip:{key}:off"]
            if not on or not off:
                continue
            # Fastest of each member's runs (run.sh runs them on, off, off, on).
            on_best = min(on, key=lambda r: float(r["cpu_ms_per_step"]))
            off_best = min(off, key=lambda r: float(r["cpu_ms_per_step"]))
            a, b = float(on_best["cpu_ms_per_step"]), float(off_best["cpu_ms_per_step"])
            out.append(f"| {name} | {note} | {f(a)} | {f(b)} | {f(a / b, 2)} | "
                       f"{on_best['cg_per_step']} / {off_best['cg_per_step']} |")
        out.append("")
    return out


def parts_table(path):
    if not os.path.exists(path):
        return []
    data = json.load(open(path))
    results = {}
    labels = []
    order = []
    barrier = None
    for b in data.get("benchmarks", []):
        name, _, arg = b["name"].partition("/")
        if name.startswith("BM_OmpBarrier"):
            # real_time per iteration of `barriers` barriers, in the benchmark's time unit
            scale_us = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}[b.get("time_unit", "ns")]
            barrier = b["real_time"] * scale_us / b.get("barriers", 1000)
            continue
        if name not in order:
            order.append(name)
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b.get("time_unit", "ns")]
        extra = ""
        if "cg_iterations" in b:
            extra = f" ({b['cg_iterations']:.0f} it)"
        results[(name, arg)] = f"{b['cpu_time'] * scale:.3g}{extra}"
        if arg not in labels:
            labels.append(arg)
    names = {lab: lab for lab in labels}
    for b in data.get("benchmarks", []):
        _, _, arg = b["name"].partition("/")
        if b.get("label"):
            names[arg] = b["label"]
    out = ["## Parts of a step (Google Benchmark, N = 1000, Pe = 10, one thread, CPU ms per call)", "",
           "Homonuclear dicolloids c/a = 0.2. A step calls neighbour refresh, forces, assembly and solve twice "
           "(base + midpoint), Brownian forces once. PCG warm: started from the solution for other noise.", "",
           "| part | " + " | ".join(names[a] for a in labels) + " |",
           "| --- |" + " --- |" * len(labels)]
    for name in order:
        out.append(f"| {name[3:]} | " + " | ".join(results.get((name, a), "-") for a in labels) + " |")
    out.append("")
    if barrier is not None:
        out += [f"One OpenMP barrier with two threads (OmpBarrier, wall time): {barrier:.2f} us. A multi-threaded "
                "step synchronises about ten times per CG iteration (parallel loops) and waits wherever an IC(0) "
                "dependency crosses threads; where this is above a few tenths of a microsecond, a second thread "
                "does not pay at N = 1000.", ""]
    return out


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    lines = step_tables(rows) + parts_table(sys.argv[2])
    print("\n".join(lines))


if __name__ == "__main__":
    main()
