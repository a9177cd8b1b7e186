#!/usr/bin/env bash
# ctest deploy_container (issue 22, part 2). There is no container engine on the build machines,
# so this checks what can be checked without one:
#  1. docker/Dockerfile's runtime stage: a numeric non-root USER, no token in ENV/ARG, a
#     HEALTHCHECK on /healthz, the entrypoint in exec form, the profile VOLUME, and every file it
#     copies from the build stage exists in an install made by `cmake --install`;
#  2. the image's run-time contract, emulated: the installed prefix at the image's path layout,
#     docker/entrypoint.sh run as uid 10001 with the root filesystem remounted read-only in a
#     private mount namespace, a tmpfs as the profile volume and a 0600 token file as the
#     secret. It serves, takes a profile PUT with the token (401 without), does not pass an
#     NCPOST_ADMIN_TOKEN from the environment on, and exits 0 on SIGTERM.
# Usage: container_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
. "$here/lib.sh"
dockerfile=$source_dir/docker/Dockerfile

# --- 1. the Dockerfile ---------------------------------------------------------------------
# The last stage, continuation lines joined.
runtime=$(sed -e ':join' -e '/\\$/N; s/\\\n[[:space:]]*/ /; t join' "$dockerfile" |
  awk '/^FROM /{stage=""} {stage = stage $0 "\n"} END{printf "%s", stage}')
user=$(sed -n 's/^USER[[:space:]]\{1,\}\([^[:space:]]*\).*/\1/p' <<<"$runtime" | tail -n1)
[[ $user =~ ^([0-9]+)(:[0-9]+)?$ ]] || fail "the runtime USER '$user' is not numeric uid[:gid]"
uid=${BASH_REMATCH[1]}
((uid != 0)) || fail "the runtime stage runs as root"
if grep -Eiq '^(ENV|ARG).*TOKEN' <<<"$runtime"; then fail "the image carries a token variable"; fi
grep -Eq '^HEALTHCHECK.*/healthz' <<<"$runtime" || fail "no HEALTHCHECK on /healthz"
entrypoint=$(sed -n 's/^ENTRYPOINT[[:space:]]*\["\([^"]*\)".*/\1/p' <<<"$runtime")
[[ -n $entrypoint ]] || fail "the ENTRYPOINT is not in exec form (SIGTERM must reach ncpostd)"
grep -Eq '^VOLUME.*/var/lib/ncpost/profiles' <<<"$runtime" || fail "no profile VOLUME"
grep -q 'scripts/install.sh /opt/ncpost' "$dockerfile" || fail "the build stage does not use scripts/install.sh"
grep -q "^COPY docker/entrypoint.sh $entrypoint\$" <<<"$runtime" || fail "the ENTRYPOINT $entrypoint is not docker/entrypoint.sh"

