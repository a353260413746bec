#!/usr/bin/env bash
# fldsim against LAMMPS FLD (pair lubricateU + pair brownian), the same sphere scene, one thread:
# ms per step of each, their ratio, CG iterations per step and the relative viscosity each gives.
# Writes OUTDIR/lammps.md (a markdown fragment) and prints it.
#
#   bench/lammps/run.sh [BUILD] [OUTDIR]      (defaults: build, bench/lammps/out)
#
# Environment: STEPS (timed steps, 200), WARMUP (steps before timing, 20), EVERY (stress sampling
# period in steps, 1), COUNT_CG (1: count CG iterations in extra runs under gdb, 0: skip),
# COUNT_STEPS (steps of those counting runs, 50), FRESH_START (1: redo the Monte Carlo start even
# if OUTDIR/start.h5 exists; it is deterministic, so it is reused by default), REPEAT (timed runs
# of each code, taking turns; the fastest is reported, 3), PHI (volume fraction of the start and the
# fldsim scene, 0.45; give each PHI its own OUTDIR: the start is reused), BEFORE (another fldsim
# build directory, e.g. of an earlier commit: its LAMMPS-forms run is timed in the same turns and
# reported as a row "before", for before/after figures from one run; BEFORE_LABEL names it),
# BROWNIAN_STRESS (fldsim's run.brownian_stress, midpoint: LAMMPS computes no Brownian stress, and
# the midpoint estimate costs one stresslet sum per sample where random_difference, fldsim's
# default, costs two assemblies and two solves; empty: the build's default, for BEFORE builds older
# than 61a2b02, which do not know the key).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
outdir="${2:-$here/out}"
mkdir -p "$outdir"
outdir="$(cd "$outdir" && pwd)"

STEPS="${STEPS:-200}"
WARMUP="${WARMUP:-20}"
EVERY="${EVERY:-1}"
COUNT_CG="${COUNT_CG:-1}"
# fldsim run re-executes itself to set this OpenMP wait policy unless it is set; setting it here
# keeps the process under gdb and /usr/bin/time the same one.
export GOMP_SPINCOUNT="${GOMP_SPINCOUNT:-10000}"
COUNT_STEPS="${COUNT_STEPS:-50}"
FRESH_START="${FRESH_START:-0}"
REPEAT="${REPEAT:-3}"
PHI="${PHI:-0.45}"
BEFORE="${BEFORE:-}"
DT=1.0e-4   # a^2/D0, both codes
PE=10
# SCENE (README.md, "The three scenes"): the settings of both codes.
#   documented  LAMMPS's documented FLD settings: inner cutoff 2.01 a, yukawa/colloid repulsion
#               A = 100 (6 pi mu a^2 gammadot), kappa = 100/a; fldsim: delta_num 0.01 and the same
#               force law (plugin yukawa)
#   paper       the paper's: gap floor 1e-5 a, the paper's repulsion in fldsim (C_p* = 10) and in
#               LAMMPS a yukawa/colloid of the same range (kappa = 1000/a, through the paper force
#               at h = 2e-4 a; a closer fit, kappa = 6106/a, loses atoms in LAMMPS at this dt)
#   clamp       no repulsion in either code, gap floor 1e-5 a (the bench's original scene)
SCENE="${SCENE:-documented}"
BROWNIAN_STRESS="${BROWNIAN_STRESS-midpoint}"
brownian_stress_set=()
if [[ -n "$BROWNIAN_STRESS" ]]; then brownian_stress_set=(--set "run.brownian_stress=$BROWNIAN_STRESS"); fi
case "$SCENE" in
  documented)
    CUTIN=2.01; LMP_A="$(awk "BEGIN{print 100 * $PE}")"; LMP_KAPPA=100; LMP_YCUT=2.5
    scene_set=(--set hydro.delta_num=0.01
      --set "forces=[{plugin: yukawa, strength: 100, kappa: 100, cutoff: 2.5, unit: shear}]") ;;
  paper)
    CUTIN=2.00001; LMP_A=90.0; LMP_KAPPA=1000; LMP_YCUT=2.01
    scene_set=(--set "forces=[{plugin: repulsion, prefactor: 10, unit: paper}]") ;;
  clamp)
    CUTIN=2.00001; LMP_A=0; LMP_KAPPA=1; LMP_YCUT=2.5
    scene_set=() ;;
  *) echo "run.sh: SCENE=$SCENE: expected documented, paper or clamp" >&2; exit 2 ;;
esac
PY=/usr/bin/python3
export OMP_NUM_THREADS=1

fldsim="$build/bin/fldsim"
[[ -x "$fldsim" ]] || { echo "run.sh: no fldsim executable at $fldsim (build first)" >&2; exit 2; }

as_root() { if [[ $(id -u) -eq 0 ]]; then "$@"; else sudo "$@"; fi; }

