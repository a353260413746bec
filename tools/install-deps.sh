#!/usr/bin/env bash
# Installs the Debian 12 packages fldsim needs, only those missing. Debian packages only.
set -euo pipefail
packages=(cmake g++ make libeigen3-dev libboost-dev libboost-filesystem-dev libyaml-cpp-dev libhdf5-dev
          hdf5-tools libgtest-dev libgmock-dev libbenchmark-dev python3 python3-numpy python3-matplotlib
          python3-h5py python3-dev pybind11-dev python3-pybind11 python3-gsd python3-mdanalysis
          libopenmpi-dev openmpi-bin)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "fldsim: installing missing Debian packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
