#!/usr/bin/env bash
# Regenerate fldsim's LAMMPS-parity references tests/data/lammps_lubricateU_phi*.txt: a hard-sphere
# start (make_start.py), one step of LAMMPS pair lubricateU on it (parity.lmp), and the reference
# file with LAMMPS's velocities and the check of its CG error (write_reference.py).
#
#   bench/lammps/parity/run.sh [OUTDIR]      (work files; default /tmp/fldsim-parity)
#
# Needs Debian's lammps package (lmp with pair lubricateU) and python3 with numpy. The fldsim test
# that reads the references does not need LAMMPS.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
work="${1:-/tmp/fldsim-parity}"
mkdir -p "$work"
PY=/usr/bin/python3
lmp_help="$(lmp -h 2> /dev/null || true)"
if ! grep -qw lubricateU <<< "$lmp_help"; then
  echo "run.sh: this LAMMPS ($(command -v lmp || echo none)) has no pair style lubricateU" \
    "(Debian: apt-get install lammps)" >&2
  exit 3
fi
# phi, Monte Carlo seed, flaglog (0: the squeeze's 1/h alone, file suffix _flaglog0)
for spec in "0.30 1 1" "0.45 2 1" "0.30 1 0"; do
  read -r phi seed flaglog <<< "$spec"
  name="phi$phi"
  suffix=""
  [[ "$flaglog" == 1 ]] || suffix="_flaglog$flaglog"
  "$PY" "$here/make_start.py" "$phi" "$seed" "$work/$name.data" --sweeps 2000
  lmp -in "$here/parity.lmp" -var data "$work/$name.data" -var out "$work/$name$suffix.dump" \
    -var flaglog "$flaglog" -log "$work/$name$suffix.log" -screen none -nocite
  (cd "$here" && "$PY" write_reference.py "$work/$name$suffix.dump" \
    "$root/tests/data/lammps_lubricateU_$name$suffix.txt" \
    "make_start.py $phi $seed --sweeps 2000 (N = 108 from fcc, hard-sphere MC); lmp -in parity.lmp -var flaglog $flaglog" \
    "$flaglog")
done