# --- LAMMPS from Debian, with the FLD pair styles --------------------------------------------
if ! command -v lmp > /dev/null; then
  echo "lammps: not installed; installing Debian's package" >&2
  install=(env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends lammps)
  as_root "${install[@]}" >&2 || { as_root apt-get update >&2 && as_root "${install[@]}" >&2; }
fi
lmp_help="$(lmp -h)"
for style in lubricateU brownian; do
  if ! grep -qw -- "$style" <<< "$lmp_help"; then
    echo "run.sh: this LAMMPS ($(command -v lmp)) has no pair style $style (FLD package missing);" \
      "rebuild Debian's source (apt-get source lammps) with -DPKG_FLD=on" >&2
    exit 3
  fi
done
lmp_version="$(lmp -h | sed -n 's/^Large-scale Atomic\/Molecular Massively Parallel Simulator - //p' | head -1)"
lmp_package="$(dpkg-query -W -f='${Version}' lammps 2> /dev/null || echo unknown)"

# --- the shared start ------------------------------------------------------------------------
cd "$outdir"
rm -f lammps.failed
# START: a start file to share between scenes (three_scenes.sh), copied here.
if [[ -n "${START:-}" && ! -f start.h5 ]]; then cp "$START" start.h5; fi
if [[ "$FRESH_START" == 1 || ! -f start.h5 ]]; then
  echo "start: fldsim hard-sphere Monte Carlo, N = 1000, phi = 0.45 (a few minutes)" >&2
  "$fldsim" run "$here/start.yaml" -o "$outdir/start.h5" --overwrite --set system.volume_fraction="$PHI" \
    > start.log 2>&1 ||
    { cat start.log >&2; exit 1; }
else
  echo "start: reusing $outdir/start.h5 (FRESH_START=1 to redo it)" >&2
fi
"$PY" "$here/to_lammps_data.py" "$outdir/start.h5" "$outdir/start.data"

# run_lammps NAME WARM STEPS: one LAMMPS run under /usr/bin/time. A run that stops with an
# error (e.g. "Lost atoms": an explicit stiff repulsion at this dt) is recorded in lammps.failed,
# reported by report.py, and not repeated; fldsim is still timed.
run_lammps() {
  [[ -f lammps.failed ]] && return 0
  if ! run_lammps_once "$@"; then
    grep -h ERROR "$1.log" | head -1 > lammps.failed
    [[ -s lammps.failed ]] || echo "LAMMPS exited with an error (see $outdir/$1.log)" > lammps.failed
    echo "lammps: $(cat lammps.failed)" >&2
  fi
}
run_lammps_once() {
  /usr/bin/time -f "%U %S %e" -o "$1.time" lmp -in "$here/fld.lmp" -log "$1.log" -screen none -nocite \
    -var data "$outdir/start.data" -var warm "$2" -var steps "$3" -var dt "$DT" -var pe "$PE" \
    -var cutin "$CUTIN" -var seed 4321 -var every "$EVERY" -var A "$LMP_A" -var kappa "$LMP_KAPPA" -var ycut "$LMP_YCUT"
}

# run_fldsim NAME STEPS [--set ...]: one fldsim run under /usr/bin/time.
run_fldsim() {
  local name="$1" steps="$2" exe="$fldsim"
  shift 2
  if [[ "$name" == fldsim-before* ]]; then exe="$BEFORE/bin/fldsim"; fi
  /usr/bin/time -f "%U %S %e" -o "$name.time" "$exe" run "$here/scene.yaml" -o "$outdir/$name.h5" \
    --overwrite --set system.init.file="$outdir/start.h5" --set system.volume_fraction="$PHI" \
    --set run.duration="$("$PY" -c "print($steps * $DT)")" \
    --set "observers.0.start=$("$PY" -c "print($WARMUP * $DT)")" --set "observers.0.every=$EVERY" \
    "${brownian_stress_set[@]}" "${scene_set[@]}" "$@" > "$name.log" 2>&1 || { cat "$name.log" >&2; exit 1; }
}

# LAMMPS's exact pair forms (hydro.conventions: lammps; LammpsParityTest checks them).
lammps_forms=(--set hydro.conventions=lammps)
total=$((WARMUP + STEPS))

