#!/usr/bin/env bash
# Paired IC(0) (its default threshold 0.15) against Eisenstat D-ILU (default 0.3) on five scenes,
# one build, one thread, the two taken in turns (bench/README.md, "Eisenstat"):
#
#   bench/lammps/ab_preconditioner.sh FLDSIM OUTDIR START.h5 FRAME.h5
#
# FLDSIM: the fldsim executable. START.h5: run.sh's start of 1000 spheres at phi 0.45 (the three
# sphere scenes). FRAME.h5: a result file of N = 1000 fused dumbbells at phi 0.3 with a trajectory
# (its last frame starts the two fused scenes, examples/paper/paper-base.yaml at Pe 10 and 1000).
# PAIRS (5) and EVERY (stress sample period in steps, 10) from the environment. Pause other jobs.
set -uo pipefail
B=$1 OUT=$2 S=$3 T=$4; PAIRS=${PAIRS:-5}; EVERY=${EVERY:-10}
mkdir -p "$OUT"
here=$(cd "$(dirname "$0")" && pwd)
Y=$here/scene.yaml BASE=$here/../../examples/paper/paper-base.yaml
run() { # scene pc
  local s=()
  case $1 in
    documented) s=(--set hydro.delta_num=0.01 --set "forces=[{plugin: yukawa, strength: 100, kappa: 100, cutoff: 2.5, unit: shear}]");;
    paper) s=(--set "forces=[{plugin: repulsion, prefactor: 10, unit: paper}]");;
  esac
  case $1 in
    documented|paper|clamp) OMP_NUM_THREADS=1 $B run $Y -o $OUT/x.h5 --overwrite --set system.init.file=$S --set run.duration=0.022 \
      --set observers.0.start=0.002 --set observers.0.every=$EVERY --set run.brownian_stress=midpoint \
      --set hydro.conventions=lammps --set hydro.preconditioner=$2 "${s[@]}" > $OUT/x.log 2>&1;;
    fused10|fused1000) OMP_NUM_THREADS=1 $B run $BASE -o $OUT/x.h5 --overwrite --set system.shape.c=1.0 \
      --set system.init.method=file --set system.init.file=$T --set run.duration=0.2 --set "observers=[{plugin: stress, every: $EVERY}]" \
      --set flow.peclet=${1#fused} --set hydro.preconditioner=$2 > $OUT/x.log 2>&1;;
  esac
  grep -o 'done: .*' $OUT/x.log | sed -E 's/.*\(([0-9.]+) ms\/step, ([0-9.]+) CG.*/\1 \2/'
}
for scene in documented paper clamp fused10 fused1000; do
  for p in $(seq 1 $PAIRS); do
    a=$(run $scene incomplete_cholesky); b=$(run $scene eisenstat_dilu)
    echo "$scene $p ic $a dilu $b"
  done
done | tee $OUT/pairs.txt
/usr/bin/python3 - $OUT/pairs.txt <<'PY'
import statistics, sys, collections
rows = collections.defaultdict(list)
for l in open(sys.argv[1]):
    f = l.split(); rows[f[0]].append((float(f[3]), float(f[4]), float(f[6]), float(f[7])))
for s, r in rows.items():
    d = [b / a - 1 for a, _, b, _ in r]
    print(f"| {s} | {statistics.median(x[0] for x in r):.2f} ({r[0][1]:.2f} it) | {statistics.median(x[2] for x in r):.2f} ({r[0][3]:.2f} it) | {100*statistics.median(d):+.1f} % (paired: {100*min(d):+.1f} ... {100*max(d):+.1f}) |")
PY
