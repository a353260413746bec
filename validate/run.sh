#!/usr/bin/env bash
# make validate: long physics validations, too slow for `make test` (each states its own length).
#   bash validate/run.sh [BUILD_DIR]            every validation, in order
#   bash validate/run.sh [BUILD_DIR] NAME ...   only those named (e.g. equilibrium)
# Each validation is a function below; it prints its tables and returns non-zero if a check fails.
# Output: validate/results/<name>.txt (git-ignored), and a pass/fail line per validation.
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-build}
case $build in /*) ;; *) build=$root/$build ;; esac
shift || true
out=$root/validate/results
mkdir -p "$out"
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}

# Equilibrium (issue 11): Brownian runs (N = 125-500) against the Monte Carlo oracle of the same
# potential: g(r) bin tables, contact and cutoff ratios, Z of free-draining runs and Z_particle of
# FLD runs for spheres, c/a = 0.2 and c/a = 1, FLD at dt: auto (tests/equilibrium/
# ValidateEquilibrium.cpp; validate/README.md lists the cases). About 66 CPU minutes in all (094d505), 18 more for the two fused_phi05 cases and 28 for the two auto_*_frame_phi05 cases (7 December 2026), 38 for the three bound_* cases.
# Each case is its own process (JOBS at a time, one thread each), its tables in
# validate/results/equilibrium/CASE.txt; validate/results/equilibrium/cases.csv records every
# finished case with the commit it was built from, so an interrupted `make validate` run again
# skips the cases already done at the same commit (FRESH=1 runs them all again).
equilibrium() {
  cmake --build "$build" -j2 --target fldsim_validate_equilibrium > "$out/equilibrium.build.log" 2>&1 || {
    tail -20 "$out/equilibrium.build.log"; return 1; }
  local bin=$build/bin/fldsim_validate_equilibrium dir=$out/equilibrium jobs=${JOBS:-1}
  local commit
  commit=$(git -C "$root" rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
  git -C "$root" diff --quiet HEAD -- 2>/dev/null || commit="$commit+changes"
  mkdir -p "$dir"
  local ledger=$dir/cases.csv
  [ "${FRESH:-0}" = 1 ] && rm -f "$ledger"
  [ -f "$ledger" ] || echo "case,commit,exit,wall_s,user_s,system_s,verdict" > "$ledger"
  local cases
  mapfile -t cases < <("$bin" --list) || return 1
  local todo=() c
  for c in "${cases[@]}"; do
    if grep -q "^$c,$commit,[01]," "$ledger"; then echo "$c: done at $commit (in cases.csv), skipped"; else todo+=("$c"); fi
  done
  echo "equilibrium: ${#todo[@]} of ${#cases[@]} cases to run, $jobs at a time, commit $commit"
  run_case() {  # one case: its tables to CASE.txt, one line to the ledger when it ends by itself
    local c=$1 t0 t rc verdict
    t0=$(date +%s)
    { TIMEFORMAT='%U %S'; time "$bin" "$c" > "$dir/$c.txt" 2>&1; } 2> "$dir/$c.time"
    rc=$?
    t=$(tail -1 "$dir/$c.time")
    verdict=$(tail -1 "$dir/$c.txt")
    if ! grep -q "^$c: " <<< "$verdict"; then
      echo "$c: stopped before its verdict (see $dir/$c.txt); run again to resume"; return 1
    fi
    echo "$c,$commit,$rc,$(( $(date +%s) - t0 )),${t// /,},\"$verdict\"" >> "$ledger"
    echo "$verdict ($(( $(date +%s) - t0 )) s)"
  }
  local status=0
  for c in "${todo[@]}"; do
    while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n; done
    run_case "$c" &
  done
  wait
  echo "equilibrium at $commit (case, exit, wall s, CPU s):"
  for c in "${cases[@]}"; do
    if grep -q "^$c,$commit," "$ledger"; then
      grep "^$c,$commit," "$ledger" | tail -1 |
        awk -F, '{printf "  %-26s %s %7d %9.0f  %s\n", $1, ($3 == 0 ? "ok  " : "FAIL"), $4, $5 + $6, $7}'
    else
      printf "  %-26s not finished\n" "$c"
    fi
    grep -q "^$c,$commit,0," "$ledger" || status=1
  done
  return $status
}

all=(equilibrium)
selected=("$@")
[ ${#selected[@]} -eq 0 ] && selected=("${all[@]}")
status=0
for name in "${selected[@]}"; do
  if ! declare -F "$name" > /dev/null; then echo "validate: no validation named '$name' (have: ${all[*]})"; exit 2; fi
  echo "== validate: $name (log: validate/results/$name.txt)"
  if "$name" 2>&1 | tee "$out/$name.txt"; then echo "== $name: pass"; else echo "== $name: FAIL"; status=1; fi
done
exit $status
