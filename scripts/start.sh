#!/usr/bin/env bash
# Fresh-machine command 1: install what is missing, build, and run the main job.
# Until the HTTP service exists (issue 7) the main job is `ncpost inspect` on the bundled example.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh build
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DNCPOST_BUILD_TESTS=OFF -DNCPOST_BUILD_BENCH=OFF
cmake --build build -j"$(nproc)"
build/bin/ncpost inspect --format text examples/bracket.stp
