# Shared by the tests/deploy scripts: start an ncpostd on an ephemeral loopback port, wait for
# its JSON start line, and fail with a message. Source it; it defines no global state beyond
# the helpers' own variables.

# Every ncpostd started here is killed when the script exits, whatever way it exits, so that a
# failed check never leaves a server holding ctest's output open.
NCPOSTD_STARTED=()
kill_started_servers() {
  local pid
  for pid in "${NCPOSTD_STARTED[@]}"; do kill -KILL "$pid" 2>/dev/null || true; done
}
trap kill_started_servers EXIT

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# start_ncpostd BINARY LOG [ARGS...]: starts BINARY on 127.0.0.1:0 in the background; sets
# NCPOSTD_PID and NCPOSTD_PORT (read from the {"event":"start","listening":...} line).
start_ncpostd() {
  local binary=$1 log=$2
  shift 2
  "$binary" --listen 127.0.0.1:0 --access-log off "$@" 2>"$log" &
  NCPOSTD_PID=$!
  NCPOSTD_STARTED+=("$NCPOSTD_PID")
  NCPOSTD_PORT=""
  local i
  for ((i = 0; i < 100; i++)); do
    NCPOSTD_PORT=$(sed -n 's/.*"listening":"127\.0\.0\.1:\([0-9]*\)".*/\1/p' "$log" | head -n1)
    [[ -n $NCPOSTD_PORT ]] && return 0
    kill -0 "$NCPOSTD_PID" 2>/dev/null || fail "ncpostd exited at start: $(cat "$log")"
    sleep 0.05
  done
  fail "ncpostd printed no start line within 5 s: $(cat "$log")"
}

# stop_ncpostd PID: SIGTERM, then wait at most 10 s; returns the exit status.
stop_ncpostd() {
  local pid=$1 i
  kill -TERM "$pid" 2>/dev/null || return 0
  for ((i = 0; i < 200; i++)); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.05
  done
  kill -0 "$pid" 2>/dev/null && { kill -KILL "$pid"; fail "ncpostd $pid did not stop within 10 s of SIGTERM"; }
  wait "$pid"
}
