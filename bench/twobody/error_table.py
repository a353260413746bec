#!/usr/bin/python3
"""Error tables of the FLD pair's free-pair functions against exact two-sphere hydrodynamics.

  error_table.py MODEL.csv [--exact tests/data/two_sphere_exact.csv] [--only key=value ...]
                 [--summary] [--check-python]

MODEL.csv is the output of fldsim_twobody (the real plugin code, every convention). For each
free-pair function the table shows the exact value and the model's relative error (model/exact - 1;
for A the error of 1 - A, the relative normal velocity, which vanishes at contact) for each setting
of the options that function depends on; options that do not change it are merged (checked).
--only keeps the conventions with those option values; --summary adds one row per convention with
the rms relative error of every function over 2.001 <= r/a <= 2.49 (the lubricated range) and
their mean. --check-python recomputes every model value with fld_pair.py (an independent statement of the
model) and reports the largest difference."""
import argparse
import csv
import itertools
import os
import sys

import numpy as np

QUANTITIES = ["G", "H", "A", "B", "C", "Xr", "Yr"]
SHOWN = [2.001, 2.01, 2.05, 2.1, 2.2, 2.3, 2.4, 2.49, 2.5, 3.0]


def read_exact(path):
    rows = [r for r in open(path) if not r.startswith("#")]
    reader = csv.DictReader(rows)
    return {round(float(r["s"]), 6): {q: float(r[q]) for q in QUANTITIES} for r in reader}


def read_model(path):
    out = {}
    for r in csv.DictReader(open(path)):
        conv = tuple(tuple(kv.split("=")) for kv in r["convention"].split(";") if kv)
        out.setdefault(conv, {})[round(float(r["s"]), 6)] = {q: float(r[q]) for q in QUANTITIES}
    return out


def measure(q, value):
    return 1.0 - value if q == "A" else value


def relevant_axes(model, q):
    convs = list(model)
    axes = [k for k, _ in convs[0]]
    out = []
    for i, axis in enumerate(axes):
        for c1, c2 in itertools.combinations(convs, 2):
            if all(c1[j] == c2[j] for j in range(len(axes)) if j != i):
                if any(abs(model[c1][s][q] - model[c2][s][q]) > 1e-9 for s in model[c1]):
                    out.append(axis)
                    break
    return out


def groups(model, q, axes):
    seen = {}
    for conv in model:
        key = tuple((k, v) for k, v in conv if k in axes)
        if key in seen:  # merged settings must agree
            other = seen[key]
            assert all(abs(model[conv][s][q] - model[other][s][q]) < 1e-9 for s in model[conv]), (q, conv, other)
        else:
            seen[key] = conv
    return seen


def table(model, exact, q):
    axes = relevant_axes(model, q)
    grp = groups(model, q, axes)
    name = "1 - A" if q == "A" else q
    head = ["r/a", f"exact {name}"] + [", ".join(f"{k} {v}" for k, v in key) or "all conventions" for key in grp]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    stats = {key: [] for key in grp}
    for s in sorted(exact):
        ex = measure(q, exact[s][q])
        errs = {}
        for key, conv in grp.items():
            if s in model[conv]:
                errs[key] = measure(q, model[conv][s][q]) / ex - 1.0
                if s < 2.5:
                    stats[key].append(errs[key])
        if s in SHOWN:
            lines.append(f"| {s:.3f} | {ex:.4f} | " + " | ".join(f"{100 * errs[k]:+.1f} %" for k in grp) + " |")
    lines.append("| max over 2.001-2.49 | | " + " | ".join(
        f"{100 * max(abs(e) for e in stats[k]):.1f} %" for k in grp) + " |")
    lines.append("| rms over 2.001-2.49 | | " + " | ".join(
        f"{100 * np.sqrt(np.mean(np.square(stats[k]))):.1f} %" for k in grp) + " |")
    return "\n".join(lines), axes


def summary(model, exact):
    lines = ["| " + " | ".join(k for k, _ in next(iter(model))) + " | " + " | ".join(
        "1 - A" if q == "A" else q for q in QUANTITIES) + " | mean |",
        "|" + "---|" * (len(next(iter(model))) + len(QUANTITIES) + 1)]
    rows = []
    for conv, by_s in model.items():
        rms = []
        for q in QUANTITIES:
            e = [measure(q, by_s[s][q]) / measure(q, exact[s][q]) - 1 for s in by_s if s < 2.5 and s in exact]
            rms.append(100 * np.sqrt(np.mean(np.square(e))))
        rows.append((np.mean(rms), conv, rms))
    for mean, conv, rms in sorted(rows, key=lambda r: r[0]):
        lines.append("| " + " | ".join(v for _, v in conv) + " | " + " | ".join(f"{x:.1f}" for x in rms)
                     + f" | {mean:.1f} |")
    return "\n".join(lines)


def check_python(model):
    sys.path.insert(0, os.path.dirname(__file__))
    import fld_pair
    import free_pair
    worst = 0.0
    for conv, by_s in model.items():
        c = dict(conv)
        pc = {"strain_arm": c.get("strain_arm", "centre"), "lever": c.get("lever", "centre"),
              "pump": c.get("pump", "jeffrey_onishi"), "twist": c.get("twist", "true") == "true",
              "taper": c.get("taper", "none")}
        for s, vals in by_s.items():
            py = free_pair.free_pair_functions(fld_pair.model(pc), s)
            for q in QUANTITIES:
                worst = max(worst, abs(py[q] - vals[q]) / max(abs(vals[q]), 1e-3))
    return worst


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("model")
    ap.add_argument("--exact", default=os.path.join(os.path.dirname(__file__), "../../tests/data/two_sphere_exact.csv"))
    ap.add_argument("--check-python", action="store_true")
    ap.add_argument("--summary", action="store_true")
    ap.add_argument("--only", nargs="*", default=[])
    args = ap.parse_args()
    exact = read_exact(args.exact)
    model = read_model(args.model)
    keep = [tuple(kv.split("=")) for kv in args.only]
    model = {c: v for c, v in model.items() if all(kv in c for kv in keep)}
    for q in QUANTITIES:
        text, axes = table(model, exact, q)
        print(f"\n#### {'1 - A' if q == 'A' else q} (depends on: {', '.join(axes) or 'none of the options'})\n")
        print(text)
    if args.summary:
        print("\n#### rms relative error (%) over 2.001 <= r/a <= 2.49, best first\n")
        print(summary(model, exact))
    if args.check_python:
        print(f"\nfld_pair.py (independent Python statement of the model) against the plugin code: largest "
              f"relative difference {check_python(model):.1e}")


if __name__ == "__main__":
    main()
