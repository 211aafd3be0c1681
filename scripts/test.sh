#!/usr/bin/env bash
# Runs all tests: installs dependencies, builds everything in build/, runs the doctest suites
# through ctest, installs the library into a scratch prefix and builds a consumer project with
# find_package(UpdatableCholesky), and runs a smoke version of every benchmark.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
(cd build && ctest --output-on-failure -j2)

echo "== install + find_package consumer =="
prefix="$(pwd)/build/install-prefix"
rm -rf "$prefix" build/consumer
cmake --install build --prefix "$prefix" >/dev/null
cmake -S test/consumer -B build/consumer -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release
cmake --build build/consumer -j2
./build/consumer/consumer

echo "== benchmark smoke runs =="
for b in build/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "-- $b --smoke"
  "$b" --smoke
done
echo "all tests passed"
