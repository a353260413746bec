#!/bin/sh
# Runs the sensitivity study's files one at a time (one thread each), skipping finished ones and
# resuming a killed run from its checkpoint. usage: run.sh BUILD_DIR [NAME ...]
# (NAME without .yaml; default: the kT = 0 runs, then the Brownian ones, as in generate.py)
set -e
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:?usage: run.sh BUILD_DIR [NAME ...]}" && pwd)
shift
out="$here/../../../results/sensitivity"
mkdir -p "$out"
names="$*"
[ -n "$names" ] || names=$(/usr/bin/python3 -c "
import sys; sys.path.insert(0, '$here'); import generate as g
print(' '.join(['nobrown-' + v for v in g.NOBROWN] + ['brownian-' + v for v in g.BROWNIAN]))")
export OMP_NUM_THREADS=1
for n in $names; do
  if [ -f "$out/$n.h5" ]; then echo "$n: done"; continue; fi
  if [ -f "$out/$n.h5.checkpoint" ]; then
    echo "$n: resuming"
    "$build/bin/fldsim" run "$here/$n.yaml" --resume "$out/$n.h5.checkpoint" >> "$out/$n.log" 2>&1
  else
    echo "$n: running"
    "$build/bin/fldsim" run "$here/$n.yaml" > "$out/$n.log" 2>&1
  fi
  grep -E '^(done|steps):' "$out/$n.log" || true
done
