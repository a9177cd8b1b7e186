#!/usr/bin/env bash
# ncpostd benchmarks on loopback (docs/benchmarks.md, "HTTP service"). Builds a Release tree in
# build-bench-server/ (BUILD_DIR overrides), starts ncpostd on a free port, and runs:
#   1. wrk GET /healthz
#   2. wrk POST /v1/posts?profile=fanuc-0i of nist_toolkit_ex1.stp and nist_toolkit_ex1E.stp,
#      16 connections, with latency percentiles
#   3. the batch baseline: the same posts as a loop of `ncpost post` processes
#   4. time to first byte and total time of a ~100 MB program (bench/make_large_stepnc)
# Needs wrk, python3 and the shared corpus (NCPOST_CORPUS or ../shared/corpus).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD_DIR=${BUILD_DIR:-build-bench-server}
DURATION=${DURATION:-10s}
CORPUS=${NCPOST_CORPUS:-../shared/corpus}
THREADS=${THREADS:-2}

cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DNCPOST_BUILD_TESTS=OFF \
  -DNCPOST_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD_DIR" -j2 --target ncpostd ncpost make_large_stepnc >/dev/null

echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(git rev-parse --short HEAD 2>/dev/null || true)"
lscpu | grep -E '^(Model name|CPU\(s\)|Thread|Core)' | sed 's/^/# /'

log=$(mktemp)
"$BUILD_DIR/bin/ncpostd" --listen 127.0.0.1:0 ${NCPOSTD_ARGS:-} 2>"$log" &
pid=$!
trap 'kill $pid 2>/dev/null || true; rm -f "$log"' EXIT
for _ in $(seq 100); do
  port=$(grep -o '"listening":"127.0.0.1:[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  [[ -n $port ]] && break
  sleep 0.05
done
url=http://127.0.0.1:$port

echo "## GET /healthz"
wrk -t"$THREADS" -c64 -d"$DURATION" --latency "$url/healthz" | grep -E 'Requests/sec|50%|99%|Socket'

for f in nist_toolkit_ex1.stp nist_toolkit_ex1E.stp; do
  file=$CORPUS/p21/$f
  echo "## POST /v1/posts?profile=fanuc-0i $f ($(stat -c %s "$file") bytes), 16 connections"
  curl -s -o /dev/null -w "# one request: status %{http_code}, %{size_download} bytes\n" \
    --data-binary "@$file" "$url/v1/posts?profile=fanuc-0i"
  NCPOST_BENCH_FILE=$file wrk -t"$THREADS" -c16 -d"$DURATION" --latency \
    -s bench/server/post.lua "$url/v1/posts?profile=fanuc-0i" |
    grep -E 'Requests/sec|50%|90%|99%|Non-2xx|Socket'
  echo "## batch baseline: ncpost post processes, $f"
  n=200
  start=$(date +%s.%N)
  for _ in $(seq $n); do "$BUILD_DIR/bin/ncpost" post --profile fanuc-0i "$file" >/dev/null 2>&1 || true; done
  end=$(date +%s.%N)
  python3 -c "print(f'processes/sec: {$n/($end-$start):.1f} (sequential, {$n} runs)')"
done

big=$(mktemp --suffix=.stp)
"$BUILD_DIR/bin/make_large_stepnc" "$CORPUS/p21/nist_toolkit_ex1E.stp" 100 "$big" >/dev/null
echo "## ~100 MB post ($(stat -c %s "$big") bytes), linuxcnc (the replicated ids exceed fanuc-0i's T9999)"
python3 bench/server/ttfb.py "$port" "$big" linuxcnc
rm -f "$big"
kill -TERM $pid
wait $pid || true
