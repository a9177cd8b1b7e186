#!/usr/bin/env bash
# The batch baseline of docs/benchmarks.md ("HTTP service"): the same posts as the server's,
# made by a loop of processes instead, started one after another (and PARALLEL at a time).
#
#   batch_baseline.sh BIN_DIR FILE PROFILE [N] [PARALLEL]
#
#   xsltproc: `ncpost trace --format xml FILE | xsltproc PLAIN.xsl -`, PLAIN.xsl being the plain
#             XSLT 1.0 stylesheet `render_bench plain-xsl` writes. The profiles call
#             urn:ncpost:ext functions, which xsltproc does not have, so this loop renders
#             G0/G1/G2/G3/F/S/T only: less work than a profile, which favours the baseline.
#   ncpost:   `ncpost post --profile PROFILE FILE`, the CLI twin of POST /v1/posts.
# Prints posts per second of each loop.
set -euo pipefail
bin=${1:?usage: batch_baseline.sh BIN_DIR FILE PROFILE [N] [PARALLEL]}
file=${2:?}
profile=${3:?}
n=${4:-200}
parallel=${5:-1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bin/render_bench" plain-xsl "$work/plain.xsl"
# The stylesheet must produce a program from this input, or the loop measures nothing.
"$bin/ncpost" trace --format xml "$file" | xsltproc "$work/plain.xsl" - >"$work/check.nc"
grep -q '^G1' "$work/check.nc" || { echo "plain.xsl gave no G1 for $file" >&2; exit 1; }
"$bin/ncpost" post --profile "$profile" "$file" >/dev/null

rate() {  # rate LABEL COMMAND...: N runs of COMMAND, PARALLEL at a time
  local label=$1
  shift
  local start end
  start=$(date +%s.%N)
  seq "$n" | xargs -P "$parallel" -I{} "$@"
  end=$(date +%s.%N)
  python3 -c "print(f'$label: {$n / ($end - $start):.1f} posts/s ($n posts, $parallel at a time)')"
}
export NCPOST_BIN=$bin NCPOST_FILE=$file NCPOST_XSL=$work/plain.xsl NCPOST_PROFILE=$profile
rate "ncpost trace | xsltproc plain.xsl" \
  sh -c '"$NCPOST_BIN/ncpost" trace --format xml "$NCPOST_FILE" | xsltproc "$NCPOST_XSL" - >/dev/null'
rate "ncpost post --profile $profile" \
  sh -c '"$NCPOST_BIN/ncpost" post --profile "$NCPOST_PROFILE" "$NCPOST_FILE" >/dev/null'
