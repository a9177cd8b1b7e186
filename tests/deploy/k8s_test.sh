#!/usr/bin/env bash
# ctest deploy_kubernetes (issue 22, part 3): renders deploy/base, both overlays and the batch
# example with Kustomize (`kustomize build` or `kubectl kustomize`, when one is installed) and
# validates every set offline with tests/deploy/validate_k8s.mjs (Kubernetes API schemas from
# the pinned npm package kubernetes-models, plus the deployment contract). Broken copies must
# fail, so a validator that accepts everything cannot pass. The small cell's ConfigMap profile
# must post, and deploy/batch/post-folder.sh must count and fail as it says.
# Without Kustomize the resource files are validated unrendered (patches unchecked) and the test
# says so. Exit 77 (skip) when the npm tools are missing, unless NCPOST_REQUIRE_CORPUS=1.
# Usage: k8s_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
. "$here/lib.sh"
deploy=$source_dir/deploy

if [[ ! -d $source_dir/tests/node_modules/kubernetes-models ]]; then
  [[ ${NCPOST_REQUIRE_CORPUS:-} == 1 ]] && fail "tests/node_modules lacks kubernetes-models (npm ci --prefix tests)"
  echo "SKIP: kubernetes-models is not installed (npm ci --prefix tests)"
  exit 77
fi
work=$(mktemp -d)
trap 'kill_started_servers; rm -rf "$work"' EXIT
validate() { node "$here/validate_k8s.mjs" "$@"; }

render=()
if command -v kustomize >/dev/null; then
  render=(kustomize build)
elif command -v kubectl >/dev/null && kubectl kustomize --help >/dev/null 2>&1; then
  render=(kubectl kustomize)
fi
sets=(base overlays/small-cell overlays/large-site batch)
for set in "${sets[@]}"; do
  out=$work/$(basename "$set").yaml
  if ((${#render[@]})); then
    "${render[@]}" "$deploy/$set" >"$out" || fail "${render[*]} $set"
    validate "$set" "$out"
  elif [[ $set == base ]]; then
    # Unrendered: the set's own resource files (a kustomization and patches are not objects).
    mapfile -t resources < <(sed -n 's/^  - \([a-z0-9-]*\.yaml\)$/\1/p' "$deploy/$set/kustomization.yaml")
    ((${#resources[@]} == 0)) || validate "$set (unrendered)" "${resources[@]/#/$deploy/$set/}"
  fi
done
((${#render[@]})) || echo "NOTE: no kustomize or kubectl: the overlays and the batch set (generated ConfigMaps) were not rendered nor checked"

# Broken copies of the base must fail, each for its own reason.
base=$deploy/base/deployment.yaml
broken() {  # broken LABEL EXPECTED SED-EXPRESSION
  sed "$3" "$base" >"$work/broken.yaml"
  cp "$deploy"/base/{service,hpa,pdb,networkpolicy}.yaml "$work/"
  if validate "broken:$1" "$work/broken.yaml" "$work"/{service,hpa,pdb,networkpolicy}.yaml >"$work/out.txt"; then
    fail "the validator accepted a deployment with $1"
  fi
  grep -q -- "$2" "$work/out.txt" || fail "broken:$1 failed without '$2': $(cat "$work/out.txt")"
}
broken "a writable root" "readOnlyRootFilesystem" 's/readOnlyRootFilesystem: true/readOnlyRootFilesystem: false/'
broken "a string port" "schema" 's/containerPort: 8080/containerPort: eighty/'
broken "a short grace period" "terminationGracePeriodSeconds" 's/terminationGracePeriodSeconds: 35/terminationGracePeriodSeconds: 20/'
broken "a misspelt probe" "readiness probe" 's/readinessProbe:/readinesProbe:/'
broken "capabilities kept" "drop ALL" 's/drop: \["ALL"\]/drop: ["NET_RAW"]/'
broken "no liveness path" "liveness" 's|path: /healthz|path: /health|'
echo "broken copies: 6 refused"

# The small cell's ConfigMap profile, laid out as the overlay mounts it beside the built-ins.
profiles=$work/profiles
mkdir -p "$profiles"
cp -r "$source_dir/stylesheets/common" "$deploy/overlays/small-cell/profiles/cell-mill" "$profiles/"
"$build/bin/ncpost" post --profiles "$profiles" --profile cell-mill \
  "$source_dir/tests/golden/trace/cases/curves.stp" >"$work/cell.ngc" || fail "the cell-mill profile does not post"
head -n 1 "$work/cell.ngc" | grep -q '^N10 ' || fail "cell-mill output is not block-numbered: $(head -n 2 "$work/cell.ngc")"

# The batch Job's script against a real ncpostd: counts, outputs, and the exit status.
start_ncpostd "$build/bin/ncpostd" "$work/server.log"
mkdir -p "$work/in" "$work/out"
cp "$source_dir"/tests/golden/trace/cases/{curves,executables}.stp "$work/in/"
batch() { NCPOST_URL=http://127.0.0.1:$NCPOSTD_PORT NCPOST_PROFILE=fanuc-0i NCPOST_IN=$work/in \
  NCPOST_OUT=$work/out sh "$deploy/batch/post-folder.sh" >"$work/batch.txt" 2>&1; }
batch || fail "post-folder.sh failed on good programs: $(cat "$work/batch.txt")"
grep -qx 'sent 2, answered 200 2, failed 0' "$work/batch.txt" || fail "counts: $(cat "$work/batch.txt")"
cmp -s "$work/out/curves.nc" "$source_dir/tests/golden/post/fanuc-0i/curves.nc" ||
  fail "post-folder.sh wrote something else than the golden fanuc-0i/curves.nc"
cp "$source_dir/tests/golden/trace/cases/errors.stp" "$work/in/"
if batch; then fail "post-folder.sh exited 0 with a failing program: $(cat "$work/batch.txt")"; fi
grep -qx 'sent 3, answered 200 2, failed 1' "$work/batch.txt" || fail "counts: $(cat "$work/batch.txt")"
[[ ! -e $work/out/errors.nc && ! -e $work/out/errors.nc.part ]] || fail "a failed post left output"
stop_ncpostd "$NCPOSTD_PID"
echo "batch script: $(tail -n 1 "$work/batch.txt"), exit status non-zero"
