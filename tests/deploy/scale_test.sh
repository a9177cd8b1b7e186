#!/usr/bin/env bash
# ctest deploy_scale (issue 22, part 4): three ncpostd replicas behind Debian's nginx on
# loopback, under a steady load of posts (curl, 6 in parallel), all started and stopped here.
#  - kill -9 of one replica mid-load: only requests in flight on it may fail (at most the
#    parallelism); nginx sends the rest, and posts refused by the dead replica, elsewhere;
#  - a rolling restart (SIGTERM one replica at a time, wait for its drain and exit 0, start it
#    again on its port, wait until ready) under load: no request fails.
# Every answer is checked: HTTP 200, curl exit 0, and the golden program's size. The counts are
# printed. Exit 77 (skip) without nginx, unless NCPOST_REQUIRE_CORPUS=1.
# Usage: scale_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
. "$here/lib.sh"
if ! command -v nginx >/dev/null; then
  [[ ${NCPOST_REQUIRE_CORPUS:-} == 1 ]] && fail "nginx is not installed (scripts/install-deps.sh all)"
  echo "SKIP: nginx is not installed (scripts/install-deps.sh all)"
  exit 77
fi
work=$(mktemp -d)
trap 'kill_started_servers; rm -rf "$work"' EXIT
program=$source_dir/tests/golden/trace/cases/curves.stp
expected_size=$(wc -c <"$source_dir/tests/golden/post/fanuc-0i/curves.nc")
parallel=6

replica_pids=() replica_ports=()
start_replica() {  # start_replica INDEX [PORT]
  NCPOSTD_LISTEN_PORT=${2:-0} start_ncpostd "$build/bin/ncpostd" "$work/replica$1.log" \
    --workers 1 --io-threads 1 --shutdown-timeout 5
  replica_pids[$1]=$NCPOSTD_PID
  replica_ports[$1]=$NCPOSTD_PORT
}
for i in 0 1 2; do start_replica $i; done
port=$(free_port)
start_nginx "$work/nginx" "$port" "${replica_ports[@]}"

# load_until STOP RESULTS: batches of 60 posts, 6 at a time, until the file STOP exists; one
# line per answer: "HTTP-status curl-exit size".
{
  echo "no-progress-meter"
  echo "parallel"
  echo "parallel-max = $parallel"
  echo "write-out = \"%{http_code} %{exitcode} %{size_download}\\n\""
  echo "header = \"Content-Type: application/octet-stream\""
  echo "data-binary = \"@$program\""
  echo "max-time = 20"
  for ((i = 0; i < 60; i++)); do
    echo "url = \"http://127.0.0.1:$port/v1/posts?profile=fanuc-0i\""
    echo "output = \"/dev/null\""
  done
} >"$work/batch.curl"
load_until() {
  while [[ ! -e $1 ]]; do curl --config "$work/batch.curl" >>"$2" 2>/dev/null || true; done
}
count() {  # count RESULTS -> "sent ok failed"
  awk -v size="$expected_size" '{ sent++; if ($1 == 200 && $2 == 0 && $3 == size) ok++ }
    END { printf "%d %d %d\n", sent, ok, sent - ok }' "$1"
}

# --- kill -9 of one replica mid-load --------------------------------------------------------
load_until "$work/stop1" "$work/kill.txt" &
loader=$!
sleep 1
before=$(wc -l <"$work/kill.txt")
{
  kill -KILL "${replica_pids[1]}"
  wait "${replica_pids[1]}" || true
} 2>/dev/null
sleep 2
touch "$work/stop1"
wait "$loader"
read -r sent ok failed < <(count "$work/kill.txt")
after=$((sent - before))
echo "kill -9 of replica 1 under load: sent $sent, answered 200 $ok, failed $failed ($before before the kill, $after after)"
((before >= 60)) || fail "the load had not started before the kill"
((after >= 120)) || fail "only $after posts after the kill: the survivors did not take the load"
((failed <= parallel)) || fail "$failed posts failed: more than could be in flight on the killed replica ($parallel)"

# --- rolling restart under load -------------------------------------------------------------
start_replica 1 "${replica_ports[1]}"
load_until "$work/stop2" "$work/rolling.txt" &
loader=$!
sleep 0.5
for i in 0 1 2; do
  kill -TERM "${replica_pids[$i]}"
  wait "${replica_pids[$i]}" || fail "replica $i exited with status $? after SIGTERM: $(cat "$work/replica$i.log")"
  start_replica "$i" "${replica_ports[$i]}"
  curl -fsS -o /dev/null --retry 20 --retry-connrefused --retry-delay 0 --max-time 10 \
    "http://127.0.0.1:${replica_ports[$i]}/readyz" || fail "replica $i is not ready after its restart"
  # nginx has no active health checks: a replica that refused connections stays out of the
  # rotation for fail_timeout (1 s); the next one is stopped only after it is back, as a
  # Deployment waits for readiness before it takes the next pod down.
  sleep 1.2
done
touch "$work/stop2"
wait "$loader"
read -r sent ok failed < <(count "$work/rolling.txt")
echo "rolling restart of 3 replicas under load: sent $sent, answered 200 $ok, failed $failed"
((sent >= 200)) || fail "only $sent posts during the rolling restart"
((failed == 0)) || { cat "$work/nginx/error.log" >&2; fail "$failed posts failed during the rolling restart: $(awk -v s="$expected_size" '$1 != 200 || $2 != 0 || $3 != s' "$work/rolling.txt" | sort | uniq -c)"; }
for i in 0 1 2; do stop_ncpostd "${replica_pids[$i]}" || fail "replica $i: exit status $? on SIGTERM"; done
kill -TERM "$NGINX_PID"
wait "$NGINX_PID" || true
