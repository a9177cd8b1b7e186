#!/bin/sh
# ctest openapi_lint: lints openapi/openapi.yaml with the pinned @redocly/cli
# (tests/package.json; installed by scripts/install-deps.sh with `npm ci --prefix tests`).
# Fails on any error or warning, and checks that the linter really refuses a broken copy
# (a dangling $ref, an unknown parameter location), so that a linter that accepts
# everything cannot pass. Exit 77 (skip) only when the linter is not installed and
# NCPOST_REQUIRE_CORPUS is not 1; CI sets it, so there a missing linter fails.
set -u
root=${1:?usage: openapi_lint.sh SOURCE_DIR}
redocly="$root/tests/node_modules/.bin/redocly"
if [ ! -x "$redocly" ]; then
  if [ "${NCPOST_REQUIRE_CORPUS:-}" = 1 ]; then
    echo "FAIL: $redocly is missing (run scripts/install-deps.sh all, or npm ci --prefix tests)"
    exit 1
  fi
  echo "SKIP: the OpenAPI linter is not installed (npm ci --prefix tests)"
  exit 77
fi
# No telemetry, no update check: the test must not depend on the network.
export REDOCLY_TELEMETRY=off REDOCLY_SUPPRESS_UPDATE_NOTICE=true NO_UPDATE_NOTIFIER=1

work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT

lint() {  # lint SPEC CONFIG: exit status 0 only without errors and without warnings
  "$redocly" lint --config "$2" "$1" >"$work/out.txt" 2>&1
  status=$?
  cat "$work/out.txt"
  [ $status -eq 0 ] || return 1
  ! grep -Eq 'You have [0-9]+ warnings?' "$work/out.txt"
}

echo "== openapi/openapi.yaml"
if ! lint "$root/openapi/openapi.yaml" "$root/openapi/redocly.yaml"; then
  echo "FAIL: openapi/openapi.yaml does not lint cleanly"
  exit 1
fi

cp "$root/openapi/redocly.yaml" "$work/redocly.yaml"
# Each broken copy must be refused.
sed 's|#/components/responses/BadRequest|#/components/responses/NoSuchResponse|' \
  "$root/openapi/openapi.yaml" >"$work/dangling.yaml"
sed '0,/in: query/s//in: querystring/' "$root/openapi/openapi.yaml" >"$work/location.yaml"
for broken in dangling location; do
  if cmp -s "$root/openapi/openapi.yaml" "$work/$broken.yaml"; then
    echo "FAIL: the '$broken' mutation changed nothing; update this script"
    exit 1
  fi
  echo "== a broken copy ($broken), which must fail"
  if lint "$work/$broken.yaml" "$work/redocly.yaml"; then
    echo "FAIL: the linter accepted the broken copy '$broken'"
    exit 1
  fi
done
echo "PASS"
