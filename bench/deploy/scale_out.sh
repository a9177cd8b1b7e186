#!/usr/bin/env bash
# Scale-out on loopback (issue 22, docs/benchmarks.md "Scale-out behind nginx"): 1, 2 and 3
# ncpostd replicas behind Debian's nginx (the balancer of tests/deploy), each replica one worker
# and one IO thread so that a replica is one core's worth of service, and wrk posting
# PROGRAM (default: the in-tree tests/golden/trace/cases/curves.stp) to fanuc-0i. Prints one
# line per replica count. Run by hand; uses an existing build (BUILD_DIR, default build/).
# Needs nginx and wrk (scripts/install-deps.sh all).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD_DIR=${BUILD_DIR:-build}
DURATION=${DURATION:-10s}
CONNECTIONS=${CONNECTIONS:-12}
THREADS=${THREADS:-2}
program=$(realpath "${PROGRAM:-tests/golden/trace/cases/curves.stp}")
workers=${WORKERS_PER_REPLICA:-1}
# shellcheck source=../../tests/deploy/lib.sh
. tests/deploy/lib.sh
work=$(mktemp -d)
trap 'kill_started_servers; rm -rf "$work"' EXIT

echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(git rev-parse --short HEAD 2>/dev/null || true)"
lscpu | grep -E '^(Model name|CPU\(s\))' | sed 's/^/# /'
echo "# load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# $(basename "$program"), $CONNECTIONS connections, $THREADS wrk threads, $DURATION, $workers worker(s) per replica"
for replicas in 1 2 3; do
  ports=() pids=()
  for ((i = 0; i < replicas; i++)); do
    start_ncpostd "$BUILD_DIR/bin/ncpostd" "$work/r$replicas-$i.log" --workers "$workers" --io-threads 1
    ports+=("$NCPOSTD_PORT")
    pids+=("$NCPOSTD_PID")
  done
  port=$(free_port)
  start_nginx "$work/nginx$replicas" "$port" "${ports[@]}"
  NCPOST_BENCH_FILE=$program wrk -t"$THREADS" -c"$CONNECTIONS" -d"$DURATION" --latency \
    -s bench/server/post.lua "http://127.0.0.1:$port/v1/posts?profile=fanuc-0i" >"$work/wrk.txt"
  rps=$(awk '/^Requests\/sec/{print $2}' "$work/wrk.txt")
  p50=$(awk '$1 == "50%"{print $2}' "$work/wrk.txt")
  p99=$(awk '$1 == "99%"{print $2}' "$work/wrk.txt")
  errors=$(grep -E 'Non-2xx|Socket errors' "$work/wrk.txt" | tr '\n' ' ' || true)
  echo "replicas $replicas: $rps posts/s, p50 $p50, p99 $p99 ${errors:-no errors}"
  for pid in "${pids[@]}"; do stop_ncpostd "$pid"; done
  kill -TERM "$NGINX_PID"
  wait "$NGINX_PID" || true
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
