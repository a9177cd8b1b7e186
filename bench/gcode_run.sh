#!/usr/bin/env bash
# G-code in (issue 19), side by side in one run: engine/gcode (gcode_bench) and LinuxCNC's
# /usr/bin/rs274 on the same files — the trajectory-planner programs of the corpus and a
# generated program of SIZE_MB (default 100) — and a FANUC macro B loop of 10^6 iterations.
# rs274 runs under the machine-wide lock (docs/HELPERS: /tmp/ncpost-rs274.lock); its time is
# the CPU time `time` reports (user + sys), as is ours ("CPU"), since the machine is shared.
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-100}
corpus=${NCPOST_CORPUS:-../shared/corpus}
work=${TMPDIR:-/tmp}/ncpost-bench
mkdir -p "$work"
large=$work/large-$size.ngc
[[ -f $large ]] || build/bin/gcode_bench generate "$size" "$large"

echo "== machine"
echo "date: $(date -u +%Y-%m-%dT%H:%MZ)  cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)  cores: $(nproc)  load: $(cut -d' ' -f1-3 /proc/loadavg)"

rs274_cpu() {
  local out=$work/rs274-canon.txt
  TIMEFORMAT='rs274: %U s user + %S s sys (%R s wall)'
  time flock /tmp/ncpost-rs274.lock rs274 -g "$1" "$out" < /dev/null > /dev/null 2>&1 || true
  echo "rs274: $(wc -l < "$out") canonical lines"
  rm -f "$out"
}

for f in "$corpus"/gcode/linuxcnc_tests_trajectory-planner/performance/*.ngc "$large"; do
  echo "== $(basename "$f") ($(du -k "$f" | cut -f1) KiB)"
  build/bin/gcode_bench read "$f" linuxcnc 5
  rs274_cpu "$f"
done

echo "== FANUC macro B loop, 10^6 iterations"
build/bin/gcode_bench macro-loop 1000000 3
