#!/usr/bin/env bash
# Installs every Debian 12 package that ncpost builds, tests and benchmarks with.
# Called by the README's two commands, by .ci/run and by docker/Dockerfile, so that a fresh
# machine and CI install exactly the same set. Safe to run again: it installs only what is missing.
set -euo pipefail

build_packages=(
  build-essential cmake ninja-build pkg-config git ca-certificates curl
  libboost-dev libboost-system-dev            # Asio + Beast 1.74 (header-only, system for errors)
  libxml2-dev libxslt1-dev                    # libxml2, libxslt and libexslt
  nlohmann-json3-dev libspdlog-dev libfmt-dev
  libpolyclipping-dev                         # Clipper 1: offsets of general feature profiles
  libxxhash-dev                               # XXH64 of the server's ETags
  nettle-dev                                  # SHA-256 of profile versions
  libre2-dev                                  # RE2: the CL checks' tool- and operation-name patterns
)
test_packages=(
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  python3 xsltproc clang-format
  python3-jsonschema                          # the profile schema checks (profile, cls checks)
  chromium                                    # tests/web: the browser test, through playwright-core
  nginx                                       # the load balancer of tests/deploy (scale-out)
)
# rs274 (LinuxCNC's stand-alone interpreter) is used by tests/interop; recommends would pull in X11.
interop_packages=(linuxcnc-uspace)
bench_packages=(hyperfine wrk)
# Peers that benchmarks compare against; large, so only `install-deps.sh peers` installs them.
peer_packages=(libocct-data-exchange-dev libtbb-dev)  # OCCT's CMake config names libtbb.so

want=("${build_packages[@]}")
case "${1:-all}" in
  build) ;;
  all) want+=("${test_packages[@]}" "${bench_packages[@]}") ;;
  peers) want+=("${test_packages[@]}" "${bench_packages[@]}" "${peer_packages[@]}") ;;
  *) echo "usage: $0 [build|all|peers]" >&2; exit 2 ;;
esac

# The front end (web/package.json: three.js, bundled by esbuild into web/index.html, which
# ncpostd serves at /) is built by every mode, so node is part of the build set; the OpenAPI
# linter and the browser test (tests/package.json) run on it too. Debian's nodejs and npm when
# the machine has no npm (a NodeSource nodejs brings its own and conflicts with them).
if ! command -v npm >/dev/null 2>&1; then
  want+=(nodejs npm)
fi

missing=()
for p in "${want[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
interop_missing=()
if [[ ${1:-all} != build ]]; then
  for p in "${interop_packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || interop_missing+=("$p")
  done
fi

if ((${#missing[@]} + ${#interop_missing[@]})); then
  SUDO=""
  [[ $(id -u) -eq 0 ]] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  if ((${#missing[@]})); then
    $SUDO apt-get install -y -qq "${missing[@]}"
  fi
  if ((${#interop_missing[@]})); then
    $SUDO apt-get install -y -qq --no-install-recommends "${interop_missing[@]}"
  fi
fi

# npm test tools, pinned by tests/package-lock.json (@redocly/cli, playwright-core, axe-core);
# again only when the lock file changed since the last install.
if [[ ${1:-all} != build ]]; then
  tests_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tests"
  if [[ ! -x $tests_dir/node_modules/.bin/redocly || ! -d $tests_dir/node_modules/playwright-core ||
        ! -d $tests_dir/node_modules/axe-core ||
        $tests_dir/package-lock.json -nt $tests_dir/node_modules/.package-lock.json ]]; then
    npm ci --prefix "$tests_dir" --no-audit --no-fund
  fi
fi

# The front end: three.js and esbuild pinned by web/package-lock.json, installed again only when
# the lock file changed, and bundled into web/index.html (web/build.mjs) whenever a source is
# newer than the page.
# (docker/Dockerfile runs this script before the sources are copied: no web/ yet, and it
# builds the page itself after the copy.)
web_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/web"
if [[ -f $web_dir/package.json ]]; then
  if [[ ! -d $web_dir/node_modules/three ||
        $web_dir/package-lock.json -nt $web_dir/node_modules/.package-lock.json ]]; then
    npm ci --prefix "$web_dir" --no-audit --no-fund
  fi
  if [[ ! -f $web_dir/index.html ||
        -n $(find "$web_dir/src" "$web_dir/build.mjs" "$web_dir/package-lock.json" -newer "$web_dir/index.html" -print -quit) ]]; then
    npm run --prefix "$web_dir" --silent build
  fi
fi
