#!/usr/bin/env bash
# ncpostd benchmarks on loopback (docs/benchmarks.md, "HTTP service"). Builds a Release tree in
# build-bench-server/ (BUILD_DIR overrides), starts ncpostd on a free port, and runs:
#   1. wrk GET /healthz, in alternating rounds with bench/server/minimal_beast.cpp (a Beast
#      server that only answers: the machine's ceiling, which issue 7 states its target against)
#   2. wrk POST /v1/posts?profile=fanuc-0i of nist_toolkit_ex1.stp and nist_toolkit_ex1E.stp,
#      16 connections, with latency percentiles
#   3. the batch baseline (batch_baseline.sh): the same posts as loops of processes,
#      `ncpost trace --format xml | xsltproc plain.xsl` and `ncpost post`, 1 and 2 at a time
#   4. the server path alone: a tiny program (a few canonical calls) at 16 connections, and a
#      post that stops at once (unknown profile) through the same worker hop
#   5. time to first byte and total time of a ~100 MB program (bench/make_large_stepnc), with
#      the server's Server-Timing; with BEFORE_NCPOSTD=path, that binary and this one side by
#      side in one run (ttfb_compare.py), alternating
#   6. where the time after a large upload goes, stage by stage, outside the server
#      (upload_stages)
# Needs wrk, python3, xsltproc and the shared corpus (NCPOST_CORPUS or ../shared/corpus).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD_DIR=${BUILD_DIR:-build-bench-server}
DURATION=${DURATION:-10s}
CORPUS=${NCPOST_CORPUS:-../shared/corpus}
THREADS=${THREADS:-2}

cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DNCPOST_BUILD_TESTS=OFF \
  -DNCPOST_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD_DIR" -j2 --target ncpostd ncpost make_large_stepnc render_bench \
  upload_stages minimal_beast >/dev/null

echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(git rev-parse --short HEAD 2>/dev/null || true)"
lscpu | grep -E '^(Model name|CPU\(s\)|Thread|Core)' | sed 's/^/# /'
echo "# load average: $(cut -d' ' -f1-3 /proc/loadavg)"

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

minimal_port=$(mktemp)
"$BUILD_DIR/bin/minimal_beast" >"$minimal_port" &
minimal=$!
trap 'kill $pid $minimal 2>/dev/null || true; rm -f "$log" "$minimal_port"' EXIT
for _ in $(seq 100); do [[ -s $minimal_port ]] && break; sleep 0.05; done
for round in 1 2 3; do
  for server in minimal_beast ncpostd; do
    target=$url
    [[ $server == minimal_beast ]] && target=http://127.0.0.1:$(cat "$minimal_port")
    echo "## GET /healthz, 64 connections, round $round: $server"
    wrk -t"$THREADS" -c64 -d"$DURATION" --latency "$target/healthz" |
      grep -E 'Requests/sec|50%|99%|Socket'
  done
done
kill $minimal

for f in nist_toolkit_ex1.stp nist_toolkit_ex1E.stp; do
  file=$CORPUS/p21/$f
  echo "## POST /v1/posts?profile=fanuc-0i $f ($(stat -c %s "$file") bytes), 16 connections"
  curl -s -o /dev/null -w "# one request: status %{http_code}, %{size_download} bytes\n" \
    --data-binary "@$file" "$url/v1/posts?profile=fanuc-0i"
  NCPOST_BENCH_FILE=$file wrk -t"$THREADS" -c16 -d"$DURATION" --latency \
    -s bench/server/post.lua "$url/v1/posts?profile=fanuc-0i" |
    grep -E 'Requests/sec|50%|90%|99%|Non-2xx|Socket'
  for p in 1 2; do
    echo "## batch baseline, $f, $p at a time"
    bash bench/server/batch_baseline.sh "$BUILD_DIR/bin" "$file" fanuc-0i "${BATCH_N:-200}" "$p"
  done
done

tiny=tests/golden/trace/cases/curves.stp
echo "## the server path: POST /v1/posts?profile=linuxcnc of $tiny ($(stat -c %s "$tiny") bytes), 16 connections"
NCPOST_BENCH_FILE=$tiny wrk -t"$THREADS" -c16 -d"$DURATION" --latency \
  -s bench/server/post.lua "$url/v1/posts?profile=linuxcnc" |
  grep -E 'Requests/sec|50%|90%|99%|Non-2xx|Socket'
echo "## the server path without the engine: POST /v1/posts?profile=none (404 from the worker), 16 connections"
NCPOST_BENCH_FILE=$tiny wrk -t"$THREADS" -c16 -d"$DURATION" --latency \
  -s bench/server/post.lua "$url/v1/posts?profile=none" |
  grep -E 'Requests/sec|50%|90%|99%|Socket'

big=$(mktemp --suffix=.stp)
"$BUILD_DIR/bin/make_large_stepnc" "$CORPUS/p21/nist_toolkit_ex1E.stp" 100 "$big" >/dev/null
echo "## ~100 MB post ($(stat -c %s "$big") bytes), linuxcnc (the replicated ids exceed fanuc-0i's T9999)"
kill -TERM $pid
wait $pid || true
trap 'rm -f "$log" "$big"' EXIT
if [[ -n ${BEFORE_NCPOSTD:-} ]]; then
  python3 bench/server/ttfb_compare.py "$BEFORE_NCPOSTD" "$BUILD_DIR/bin/ncpostd" "$big" linuxcnc \
    "${FIRST_BYTE_RUNS:-7}" "${TOTAL_RUNS:-2}"
else
  "$BUILD_DIR/bin/ncpostd" --listen 127.0.0.1:0 --access-log off 2>"$log" &
  pid=$!
  trap 'kill $pid 2>/dev/null || true; rm -f "$log" "$big"' EXIT
  for _ in $(seq 100); do
    port=$(grep -o '"listening":"127.0.0.1:[0-9]*' "$log" | grep -o '[0-9]*$' || true)
    [[ -n $port ]] && break
    sleep 0.05
  done
  python3 bench/server/ttfb.py "$port" "$big" linuxcnc "${FIRST_BYTE_RUNS:-7}" --first-byte-only
  python3 bench/server/ttfb.py "$port" "$big" linuxcnc "${TOTAL_RUNS:-2}"
  kill -TERM $pid
  wait $pid || true
fi
echo "## after the upload, outside the server (median ms per stage)"
"$BUILD_DIR/bin/upload_stages" "$big" linuxcnc 3
