#!/usr/bin/env bash
# Fresh-machine command 2: install everything, build, and run every test through ctest,
# first in the Release build, then again with AddressSanitizer and UBSan.
# NCPOST_SKIP_SANITIZE=1 skips the second pass (for a quick local run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh all
jobs=$(nproc)

# Tests are switched on explicitly: scripts/start.sh configures the same build/ without them.
# Without link-time optimisation: each of the test programs would repeat it (CMakeLists.txt).
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DNCPOST_BUILD_TESTS=ON -DNCPOST_BUILD_BENCH=ON \
  -DNCPOST_LTO=OFF
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure --no-tests=error -j"$jobs")

if [[ ${NCPOST_SKIP_SANITIZE:-0} != 1 ]]; then
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DNCPOST_SANITIZE=ON -DNCPOST_BUILD_TESTS=ON \
    -DNCPOST_BUILD_BENCH=OFF
  cmake --build build-asan -j"$jobs"
  (cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
     ctest --output-on-failure --no-tests=error -j"$jobs")
fi
