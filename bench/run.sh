#!/usr/bin/env bash
# Runs the benchmarks that docs/benchmarks.md reports, side by side with their peers, on a
# generated file of SIZE_MB (default 100). Needs a Release build in build/ and, for the peer,
# `scripts/install-deps.sh peers` before configuring. Not part of CI: it takes minutes and wants a
# quiet machine.
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-100}
corpus=${NCPOST_CORPUS:-../shared/corpus}
work=${TMPDIR:-/tmp}/ncpost-bench
mkdir -p "$work"
large=$work/large-$size.stp
[[ -f $large ]] || build/bin/make_large_stepnc "$corpus/p21/nist_toolkit_ex1E.stp" "$size" "$large"

echo "== machine"
echo "date: $(date -u +%Y-%m-%dT%H:%MZ)  cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)  cores: $(nproc)"
echo "file: $large ($(du -m "$large" | cut -f1) MiB)"

echo "== P21 reader: ncpost (5 runs) then Open CASCADE (2 runs), same file, same run"
build/bin/p21_read_bench "$large" 5
build/bin/p21_read_bench --rss "$large"
if [[ -x build/bin/peer_occt_read ]]; then
  build/bin/peer_occt_read "$large" 2
  build/bin/peer_occt_read --rss "$large"
else
  echo "peer_occt_read not built (run scripts/install-deps.sh peers, then re-configure)"
fi

echo "== P21 -> P28 writer and P28 reader"
build/bin/p28_bench "$large" 3
build/bin/p28_bench --rss "$large"

echo "== end to end: ncpost convert --to p28 --binding early (read + write), and to P21"
if command -v hyperfine >/dev/null; then
  hyperfine --warmup 1 --runs 5 --export-markdown "$work/convert.md" \
    "build/bin/ncpost convert --to p28 --binding early $large > /dev/null" \
    "build/bin/ncpost convert --to p21 $large > /dev/null"
  cat "$work/convert.md"
fi

echo "== render (issue 6): transform vs xsltproc, cached vs recompiled stylesheet, end to end post"
ex1e=$corpus/p21/nist_toolkit_ex1E.stp
mid=$work/large-5.stp
[[ -f $mid ]] || build/bin/make_large_stepnc "$ex1e" 5 "$mid"
build/bin/ncpost trace --format xml "$ex1e" > "$work/ex1e.xml"
build/bin/ncpost trace --format xml "$mid" > "$work/large-5.xml"
# The profiles' post.xsl call urn:ncpost:ext functions that xsltproc does not have, so the
# side-by-side comparison uses a plain XSLT 1.0 stylesheet of comparable work (render_bench
# writes it). Both sides time parse of the document + apply + serialise, stylesheet compiled once.
build/bin/render_bench plain-xsl "$work/plain.xsl"
xsltproc_ms() {  # median over $2 runs of xsltproc's own parse-document + apply + save times
  for _ in $(seq "$2"); do
    xsltproc --timing "$work/plain.xsl" "$1" 2>&1 >/dev/null |
      awk '/Parsing document|Applying stylesheet|Saving result/ {s += $(NF-1)} END {print s}'
  done | sort -n | awk '{v[NR] = $1} END {print "xsltproc parse+apply+save median_ms=" v[int((NR+1)/2)] " best_ms=" v[1]}'
}
for xml in "$work/ex1e.xml" "$work/large-5.xml"; do
  for round in 1 2; do
    echo "-- $xml round $round"
    build/bin/render_bench transform "$work/plain.xsl" "$xml" 10
    xsltproc_ms "$xml" 10
  done
  xsltproc --timing --repeat "$work/plain.xsl" "$xml" 2>&1 >/dev/null | grep Applying
  build/bin/render_bench transform fanuc-0i "$xml" 5
  build/bin/render_bench transform linuxcnc "$xml" 5
done
for profile in fanuc-0i linuxcnc; do
  build/bin/render_bench cache "$profile" tests/golden/trace/cases/curves.stp 50
  build/bin/render_bench cache "$profile" "$ex1e" 20
done
# fanuc-0i rejects the generated file (its renumbered tool slots exceed 9999: RENDER-001 errors,
# exit 1), so the end-to-end figure is taken with linuxcnc too.
for profile in fanuc-0i linuxcnc; do
  build/bin/render_bench pipeline "$profile" "$large" 3 2>/dev/null || echo "render_bench pipeline $profile: post failed"
done
# Batching (docs/render.md): one transform per chunk (0, as before batching) against batch
# budgets of 16 KiB .. 1 MiB of chunk XML, same binary, same file, one after the other.
for batch in 0 16384 65536 262144 1048576; do
  build/bin/render_bench pipeline linuxcnc "$large" 3 "$batch"
done
# The peer of an optimisation is the build before it: set BEFORE=DIR to a directory holding the
# render_bench of the previous build, and it runs side by side here.
if [[ -n ${BEFORE:-} && -x $BEFORE/render_bench ]]; then
  for round in 1 2; do
    echo "-- before/after round $round"
    "$BEFORE/render_bench" pipeline linuxcnc "$large" 3
    build/bin/render_bench pipeline linuxcnc "$large" 3
    "$BEFORE/render_bench" cache linuxcnc tests/golden/trace/cases/curves.stp 50
    build/bin/render_bench cache linuxcnc tests/golden/trace/cases/curves.stp 50
  done
fi
# Instruction counts do not depend on the machine's load: the same post under callgrind
# (1 MB file, one copy of ex1E's workingsteps x 10), before and after.
if command -v valgrind >/dev/null; then
  small=$work/large-1.stp
  [[ -f $small ]] || build/bin/make_large_stepnc "$ex1e" 1 "$small"
  for bin in ${BEFORE:+$BEFORE/render_bench} build/bin/render_bench; do
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" pipeline linuxcnc "$small" 1 2>&1 |
      grep -E 'refs' | sed "s|^|$bin: |"
  done
fi
if command -v hyperfine >/dev/null; then
  hyperfine -i --runs 3 --export-markdown "$work/post.md" \
    "build/bin/ncpost post --profile fanuc-0i $large > /dev/null 2>&1" \
    "build/bin/ncpost post --profile linuxcnc $large > /dev/null 2>&1"
  cat "$work/post.md"
fi
for profile in fanuc-0i linuxcnc; do
  /usr/bin/time -v build/bin/ncpost post --profile "$profile" "$large" 2>&1 >/dev/null |
    grep -E 'Maximum resident|Elapsed|Exit status' || true
done
build/bin/p21_read_bench --rss "$large"
