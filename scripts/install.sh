#!/usr/bin/env bash
# Builds ncpost and ncpostd in Release and installs them with their data under PREFIX
# (PREFIX/bin, PREFIX/share/ncpost; docs/deploy.md). docker/Dockerfile runs it; so can anyone.
# Usage: scripts/install.sh PREFIX [BUILD_DIR]   (BUILD_DIR defaults to build-install)
set -euo pipefail
cd "$(dirname "$0")/.."
prefix=${1:?usage: scripts/install.sh PREFIX [BUILD_DIR]}
build=${2:-build-install}
bash scripts/install-deps.sh build
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DNCPOST_BUILD_TESTS=OFF -DNCPOST_BUILD_BENCH=OFF \
  -DCMAKE_INSTALL_PREFIX="$prefix"
cmake --build "$build" -j"$(nproc)" --target ncpost ncpostd
cmake --install "$build" --prefix "$prefix"
