#!/bin/sh
# Time against error: `bench/accuracy/run.sh BUILD OUTDIR` writes OUTDIR/accuracy.md and
# OUTDIR/time_vs_error.png (see bench/accuracy/README.md). FLDSIM_BENCH_QUICK=1: short version.
set -e
if [ $# -ne 2 ]; then
  echo "usage: $0 BUILD OUTDIR" >&2
  exit 2
fi
mkdir -p "$2"
OMP_NUM_THREADS=1 exec /usr/bin/python3 "$(dirname "$0")/accuracy.py" "$1" "$2"
