#!/usr/bin/env bash
# Issue 7's two wrk targets, round by round (docs/benchmarks.md): in each round, GET /healthz on
# minimal_beast (the machine's ceiling of the moment) and then on ncpostd, 64 connections; then
# POST /v1/posts?profile=fanuc-0i of nist_toolkit_ex1.stp on ncpostd, 16 connections. One line
# per round, so that a round's figures can be read against the minimal server's of the same
# moment: other tenants of a shared machine move all of them together.
#
#   targets.sh BIN_DIR [ROUNDS]      (BIN_DIR holds ncpostd and minimal_beast; DURATION=5s)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=${1:?usage: targets.sh BIN_DIR [ROUNDS]}
rounds=${2:-6}
duration=${DURATION:-5s}
small=${NCPOST_CORPUS:-../shared/corpus}/p21/nist_toolkit_ex1.stp
work=$(mktemp -d)
pids=()
trap 'kill "${pids[@]}" 2>/dev/null || true; rm -rf "$work"' EXIT
"$bin/ncpostd" --listen 127.0.0.1:0 ${NCPOSTD_ARGS:-} 2>"$work/ncpostd.log" &
pids+=($!)
"$bin/minimal_beast" >"$work/minimal.port" &
pids+=($!)
port=
for _ in $(seq 100); do
  port=$(grep -o '"listening":"127.0.0.1:[0-9]*' "$work/ncpostd.log" | grep -o '[0-9]*$' || true)
  [[ -n $port && -s $work/minimal.port ]] && break
  sleep 0.05
done
minimal=$(cat "$work/minimal.port")
summary() {  # wrk output on stdin → "req/s p50 p99"
  awk '/Requests\/sec/ {r=$2} / 50%/ {p50=$2} / 99%/ {p99=$2} /Non-2xx/ {bad=$5}
       END {printf "%s p50=%s p99=%s%s", r, p50, p99, bad ? " non-2xx=" bad : ""}'
}
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(git rev-parse --short HEAD 2>/dev/null || true)," \
  "load average $(cut -d' ' -f1-3 /proc/loadavg)"
for round in $(seq "$rounds"); do
  ceiling=$(wrk -t2 -c64 -d"$duration" --latency "http://127.0.0.1:$minimal/healthz" | summary)
  health=$(wrk -t2 -c64 -d"$duration" --latency "http://127.0.0.1:$port/healthz" | summary)
  posts=$(NCPOST_BENCH_FILE=$small wrk -t2 -c16 -d"$duration" --latency \
    -s bench/server/post.lua "http://127.0.0.1:$port/v1/posts?profile=fanuc-0i" | summary)
  echo "$(date -u +%H:%M:%SZ) | minimal_beast /healthz $ceiling | ncpostd /healthz $health" \
    "| ex1 to fanuc-0i $posts"
done
