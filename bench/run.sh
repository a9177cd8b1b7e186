#!/usr/bin/env bash
# Runs the benchmarks that docs/benchmarks.md reports, side by side with their peers, on a
# generated file of SIZE_MB (default 100). Needs a Release build in build/ and, for the peer,
# `scripts/install-deps.sh peers` before configuring. Not part of CI: it takes minutes and wants a
# quiet machine.
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-100}
corpus=${NCPOST_CORPUS:-../shared/corpus}
work=${TMPDIR:-/tmp}/ncpost-bench
mkdir -p "$work"
large=$work/large-$size.stp
[[ -f $large ]] || build/bin/make_large_stepnc "$corpus/p21/nist_toolkit_ex1E.stp" "$size" "$large"

echo "== machine"
echo "date: $(date -u +%Y-%m-%dT%H:%MZ)  cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)  cores: $(nproc)"
echo "file: $large ($(du -m "$large" | cut -f1) MiB)"

echo "== P21 reader: ncpost (5 runs) then Open CASCADE (2 runs), same file, same run"
build/bin/p21_read_bench "$large" 5
build/bin/p21_read_bench --rss "$large"
if [[ -x build/bin/peer_occt_read ]]; then
  build/bin/peer_occt_read "$large" 2
  build/bin/peer_occt_read --rss "$large"
else
  echo "peer_occt_read not built (run scripts/install-deps.sh peers, then re-configure)"
fi

echo "== P21 -> P28 writer and P28 reader"
build/bin/p28_bench "$large" 3
build/bin/p28_bench --rss "$large"

echo "== end to end: ncpost convert --to p28 --binding early (read + write), and to P21"
if command -v hyperfine >/dev/null; then
  hyperfine --warmup 1 --runs 5 --export-markdown "$work/convert.md" \
    "build/bin/ncpost convert --to p28 --binding early $large > /dev/null" \
    "build/bin/ncpost convert --to p21 $large > /dev/null"
  cat "$work/convert.md"
fi
