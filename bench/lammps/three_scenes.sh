#!/usr/bin/env bash
# fldsim against LAMMPS FLD on three scenes, one after the other (README.md, "The three
# scenes"): LAMMPS's documented settings (the headline), the paper's settings, and the original
# clamp-only scene. Writes OUTDIR/<scene>/lammps.md and OUTDIR/three_scenes.md (all three).
#
#   bench/lammps/three_scenes.sh [BUILD] [OUTDIR]     (defaults: build, bench/lammps/out)
# Environment as run.sh (STEPS, WARMUP, EVERY, REPEAT, COUNT_CG, ...).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${1:-$here/../../build}"
outdir="${2:-$here/out}"
mkdir -p "$outdir"
outdir="$(cd "$outdir" && pwd)"
for scene in documented paper clamp; do
  mkdir -p "$outdir/$scene"
  # One Monte Carlo start for all three (the first scene makes it).
  [[ -f "$outdir/documented/start.h5" ]] && export START="$outdir/documented/start.h5"
  SCENE="$scene" bash "$here/run.sh" "$build" "$outdir/$scene" > /dev/null
done
cat "$outdir"/{documented,paper,clamp}/lammps.md > "$outdir/three_scenes.md"
cat "$outdir/three_scenes.md"