# Per-step CPU time = (CPU of a WARMUP + STEPS run - CPU of a WARMUP run) / STEPS: start-up and
# warm-up cancel, and CPU time, unlike wall time, does not count the time a process waits for a
# core on a shared machine. The long runs are repeated REPEAT times, the codes taking turns, and
# report.py takes the fastest (same seeds: every repeat computes the same trajectory; other jobs
# on the machine only add time).
echo "timing: warm-up runs ($WARMUP steps)" >&2
run_lammps lammps-short "$WARMUP" 0
run_fldsim fldsim-lammps-short "$WARMUP" "${lammps_forms[@]}"
run_fldsim fldsim-default-short "$WARMUP"
if [[ -n "$BEFORE" ]]; then run_fldsim fldsim-before-short "$WARMUP" "${lammps_forms[@]}"; fi
for ((r = 1; r <= REPEAT; ++r)); do
  echo "timing: repeat $r of $REPEAT: LAMMPS, fldsim (LAMMPS forms), fldsim (defaults), $total steps each" >&2
  run_lammps "lammps.$r" "$WARMUP" "$STEPS"
  run_fldsim "fldsim-lammps.$r" "$total" "${lammps_forms[@]}"
  run_fldsim "fldsim-default.$r" "$total"
  if [[ -n "$BEFORE" ]]; then run_fldsim "fldsim-before.$r" "$total" "${lammps_forms[@]}"; fi
done

# --- CG iterations: count matrix-vector products in separate runs under gdb ------------------
# LAMMPS: every CG iteration of lubricateU calls compute_RU once, plus once per solve for the
# initial residual; compute() is one step (two solves, the midpoint scheme). fldsim: one
# BlockSparseMatrix::multiply per iteration plus one per solve, BlockJacobiPCG::solve per solve.
count_calls() {  # count_calls OUT STOP sym1 sym2 ... -- command...
  # Breakpoints at the functions' own entry points (break *'sym', not by name: a name also matches
  # PLT stubs and OpenMP-outlined clones, which would count one call two or three times). With
  # STOP = main they are set once the executable's libraries are loaded; with STOP = - they are set
  # as pending breakpoints before the run (for a stripped executable such as Debian's lmp).
  local out="$1" stop="$2"
  shift 2
  local -a bps=()
  while [[ "$1" != "--" ]]; do
    if [[ "$stop" == - ]]; then bps+=(-ex "break $1"); else bps+=(-ex "break *'$1'"); fi
    bps+=(-ex "ignore \$bpnum 100000000")
    shift
  done
  shift
  local -a gdbargs=(-q -batch -ex "set breakpoint pending on" -ex "set pagination off")
  if [[ "$stop" == - ]]; then
    gdbargs+=("${bps[@]}" -ex run)
  else
    gdbargs+=(-ex "break $stop" -ex run -ex "delete" "${bps[@]}" -ex continue)
  fi
  gdb "${gdbargs[@]}" -ex "info breakpoints" --args "$@" > "$out" 2>&1 || true
}
if [[ "$COUNT_CG" == 1 ]] && command -v gdb > /dev/null; then
  echo "counting CG iterations under gdb ($COUNT_STEPS steps each)" >&2
  count_calls lammps.gdb - 'LAMMPS_NS::PairLubricateU::compute_RU()' \
    'LAMMPS_NS::PairLubricateU::compute_RU(double**)' -- \
    lmp -in "$here/fld.lmp" -log none -screen none -nocite -var data "$outdir/start.data" -var warm 0 \
    -var steps "$COUNT_STEPS" -var dt "$DT" -var pe "$PE" -var cutin "$CUTIN" -var seed 4321 -var every "$EVERY" \
    -var A "$LMP_A" -var kappa "$LMP_KAPPA" -var ycut "$LMP_YCUT"
  variants=(lammps default)
  if [[ -n "$BEFORE" ]]; then variants+=(before); fi
  for variant in "${variants[@]}"; do
    extra=()
    exe="$fldsim"
    if [[ $variant != default ]]; then extra=("${lammps_forms[@]}"); fi
    if [[ $variant == before ]]; then exe="$BEFORE/bin/fldsim"; fi
    count_calls "fldsim-$variant.gdb" main \
      'fldsim::BlockPCG::solve(fldsim::BlockSparseMatrix const&, double const*, double*, double, int)' \
      'fldsim::BlockSparseMatrix::multiply(double const*, double*) const' -- \
      "$exe" run "$here/scene.yaml" -o "$outdir/count-$variant.h5" --overwrite \
      --set system.init.file="$outdir/start.h5" --set system.volume_fraction="$PHI" --set run.duration="$("$PY" -c "print($COUNT_STEPS * $DT)")" \
      "${brownian_stress_set[@]}" "${scene_set[@]}" "${extra[@]}"
  done
fi

"$PY" "$here/report.py" --scene "$SCENE" --outdir "$outdir" --steps "$STEPS" --warmup "$WARMUP" --every "$EVERY" --repeat "$REPEAT" \
  --count-steps "$COUNT_STEPS" --dt "$DT" --pe "$PE" --phi "$PHI" --brownian-stress "$BROWNIAN_STRESS" \
  ${BEFORE:+--before "${BEFORE_LABEL:-$BEFORE}"} --lammps-version "$lmp_version ($lmp_package)" \
  > "$outdir/lammps.md"
cat "$outdir/lammps.md"
