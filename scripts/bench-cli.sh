#!/usr/bin/env bash
# CLI scaling bench (a script, not a timed test): generates 1,000 / 10,000 / 100,000-hole
# KUKA KRL drilling programs for the KR 120 sample cell (samples/cells/housing-kr120.xml: the
# top face of the e-motor housing, a 1.2 mm grid of OLP-style drill cycles like
# samples/emotor-housing/housing_kr120.src), then runs
#   roprec predict    --cell CELL JOB.src --json OUT.json --threads T
#   roprec compensate --cell CELL JOB.src -o OUT.src --targets OUT.csv --orientation flip-free
#                     --threads T                                   (1k and 10k holes)
# with T = 1 and 2 (BENCH_REPEAT times each, alternating), and prints the best wall time (bash's
# µs clock), the peak RSS and CPU time (GNU time -v) of each command, the 2-vs-1 speed-up, and
# whether the outputs of T = 1 and T = 2 are byte-identical (cmp).
#
#   scripts/bench-cli.sh [ROPREC_BINARY]     (default build/bin/roprec)
#
# Measured 2026-11-25 09:01 on the 2-core machine with no other build running
# (scripts/bench-table.sh, best of 5; CHANGELOG.md has the history):
#   predict 10,000 holes      0.113 s / 41 MiB (1 thread), 0.077 s / 53 MiB (2): 1.46x
#   compensate 10,000 holes   0.663 s / 108 MiB (1 thread), 0.385 s (2): 1.72x
#   predict 100,000 holes     1.01 s / 187 MiB (1 thread), 0.84 s / 188 MiB (2)
# every output byte-identical for 1 and 2 threads. Wall times of a 2-thread run depend on the
# second core being free: with other builds running, the speed-ups drop to ~1.0x.
# The last column is user + system CPU: about the same for 1 and 2 threads.
#
# BENCH_SIZES  hole counts (default "1000 10000 100000")
# BENCH_COMPENSATE_MAX  largest job that is also compensated (default 10000)
# BENCH_REPEAT runs of each command (default 3; 1 and 2 threads alternate): each row shows the
#              least wall time (the CPU time of that run) and the largest peak RSS. On a shared
#              virtual machine one run's speed varies by up to ~30 % from run to run.
# BENCH_DIR    work folder (default a fresh mktemp -d, removed at the end)
# Exit 1 when a run fails or two outputs differ.
set -euo pipefail
export LC_ALL=C  # EPOCHREALTIME and awk with a decimal point
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${1:-$ROOT/build/bin/roprec}"
SIZES="${BENCH_SIZES:-1000 10000 100000}"
COMP_MAX="${BENCH_COMPENSATE_MAX:-10000}"
REPEAT="${BENCH_REPEAT:-3}"
[ -x "$BIN" ] || { echo "bench-cli: $BIN is not an executable (build roprec first)" >&2; exit 2; }
# shellcheck source=scripts/lib/measure.sh
source "$ROOT/scripts/lib/measure.sh"
measure_require bench-cli
DIR="${BENCH_DIR:-$(mktemp -d)}"
[ -n "${BENCH_DIR:-}" ] || trap 'rm -rf "$DIR"' EXIT
mkdir -p "$DIR"
CELL="$ROOT/samples/cells/housing-kr120.xml"

gen() {  # gen N FILE: a KRL program with N drill cycles on the housing's top face
  python3 "$ROOT/scripts/gen-drill-job.py" "$1" "$2"
}

FAILED=0
declare -A WALL RSS CPU
run() {  # run KEY ARGS...: one roprec run under GNU time; keeps the key's least wall time (and the
  # CPU time of that run) and its largest peak RSS over the repetitions
  local key="$1"
  shift
  measure "$DIR" "$BIN" "$@"
  if [ "$MEASURE_RC" -gt 1 ]; then
    echo "bench-cli: $key failed (exit $MEASURE_RC):" >&2
    tail -3 "$DIR/err.txt" >&2
    FAILED=1
    return
  fi
  if [ -z "${WALL[$key]:-}" ] || awk "BEGIN { exit !($MEASURE_WALL < ${WALL[$key]}) }"; then
    WALL[$key]=$MEASURE_WALL
    CPU[$key]=$MEASURE_CPU
  fi
  if [ -z "${RSS[$key]:-}" ] || [ "$MEASURE_RSS" -gt "${RSS[$key]}" ]; then
    RSS[$key]=$MEASURE_RSS
  fi
}

show() {  # show KEY: the key's best wall time, peak RSS and CPU time
  [ -n "${WALL[$1]:-}" ] || return 0
  printf '%-44s %8.3f s %8s MiB %8.2f s CPU\n' "$1" "${WALL[$1]}" "${RSS[$1]}" "${CPU[$1]}"
}

same() {  # same LABEL A B: byte-identity of two outputs
  if cmp -s "$2" "$3"; then
    printf '%-44s %s\n' "$1" "byte-identical"
  else
    printf '%-44s %s\n' "$1" "DIFFERENT"
    FAILED=1
  fi
}

speedup() {  # speedup LABEL KEY1 KEY2
  [ -n "${WALL[$2]:-}" ] && [ -n "${WALL[$3]:-}" ] || return 0
  printf '%-44s %8.2fx\n' "$1" "$(awk "BEGIN { print ${WALL[$2]} / ${WALL[$3]} }")"
}

echo "bench-cli: $("$BIN" --version 2>/dev/null | head -1 || echo roprec), $(nproc) cores," \
  "best of $REPEAT runs, 1 and 2 threads alternating"
for n in $SIZES; do
  gen "$n" "$DIR/job$n.src"
  for r in $(seq "$REPEAT"); do
    for t in 1 2; do
      run "predict $n holes, --threads $t" predict --cell "$CELL" "$DIR/job$n.src" --quiet \
        --json "$DIR/p$n-t$t.json" --threads "$t"
    done
  done
  show "predict $n holes, --threads 1"
  show "predict $n holes, --threads 2"
  speedup "predict $n: 2 vs 1 threads" "predict $n holes, --threads 1" "predict $n holes, --threads 2"
  same "predict $n: JSON 1 vs 2 threads" "$DIR/p$n-t1.json" "$DIR/p$n-t2.json"
  if [ "$n" -le "$COMP_MAX" ]; then
    for r in $(seq "$REPEAT"); do
      for t in 1 2; do
        run "compensate $n flip-free, --threads $t" compensate --cell "$CELL" "$DIR/job$n.src" \
          --quiet --orientation flip-free -o "$DIR/c$n-t$t.src" --targets "$DIR/c$n-t$t.csv" \
          --threads "$t"
      done
    done
    show "compensate $n flip-free, --threads 1"
    show "compensate $n flip-free, --threads 2"
    speedup "compensate $n: 2 vs 1 threads" "compensate $n flip-free, --threads 1" \
      "compensate $n flip-free, --threads 2"
    same "compensate $n: program 1 vs 2 threads" "$DIR/c$n-t1.src" "$DIR/c$n-t2.src"
    same "compensate $n: targets 1 vs 2 threads" "$DIR/c$n-t1.csv" "$DIR/c$n-t2.csv"
  fi
done
exit "$FAILED"
