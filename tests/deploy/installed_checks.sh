#!/usr/bin/env bash
# Run by install_test.sh inside a mount namespace where the source and build trees are empty.
# Usage: installed_checks.sh PREFIX WORK_DIR
set -euo pipefail
prefix=$1
work=$2
. "$work/lib.sh"
cd "$work"

"$prefix/bin/ncpost" profiles >profiles.txt || fail "installed ncpost profiles failed"
grep -q '^linuxcnc	' profiles.txt || fail "installed ncpost lists no built-in linuxcnc: $(cat profiles.txt)"
"$prefix/bin/ncpost" post --profile linuxcnc curves.stp >cli.ngc || fail "installed ncpost post failed"
cmp -s cli.ngc expected.nc || fail "the installed CLI post differs from tests/golden/post/linuxcnc/curves.nc"

start_ncpostd "$prefix/bin/ncpostd" server.log
base=http://127.0.0.1:$NCPOSTD_PORT
get() { curl -fsS --max-time 10 -o "$2" "$base$1" || fail "GET $1"; }
get /healthz healthz.txt
get /readyz readyz.txt
get /openapi.yaml openapi.yaml
grep -q '^openapi:' openapi.yaml || fail "/openapi.yaml is not the installed OpenAPI file"
get / index.html
grep -qi '<html' index.html || fail "/ is not the installed web front end"
get /v1/profiles profiles.json
grep -Eq '"id": *"linuxcnc"' profiles.json || fail "/v1/profiles has no built-in linuxcnc"
curl -fsS --max-time 30 --data-binary @curves.stp -H 'Content-Type: application/octet-stream' \
  "$base/v1/posts?profile=linuxcnc" >server.ngc || fail "POST /v1/posts from the installed server"
cmp -s cli.ngc server.ngc || fail "the installed server's post differs from the installed CLI's"
stop_ncpostd "$NCPOSTD_PID" || fail "ncpostd exited non-zero after SIGTERM: $(cat server.log)"

# Moved away from its data, the binary finds nothing until NCPOST_DATA_DIR names the data.
mkdir -p alone/bin
cp "$prefix/bin/ncpost" alone/bin/
alone/bin/ncpost profiles >alone.txt 2>/dev/null || true
if grep -q '^linuxcnc	' alone.txt; then
  fail "a moved ncpost still found built-in profiles (a compiled-in path?)"
fi
NCPOST_DATA_DIR=$prefix/share/ncpost alone/bin/ncpost profiles >alone.txt
grep -q '^linuxcnc	' alone.txt ||
  fail "NCPOST_DATA_DIR does not lead a moved ncpost to the data"
echo "installed CLI and server: $(wc -l <profiles.txt) profiles, post of $(wc -c <server.ngc) bytes identical"
