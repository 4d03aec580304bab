#!/usr/bin/env bash
# Installs granjet's build dependencies, the Python module's and the plot scripts' from Debian
# packages (as root, idempotent) and builds it in Release under build/. Safe to run again: it
# installs only what is missing and rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake
  libeigen3-dev libboost-dev libboost-program-options-dev libhdf5-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev
  libopenmpi-dev openmpi-bin hdf5-tools
  python3-h5py python3-matplotlib python3-numpy
  pybind11-dev python3-dev python3-pytest
)
bash scripts/debian_packages.sh "${packages[@]}"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
