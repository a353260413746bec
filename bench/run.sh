#!/usr/bin/env bash
# make bench: builds the benchmarks if needed, runs them and regenerates bench/RESULTS.md.
#   bash bench/run.sh [BUILD_DIR]        full set, about 4-6 minutes on 2 cores
#   FLDSIM_BENCH_QUICK=1 bash bench/run.sh [BUILD_DIR]   smoke version, about 2 minutes
# Outputs: bench/results/{step.csv, parts.json, *.md} (git-ignored) and bench/RESULTS.md (rewritten whole;
# hand-made runs worth keeping go in bench/HISTORY.md, which this script never touches).
# Every figure that is compared is a ratio of two numbers measured in this one invocation.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-build}
case $build in /*) ;; *) build=$root/$build ;; esac
out=$root/bench/results
mkdir -p "$out"
quick=${FLDSIM_BENCH_QUICK:-0}
py=/usr/bin/python3
load_at_start=$(cut -d' ' -f1-3 /proc/loadavg)

echo "== building the benchmarks in $build"
cmake --build "$build" -j"$(nproc)" --target fldsim fldsim_bench_step fldsim_bench_parts > "$out/build.log" 2>&1 || {
  tail -30 "$out/build.log"; echo "bench/run.sh: build failed (log: $out/build.log)"; exit 1; }
step=$build/bin/fldsim_bench_step
parts=$build/bin/fldsim_bench_parts

# One thread unless a case asks for more: spinning OpenMP threads on a shared machine distort
# everything. Two-thread cases spin briefly before sleeping (GOMP_SPINCOUNT=10000, what `fldsim run`
# sets): fully passive waiting makes every barrier of the level-scheduled IC(0) sweeps a sleep.
export OMP_NUM_THREADS=1
cache=$out/configs

csv=$out/step.csv
"$step" --header > "$csv"
run_case() {  # label, then key=value arguments of fldsim_bench_step
  local label=$1; shift
  local threads=1
  for a in "$@"; do case $a in threads=*) threads=${a#threads=} ;; esac; done
  local line
  if line=$(OMP_NUM_THREADS=$threads GOMP_SPINCOUNT=10000 "$step" label="$label" cache="$cache" "$@" \
            2>> "$out/step.log"); then
    echo "$line" >> "$csv"
    echo "  $line" | cut -d, -f1-15
  else
    echo "  $label: FAILED (see $out/step.log)"
  fi
}

if [ "$quick" = 1 ]; then
  s1=4; s8=2; s27=1; reps=1; pes="10"; phis="0.3 0.5"; shapes="sphere dicolloid:0.2"
else
  s1=5; s8=3; s27=2; reps=3; pes="10 1000"; phis="0.3 0.5"; shapes="sphere dicolloid:0.2 dicolloid:1"
fi

echo "== whole step, N = 1000 (ms/step, CG iterations/step, peak RSS)"
for sh in $shapes; do
  shape=${sh%%:*}; c=0.2; [ "$sh" != "$shape" ] && c=${sh#*:}
  for phi in $phis; do
    for pe in $pes; do
      for th in 1 2; do
        # Two threads at Pe = 10 only (the speed-up barely depends on Pe); spheres only when quick.
        [ $th = 2 ] && [ "$pe" != 10 ] && continue
        [ "$quick" = 1 ] && [ $th = 2 ] && [ "$shape" != sphere ] && continue
        run_case table start=mc shape=$shape c=$c n=1000 phi=$phi pe=$pe threads=$th steps=$s1 repeats=$reps
      done
    done
  done
done

echo "== scaling with N (spheres, Pe = 10, no observers; one thread, and two at N >= 8000)"
# The same work at every N: no observers (a stress sample, with its two tight probe solves, fell into
# the few timed steps of some N and not of others) and three warm-up steps (the first step sets up the
# pattern and the preconditioner's order; the next few from a lattice start are dearer than the steady
# ones: N = 64000, 669 ms/step over 2 steps, 483 over 6, 410 over 20). And the same steps at every N,
# averaged, not the fastest of several blocks: CG iterations drift as the lattice start relaxes and
# fluctuate between blocks far more for 1000 bodies than for 64000, so the fastest block of N = 1000
# was the one with the fewest iterations (phi 0.5: 47 against a mean of 55 it/step over the same
# steps), and the per-body ratio read 2.28x where the mean over steps 4-33 reads 1.4-1.8x
# (bench/README.md, "The scaling table's protocol"). The machine's noise then adds to every N; the
# PCG time per iteration column does not depend on the iteration count.
scaling_steps=30
[ "$quick" = 1 ] && scaling_steps=10
for phi in $phis; do
  sc="phi=$phi observers=none warmup=3 repeats=1 steps=$scaling_steps"
  run_case scaling n=1000 $sc
  run_case scaling n=8000 $sc
  run_case scaling n=8000 $sc threads=2
  if [ "$quick" != 1 ]; then
    run_case scaling n=27000 $sc
    run_case scaling n=27000 $sc threads=2
    # Beyond the cache: is the cost per body and iteration flat from 27000 on? (one thread only)
    run_case scaling n=64000 $sc
  fi
done

echo "== skipped work (spheres, N = 1000, phi = 0.3, Pe = 10, one thread): each pair back to back"
base="start=mc n=1000 phi=0.3 pe=10 steps=$s1 repeats=$reps dt=1e-4"
# Each pair runs on, off, off, on (ABBA): the machine's speed drifts over seconds, and the table
# takes each member's fastest run, so a drift cannot make a saving appear or vanish.
skip_pair() {  # key, then the arguments of the "on" and "off" cases separated by --
  local key=$1; shift
  local on=() off=() side=on
  for a in "$@"; do
    if [ "$a" = -- ]; then side=off; continue; fi
    if [ $side = on ]; then on+=("$a"); else off+=("$a"); fi
  done
  run_case "skip:$key:on" $base "${on[@]}"
  run_case "skip:$key:off" $base "${off[@]}"
  run_case "skip:$key:off" $base "${off[@]}"
  run_case "skip:$key:on" $base "${on[@]}"
}
skip_pair brownian  kT=1 observers=none -- kT=0 observers=none
skip_pair shear     pe=10 observers=none -- pe=0 observers=none
skip_pair stress    observers=stress1 -- observers=none
skip_pair solve     hydro=fld observers=none -- hydro=free_draining observers=none
skip_pair observers observers=all1 -- observers=all100
skip_pair rebuild   skin=0 observers=none -- skin=0.3 observers=none
skip_pair precond   observers=none "hydro_params={preconditioner: block_jacobi}" -- \
                    observers=none "hydro_params={preconditioner: incomplete_cholesky}"
skip_pair dilu      observers=none "hydro_params={preconditioner: incomplete_cholesky}" -- \
                    observers=none "hydro_params={preconditioner: eisenstat_dilu}"
# Not a skip: the bodies' numbering should not matter (IC(0) factorises in its own row order).
skip_pair order     observers=none order=shuffle -- observers=none order=cells

echo "== parts of a step (Google Benchmark)"
min_time=0.2; [ "$quick" = 1 ] && min_time=0.02
if [ -x "$parts" ]; then
  "$parts" --benchmark_min_time=$min_time --benchmark_out="$out/parts.json" --benchmark_out_format=json \
    2>> "$out/parts.log" | grep -E '^BM_|^-|^Benchmark' || echo "  fldsim_bench_parts failed (see $out/parts.log)"
else
  echo "  fldsim_bench_parts not built (Google Benchmark missing: apt-get install libbenchmark-dev)"
fi

"$py" "$root/bench/step/results_tables.py" "$csv" "$out/parts.json" > "$out/fldsim.md"

# The other benchmark sets write OUTDIR/<name>.md.
echo "== bench/accuracy"
"$root/bench/accuracy/run.sh" "$build" "$out" || echo "  bench/accuracy/run.sh failed"
# Against LAMMPS on three scenes, LAMMPS's documented settings first (bench/lammps/README.md).
echo "== bench/lammps (three scenes)"
"$root/bench/lammps/three_scenes.sh" "$build" "$out/lammps" > /dev/null && cp "$out/lammps/three_scenes.md" "$out/lammps.md" ||
  echo "  bench/lammps/three_scenes.sh failed"

{
  echo "# fldsim benchmark results"
  echo
  echo "Regenerated by \`make bench\` (bench/run.sh$([ "$quick" = 1 ] && echo ", FLDSIM_BENCH_QUICK=1 smoke run")). What each figure measures: bench/README.md."
  echo
  echo "- machine: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc --all) cores; load average (1, 5, 15 min) at the start: $load_at_start"
  echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "- commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$root" diff --quiet HEAD 2>/dev/null || echo ' (with uncommitted changes)')"
  echo "- build type: $(sed -n 's/^CMAKE_BUILD_TYPE:STRING=//p' "$build/CMakeCache.txt")"
  echo
  cat "$out/fldsim.md"
  for name in accuracy lammps; do
    [ -f "$out/$name.md" ] && { echo; cat "$out/$name.md"; }
  done
  echo
  echo "Earlier hand-made runs (single scenes, repeated turns), cited by README.md: [HISTORY.md](HISTORY.md); \`make bench\` never writes there."
} > "$root/bench/RESULTS.md"
echo "== wrote bench/RESULTS.md"
