#!/usr/bin/env bash
# ctest deploy_install (issue 22, part 1): `cmake --install` into a temporary prefix, then the
# installed ncpost and ncpostd run with the source and build trees out of reach (empty tmpfs
# mounted over both in a private mount namespace) and post a program; the data folder is
# found beside the executable, or through NCPOST_DATA_DIR when the binary is moved away.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
. "$here/lib.sh"

work=$(mktemp -d)
trap 'kill_started_servers; rm -rf "$work"' EXIT
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null

for file in bin/ncpost bin/ncpostd share/ncpost/openapi.yaml share/ncpost/web/index.html \
  share/ncpost/schemas/iso14649.exp share/ncpost/stylesheets/linuxcnc/profile.json \
  share/ncpost/stylesheets/common; do
  [[ -e $prefix/$file ]] || fail "the install has no $file"
done
if links=$(find "$prefix" -type l) && [[ -n $links ]]; then
  fail "the install holds links (into the build tree?): $links"
fi
for binary in ncpost ncpostd; do
  if grep -qF "$source_dir" "$prefix/bin/$binary"; then
    fail "$binary has the source path $source_dir compiled in"
  fi
done

cp "$here/lib.sh" "$here/installed_checks.sh" "$source_dir/tests/golden/trace/cases/curves.stp" "$work/"
cp "$source_dir/tests/golden/post/linuxcnc/curves.nc" "$work/expected.nc"
cd "$work"
unset NCPOST_DATA_DIR
hide="mount -t tmpfs ncpost-hidden '$build' && mount -t tmpfs ncpost-hidden '$source_dir'"
if [[ $build == "$source_dir"/* ]]; then
  hide="mount -t tmpfs ncpost-hidden '$source_dir'"
fi
namespace=(unshare --mount)
[[ $(id -u) -eq 0 ]] || namespace=(unshare --mount --map-root-user)
if ! "${namespace[@]}" true 2>/dev/null; then
  fail "cannot make a private mount namespace (unshare --mount) to hide the source tree"
fi
"${namespace[@]}" bash -c "$hide && [ ! -e '$source_dir/CMakeLists.txt' ] && exec bash '$work/installed_checks.sh' '$prefix' '$work'"
echo "deploy_install: install into $prefix, posts from the installed CLI and server with the source tree hidden: ok"
