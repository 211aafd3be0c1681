#!/usr/bin/env bash
# Installs the Debian packages the project builds, tests and benchmarks with.
# Library: Eigen (the matrix types), OpenBLAS (dense kernels), METIS (nested-dissection ordering).
# Tests: doctest. Benchmarks: Google Benchmark's Debian package set, zlib (gzip meshes) and
# SuiteSparse (CHOLMOD, a GPL peer used only in bench/ and test/, never by the library).
set -euo pipefail
packages=(cmake g++ make libeigen3-dev libmetis-dev libopenblas-dev doctest-dev libbenchmark-dev
          zlib1g-dev libsuitesparse-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y "${missing[@]}"
fi