# Every Debian package whose library ncpostd or ncpost links must be installed by the runtime
# stage (listed, or pulled in by one listed) or be part of the debian:12 base (libc6, libgcc-s1,
# libstdc++6, as apt needs them).
package_of() {  # the package owning a library path (usrmerge: /lib and /usr/lib both tried)
  local path=$1 candidate
  for candidate in "$path" "/usr$path" "$(realpath "$path")" "*/$(basename "$path")"; do
    dpkg -S "$candidate" 2>/dev/null | head -n1 | cut -d: -f1 && return 0
  done
  return 1
}
check_runtime_packages() {
  local listed closure linked package missing=()
  listed=$(sed -n 's/.*--no-install-recommends[[:space:]]\{1,\}\([^&]*\)&&.*/\1/p' <<<"$runtime" | head -n1)
  [[ -n $listed ]] || fail "no apt-get install --no-install-recommends line in the runtime stage"
  # shellcheck disable=SC2086
  if ! closure=$(apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts \
    --no-breaks --no-replaces --no-enhances $listed 2>/dev/null | grep -v '^ ' | sed 's/:.*//' | sort -u) ||
    [[ -z $closure ]]; then
    echo "NOTE: apt-cache knows no packages (no apt lists): run-time libraries not checked"
    return 0
  fi
  linked=$(for binary in "$@"; do ldd "$binary" | awk '$3 ~ /^\// {print $3}'; done | sort -u)
  for library in $linked; do
    package=$(package_of "$library") || fail "no Debian package owns $library"
    case $package in libc6 | libgcc-s1 | libstdc++6) continue ;; esac
    grep -qx "$package" <<<"$closure" || missing+=("$package")
  done
  ((${#missing[@]} == 0)) || fail "the runtime stage does not install: $(printf '%s\n' "${missing[@]}" | sort -u | tr '\n' ' ')"
  echo "run-time libraries: $(wc -w <<<"$linked") linked, all installed by the runtime stage or the base"
}

work=$(mktemp -d)
trap 'kill_started_servers; rm -rf "$work"' EXIT
root=$work/image  # stands for the image's /
cmake --install "$build" --prefix "$root/opt/ncpost" >/dev/null
copies=0
while read -r from to; do
  [[ -e $root$from ]] || fail "the Dockerfile copies $from, which the install does not have"
  [[ $to == "$from" ]] || fail "COPY $from $to: expected the same path in both stages"
  copies=$((copies + 1))
done < <(sed -n 's/^COPY --from=build[[:space:]]\{1,\}\([^[:space:]]*\)[[:space:]]\{1,\}\([^[:space:]]*\)$/\1 \2/p' <<<"$runtime")
((copies > 0)) || fail "the runtime stage copies nothing from the build stage"
check_runtime_packages "$root/opt/ncpost/bin/ncpostd" "$root/opt/ncpost/bin/ncpost"
for file in bin/ncpostd share/ncpost/stylesheets/linuxcnc/post.xsl share/ncpost/openapi.yaml; do
  [[ -e $root/opt/ncpost/$file ]] || fail "the image would lack /opt/ncpost/$file"
done
cp "$source_dir/docker/entrypoint.sh" "$root$entrypoint"
mkdir -p "$root/profiles" "$root/secrets" "$root/logs"
printf 'container-test-token\n' >"$root/secrets/token"
chown "$uid" "$root/secrets/token"
chmod 0600 "$root/secrets/token"
chmod -R a+rX "$work"
cp "$source_dir/stylesheets/linuxcnc/post.xsl" "$work/post.xsl"
sed 's/"id": "linuxcnc"/"id": "cell-mill"/' "$source_dir/stylesheets/linuxcnc/profile.json" >"$work/profile.json"
cp "$here/lib.sh" "$here/container_checks.sh" "$source_dir/tests/golden/trace/cases/curves.stp" "$work/"

# --- 2. the run-time contract --------------------------------------------------------------
if [[ $(id -u) -ne 0 ]]; then
  [[ ${NCPOST_REQUIRE_CORPUS:-} == 1 ]] && fail "the emulation needs root (setpriv to uid $uid, mounts)"
  echo "SKIP: the image emulation needs root (setpriv to uid $uid, mounts); the Dockerfile checks passed"
  exit 77
fi
unshare --mount --propagation private bash -c "
  set -e
  mount --bind / / && mount -o remount,bind,ro / || exit 3
  # in case the temporary folder is a file system of its own (a tmpfs /tmp)
  mount --bind '$work' '$work' && mount -o remount,bind,ro '$work'
  mount -t tmpfs -o uid=$uid,gid=$uid,mode=0750 ncpost-profiles '$root/profiles'
  mount -t tmpfs -o uid=$uid,mode=0700 ncpost-logs '$root/logs'
  exec setpriv --reuid=$uid --regid=$uid --clear-groups --inh-caps=-all --bounding-set=-all \
    env -i PATH=/usr/bin:/bin NCPOST_ADMIN_TOKEN=from-the-environment \
    bash '$work/container_checks.sh' '$root' '$entrypoint' '$work'
"
echo "deploy_container: Dockerfile contract ($copies copies, USER $user) and the emulated image: ok"
