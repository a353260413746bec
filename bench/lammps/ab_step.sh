#!/usr/bin/env bash
# Paired before/after timing of fldsim's step on the documented-settings scene (scene.yaml with the
# `documented` sets of run.sh: LAMMPS's forms, delta_num 0.01, the yukawa repulsion), one thread,
# runs taken in turns so that the VM's drift hits both alike.
#
#   bench/lammps/ab_step.sh BEFORE_PREFIX AFTER_PREFIX START.h5 [OUTDIR]
#
# BEFORE_PREFIX, AFTER_PREFIX: `cmake --install` prefixes of the two builds. START.h5: a start of
# 1000 spheres at phi 0.45 (run.sh writes OUTDIR/start.h5). PAIRS (5), STEPS (220: 0.022 a^2/D0),
# EVERY (stress sample period in steps, 10) from the environment. Prints each pair's ms/step (the
# run's own loop timer) and CG iterations per step, then the medians and the median paired change.
# Pause other jobs while it runs (kill -STOP); the figures in bench/README.md were taken that way.
set -euo pipefail
before=$1 after=$2 start=$3 out=${4:-$(mktemp -d)}
pairs=${PAIRS:-5} steps=${STEPS:-220} every=${EVERY:-10}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"

run() {  # run LABEL PREFIX -> "ms_per_step cg_per_step"
  OMP_NUM_THREADS=1 "$2/bin/fldsim" run "$here/scene.yaml" -o "$out/$1.h5" --overwrite \
    --set system.init.file="$start" --set run.duration="$(awk "BEGIN{print $steps * 1e-4}")" \
    --set observers.0.start=0.002 --set observers.0.every="$every" --set run.brownian_stress=midpoint \
    --set hydro.delta_num=0.01 --set hydro.conventions=lammps \
    --set "forces=[{plugin: yukawa, strength: 100, kappa: 100, cutoff: 2.5, unit: shear}]" > "$out/$1.log" 2>&1
  grep -o 'done: .*' "$out/$1.log" | sed -E 's/.*\(([0-9.]+) ms\/step, ([0-9.]+) CG.*/\1 \2/'
}

: > "$out/pairs.txt"
for p in $(seq 1 "$pairs"); do
  b=$(run "before$p" "$before")
  a=$(run "after$p" "$after")
  echo "pair $p: before $b  after $a" | tee -a "$out/pairs.txt"
done
python3 - "$out/pairs.txt" <<'PY'
import statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
b = [float(r[3]) for r in rows]; a = [float(r[6]) for r in rows]
d = statistics.median(y / x - 1 for x, y in zip(b, a))
print(f"median ms/step: before {statistics.median(b):.2f}, after {statistics.median(a):.2f}; "
      f"median paired change {100 * d:+.1f} % ({len(rows)} pairs)")
PY
