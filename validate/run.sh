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

# Equilibrium (issue 11): Brownian runs (N = 500, 40 a^2/D0) against the Monte Carlo oracle of the
# same potential: g(r) bin tables, contact and cutoff ratios, Z of free-draining runs and Z_particle
# of FLD runs for spheres, c/a = 0.2 and c/a = 1, FLD at dt: auto (tests/equilibrium/
# ValidateEquilibrium.cpp; validate/README.md lists the cases). About 4-5 hours on one core.
equilibrium() {
  cmake --build "$build" -j2 --target fldsim_validate_equilibrium > "$out/equilibrium.build.log" 2>&1 || {
    tail -20 "$out/equilibrium.build.log"; return 1; }
  "$build/bin/fldsim_validate_equilibrium"
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
