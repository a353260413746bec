#!/usr/bin/env bash
# The quick study (examples/paper/quick/README.md): runs every experiment file in this folder
# that has no result yet, two at a time on one thread each, then draws the study figures into
# results/quick/figures and prints the summary table.
#
# usage: bash examples/paper/quick/run_quick_study.sh [BUILD]      (BUILD: build dir, default build)
#   JOBS=1 ...        runs one at a time (default 2)
#   NICE=5 ...        runs the simulations under `nice -n 5` (default 0)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
cd "$ROOT"
BUILD="${1:-build}"
FLDSIM="$BUILD/bin/fldsim"
JOBS="${JOBS:-2}"
NICE="${NICE:-0}"
PY=/usr/bin/python3
OUT=results/quick
LOGS="$OUT/logs"

[[ -x "$FLDSIM" ]] || { echo "run_quick_study.sh: $FLDSIM not found: build first (make build BUILD=$BUILD)" >&2; exit 1; }
"$PY" -c "import h5py, matplotlib" 2>/dev/null ||
  { echo "run_quick_study.sh: $PY lacks h5py/matplotlib (apt-get install python3-h5py python3-matplotlib)" >&2; exit 1; }
mkdir -p "$LOGS"

# Homonuclear rows first: they carry the main trends; the fused-dumbbell row last.
FILES=(examples/paper/quick/homonuclear-*.yaml examples/paper/quick/fused_dumbbell-*.yaml)
todo=()
for f in "${FILES[@]}"; do
  name="$(basename "$f" .yaml)"
  if [[ -f "$OUT/$name.h5" ]]; then echo "have  $OUT/$name.h5 (skipped)"; else todo+=("$f"); fi
done

run_one() {  # FILE: one run, log to results/quick/logs/NAME.log
  local f="$1" name
  name="$(basename "$f" .yaml)"
  local t0=$SECONDS
  if OMP_NUM_THREADS=1 nice -n "$NICE" "$FLDSIM" run "$f" -o "$OUT/$name.h5" --overwrite >"$LOGS/$name.log" 2>&1; then
    echo "done  $OUT/$name.h5 in $((SECONDS - t0)) s"
  else
    echo "FAILED $name (log: $LOGS/$name.log)"
  fi
}
export -f run_one
export FLDSIM OUT LOGS NICE

start=$SECONDS
if ((${#todo[@]})); then
  echo "running ${#todo[@]} of ${#FILES[@]} quick-study runs, $JOBS at a time (logs in $LOGS)"
  printf '%s\n' "${todo[@]}" | xargs -P "$JOBS" -I{} bash -c 'run_one "$1"' _ {}
fi
echo "simulations: $((SECONDS - start)) s wall"

results=()
for f in "${FILES[@]}"; do
  r="$OUT/$(basename "$f" .yaml).h5"
  [[ -f "$r" ]] && results+=("$r")
done
((${#results[@]})) || { echo "no results to plot" >&2; exit 1; }
"$PY" tools/plot_study.py "${results[@]}" -o "$OUT/figures" --table
echo "figures: $OUT/figures   table: $OUT/figures/study.csv"
