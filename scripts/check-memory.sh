#!/usr/bin/env bash
# Memory check (a benchmark script, CTest label "perf"; not a unit test): fails when a command
# whose memory should not grow with the job does. Runs each command on generated KRL jobs of
# MEM_SMALL and MEM_LARGE holes (default 10,000 and 100,000; scripts/gen-drill-job.py, the KR 120
# sample cell) under GNU time -v and requires
#     peak RSS(large) <= MEM_RATIO x peak RSS(small) + MEM_SLACK_MIB
# (defaults 1.25 and 16 MiB): a tenfold job may add little beyond its larger input. Checked:
#   predict --json FILE   (the prediction streamed in blocks)
#   predict, JSON on stdout
# Prints one line per command (both peaks, the bound, ok/GROWS) and exits 1 when one grows.
#
#   scripts/check-memory.sh [ROPREC_BINARY]     (default build/bin/roprec)
set -euo pipefail
export LC_ALL=C
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${1:-$ROOT/build/bin/roprec}"
SMALL="${MEM_SMALL:-10000}"
LARGE="${MEM_LARGE:-100000}"
RATIO="${MEM_RATIO:-1.25}"
SLACK="${MEM_SLACK_MIB:-16}"
[ -x "$BIN" ] || { echo "check-memory: $BIN is not an executable (build roprec first)" >&2; exit 2; }
# shellcheck source=scripts/lib/measure.sh
source "$ROOT/scripts/lib/measure.sh"
measure_require check-memory
DIR="$(mktemp -d)"
trap 'rm -rf "$DIR"' EXIT
CELL="$ROOT/samples/cells/housing-kr120.xml"
for n in "$SMALL" "$LARGE"; do python3 "$ROOT/scripts/gen-drill-job.py" "$n" "$DIR/job$n.src"; done

peak() {  # peak N ARGS...: the peak RSS in MiB of roprec ARGS on the N-hole job (JOB in ARGS)
  local n="$1"
  shift
  local args=("${@//JOB/$DIR/job$n.src}")
  MEASURE_STDOUT=/dev/null measure "$DIR" "$BIN" "${args[@]}"
  if [ "$MEASURE_RC" -ne 0 ]; then
    echo "check-memory: roprec ${args[*]} failed:" >&2
    tail -3 "$DIR/err.txt" >&2
    exit 2
  fi
  echo "$MEASURE_RSS"
}

FAILED=0
check() {  # check LABEL ARGS...
  local label="$1"
  shift
  local small large bound
  small=$(peak "$SMALL" "$@")
  large=$(peak "$LARGE" "$@")
  bound=$(awk "BEGIN { printf \"%.0f\", $RATIO * $small + $SLACK }")
  local verdict=ok
  if [ "$large" -gt "$bound" ]; then
    verdict=GROWS
    FAILED=1
  fi
  printf '%-28s %6s MiB (%s holes) %6s MiB (%s holes)  bound %6s MiB  %s\n' "$label" "$small" \
    "$SMALL" "$large" "$LARGE" "$bound" "$verdict"
}

check "predict --json" predict --cell "$CELL" JOB --quiet --json "$DIR/out.json"
check "predict, JSON on stdout" predict --cell "$CELL" JOB --quiet
exit "$FAILED"
