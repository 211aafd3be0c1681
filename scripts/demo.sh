#!/usr/bin/env bash
# Runs the main demo: installs dependencies, builds in build/ and runs examples/demo (a scripted BFF
# seam-editing session, PNGs in demo-out/) on the default mesh shipped in data/ (or on the mesh
# given as the first argument; a second argument names the output folder).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2 --target demo
./build/examples/demo "$@"
