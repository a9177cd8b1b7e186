#!/usr/bin/env bash
# Fresh-machine command 1: install what is missing, build, and start the HTTP service ncpostd
# on the built-in profiles, in the foreground. The first log line is JSON and names the bound
# address ({"event":"start","listening":"127.0.0.1:8080",...}); SIGINT (Ctrl-C) or SIGTERM
# drains in-flight requests and exits 0. NCPOST_LISTEN overrides the address (port 0: any).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh build
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DNCPOST_BUILD_TESTS=OFF -DNCPOST_BUILD_BENCH=OFF
cmake --build build -j"$(nproc)" --target ncpost ncpostd
exec build/bin/ncpostd --listen "${NCPOST_LISTEN:-127.0.0.1:8080}" "$@"
