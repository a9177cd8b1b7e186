#!/usr/bin/env bash
# The server path of two ncpostd binaries side by side (docs/benchmarks.md, "HTTP service"):
# both run at once on free ports, and wrk runs alternate between them, ROUNDS times, so that
# both see the same machine load. Reports req/s and p50/p99 per run.
#
#   wrk_compare.sh BEFORE_NCPOSTD AFTER_NCPOSTD [ROUNDS]
#
# Loads: GET /healthz at 64 connections; POST /v1/posts?profile=linuxcnc of a tiny program
# (tests/golden/trace/cases/curves.stp: 34 canonical calls) at 16 connections; the issue's small
# post, nist_toolkit_ex1.stp to fanuc-0i, at 16 connections (NCPOST_CORPUS: the corpus).
set -euo pipefail
cd "$(dirname "$0")/../.."
before=${1:?usage: wrk_compare.sh BEFORE_NCPOSTD AFTER_NCPOSTD [ROUNDS]}
after=${2:?}
rounds=${3:-3}
duration=${DURATION:-5s}
tiny=tests/golden/trace/cases/curves.stp
small=${NCPOST_CORPUS:-../shared/corpus}/p21/nist_toolkit_ex1.stp
logs=$(mktemp -d)
pids=()
trap 'kill "${pids[@]}" 2>/dev/null || true; rm -rf "$logs"' EXIT
declare -A port
for name in before after; do
  bin=${!name}
  "$bin" --listen 127.0.0.1:0 ${NCPOSTD_ARGS:-} 2>"$logs/$name.log" &
  pids+=($!)
  for _ in $(seq 100); do
    p=$(grep -o '"listening":"127.0.0.1:[0-9]*' "$logs/$name.log" | grep -o '[0-9]*$' || true)
    [[ -n $p ]] && break
    sleep 0.05
  done
  port[$name]=$p
done
echo "# $(date -u +%Y-%m-%dT%H:%MZ), load average $(cut -d' ' -f1-3 /proc/loadavg)"
summary() {  # wrk output on stdin → one line
  awk '/Requests\/sec/ {r=$2} / 50%/ {p50=$2} / 99%/ {p99=$2} /Non-2xx/ {bad=$5}
       END {printf "req/s=%s p50=%s p99=%s%s\n", r, p50, p99, bad ? " non-2xx=" bad : ""}'
}
for round in $(seq "$rounds"); do
  for name in before after; do
    url=http://127.0.0.1:${port[$name]}
    echo "round $round $name healthz: $(wrk -t2 -c64 -d"$duration" --latency "$url/healthz" | summary)"
    echo "round $round $name tiny post: $(NCPOST_BENCH_FILE=$tiny wrk -t2 -c16 -d"$duration" \
      --latency -s bench/server/post.lua "$url/v1/posts?profile=linuxcnc" | summary)"
    echo "round $round $name ex1 post: $(NCPOST_BENCH_FILE=$small wrk -t2 -c16 -d"$duration" \
      --latency -s bench/server/post.lua "$url/v1/posts?profile=fanuc-0i" | summary)"
  done
done
