# Shared by the tests/deploy scripts: start an ncpostd on an ephemeral loopback port, wait for
# its JSON start line, and fail with a message. Source it; it defines no global state beyond
# the helpers' own variables.

# Every ncpostd started here is killed when the script exits, whatever way it exits, so that a
# failed check never leaves a server holding ctest's output open.
NCPOSTD_STARTED=()
kill_started_servers() {
  local pid
  for pid in "${NCPOSTD_STARTED[@]}"; do
    kill -KILL "$pid" 2>/dev/null || continue
    wait "$pid" 2>/dev/null || true
  done
}
trap kill_started_servers EXIT

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# start_ncpostd BINARY LOG [ARGS...]: starts BINARY on 127.0.0.1:${NCPOSTD_LISTEN_PORT:-0} in the
# background; sets NCPOSTD_PID and NCPOSTD_PORT (from the {"event":"start","listening":...} line).
start_ncpostd() {
  local binary=$1 log=$2
  shift 2
  : >"$log"
  "$binary" --listen "127.0.0.1:${NCPOSTD_LISTEN_PORT:-0}" --access-log off "$@" 2>"$log" &
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

# free_port: a TCP port free on 127.0.0.1 now (nginx cannot report the port it bound for :0).
free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

# start_nginx DIR PORT BACKEND_PORT...: Debian's nginx in the foreground (as a child of this
# script) balancing 127.0.0.1:PORT over the ncpostd replicas; everything it writes stays in
# DIR. Posts are idempotent (same input, same output and ETag), so nginx may send a POST again
# to the next replica when the first refused the connection or failed before answering
# (`non_idempotent`); a response cut after it started cannot be retried. Sets NGINX_PID.
start_nginx() {
  local dir=$1 port=$2 backend
  shift 2
  mkdir -p "$dir/temp"
  {
    echo "daemon off; worker_processes 1; pid $dir/nginx.pid; error_log $dir/error.log warn;"
    echo "events { worker_connections 4096; }"
    echo "http {"
    echo "  access_log off; client_max_body_size 256m;"
    echo "  client_body_temp_path $dir/temp/body; proxy_temp_path $dir/temp/proxy;"
    echo "  fastcgi_temp_path $dir/temp/fastcgi; uwsgi_temp_path $dir/temp/uwsgi; scgi_temp_path $dir/temp/scgi;"
    echo "  upstream ncpostd {"
    for backend in "$@"; do echo "    server 127.0.0.1:$backend max_fails=1 fail_timeout=1s;"; done
    echo "    keepalive 32;"
    echo "  }"
    echo "  server {"
    echo "    listen 127.0.0.1:$port reuseport;"
    echo "    location / {"
    echo "      proxy_pass http://ncpostd; proxy_http_version 1.1; proxy_set_header Connection \"\";"
    echo "      proxy_next_upstream error timeout http_502 http_503 non_idempotent;"
    echo "      proxy_next_upstream_tries 3; proxy_connect_timeout 2s; proxy_read_timeout 60s;"
    echo "    }"
    echo "  }"
    echo "}"
  } >"$dir/nginx.conf"
  nginx -p "$dir" -c "$dir/nginx.conf" -e "$dir/error.log" &
  NGINX_PID=$!
  NCPOSTD_STARTED+=("$NGINX_PID")
  local i
  for ((i = 0; i < 100; i++)); do
    curl -fsS -o /dev/null --max-time 1 "http://127.0.0.1:$port/healthz" 2>/dev/null && return 0
    kill -0 "$NGINX_PID" 2>/dev/null || fail "nginx exited at start: $(cat "$dir/error.log")"
    sleep 0.05
  done
  fail "nginx did not answer /healthz within 5 s: $(cat "$dir/error.log")"
}
