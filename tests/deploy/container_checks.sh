#!/usr/bin/env bash
# Run by container_test.sh as the image's uid, with / read-only. Usage: ROOT ENTRYPOINT WORK
set -euo pipefail
root=$1
entrypoint=$2
work=$3
. "$work/lib.sh"

if touch "$root/opt/ncpost/probe" 2>/dev/null || touch /probe 2>/dev/null; then
  fail "the root filesystem is writable in the emulation"
fi
export NCPOST_PREFIX=$root/opt/ncpost NCPOST_ADMIN_TOKEN_FILE=$root/secrets/token \
  NCPOST_PROFILES_DIR=$root/profiles NCPOST_LISTEN=127.0.0.1:0 NCPOST_SHUTDOWN_TIMEOUT=5
log=$root/logs/server.log
start_ncpostd "$root$entrypoint" "$log"
pid=$NCPOSTD_PID
[[ $(readlink "/proc/$pid/exe") == "$root/opt/ncpost/bin/ncpostd" ]] ||
  fail "the entrypoint did not exec ncpostd (SIGTERM would hit a shell)"
[[ $(awk '/^Uid:/{print $2}' "/proc/$pid/status") == "$(id -u)" ]] || fail "ncpostd changed uid"
if tr '\0' '\n' <"/proc/$pid/environ" | grep -q '^NCPOST_ADMIN_TOKEN='; then
  fail "the entrypoint passed NCPOST_ADMIN_TOKEN from the environment to ncpostd"
fi
base=http://127.0.0.1:$NCPOSTD_PORT
out=$root/logs/out
code() { curl -sS --max-time 10 -o "$out" -w '%{http_code}' "$@"; }
[[ $(code "$base/healthz") == 200 ]] || fail "/healthz"
[[ $(code "$base/readyz") == 200 ]] || fail "/readyz"
put=(-X PUT -F "profile=<$work/profile.json" -F "stylesheet=<$work/post.xsl" "$base/v1/profiles/cell-mill")
status=$(code "${put[@]}")
[[ $status == 401 ]] || fail "PUT without the token answered $status, not 401"
status=$(code -H "Authorization: Bearer container-test-token" "${put[@]}")
[[ $status == 201 ]] || fail "PUT with the secret file's token answered $status: $(cat "$out")"
[[ -e $root/profiles/cell-mill ]] || fail "the profile was not written to the volume"
status=$(code --data-binary "@$work/curves.stp" "$base/v1/posts?profile=cell-mill")
[[ $status == 200 ]] || fail "POST with the profile from the volume answered $status: $(cat "$out")"
grep -q 'M2\|M30' "$out" || fail "the post from the volume's profile has no program end"
stop_ncpostd "$pid" || fail "ncpostd exited non-zero on SIGTERM: $(cat "$log")"
echo "emulated image: uid $(id -u), read-only /, profile PUT to the volume, SIGTERM exit 0"
