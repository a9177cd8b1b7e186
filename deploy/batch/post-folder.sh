#!/bin/sh
# Posts every program in NCPOST_IN to ncpostd (POST /v1/posts?profile=NCPOST_PROFILE) and writes
# each controller program to NCPOST_OUT with the profile's extension. Prints one line per file
# and the counts; exits 1 if any post failed (a problem+json answer, or a stream cut short:
# curl exits 18 on the missing last chunk, docs/server.md), 2 on a usage error.
# Transient failures (refused connection, 429/5xx/timeouts) are retried: posts are idempotent.
# Runs under POSIX sh with curl: the ncpostd image has both (deploy/batch/job.yaml).
set -u
url=${NCPOST_URL:?NCPOST_URL: the service, e.g. http://ncpostd}
profile=${NCPOST_PROFILE:?NCPOST_PROFILE: the profile id}
in=${NCPOST_IN:?NCPOST_IN: the folder of programs}
out=${NCPOST_OUT:?NCPOST_OUT: the folder for controller programs}
timeout=${NCPOST_POST_TIMEOUT:-600}
mkdir -p "$out" || exit 2

info=$(curl -fsS --retry 5 --retry-connrefused --max-time 30 "$url/v1/profiles/$profile") || {
  echo "cannot read profile $profile from $url" >&2
  exit 2
}
extension=$(printf '%s' "$info" | sed -n 's/.*"extension": *"\([^"]*\)".*/\1/p' | head -n 1)

sent=0 answered=0 failed=0
for program in "$in"/*; do
  [ -f "$program" ] || continue
  name=$(basename "$program")
  target=$out/${name%.*}$extension
  sent=$((sent + 1))
  status=$(curl -sS --retry 3 --retry-connrefused --retry-delay 1 --max-time "$timeout" \
    -H 'Content-Type: application/octet-stream' --data-binary "@$program" \
    -o "$target.part" -w '%{http_code}' "$url/v1/posts?profile=$profile") || status="cut($?)"
  if [ "$status" = 200 ]; then
    mv "$target.part" "$target"
    answered=$((answered + 1))
    echo "ok     $name -> $(basename "$target")"
  else
    failed=$((failed + 1))
    echo "FAILED $name: HTTP $status $(head -c 300 "$target.part" 2>/dev/null | tr '\n' ' ')"
    rm -f "$target.part"
  fi
done
echo "sent $sent, answered 200 $answered, failed $failed"
[ "$failed" -eq 0 ]
