#!/usr/bin/env bash
# The large-job rows of the performance table (a script, not a timed test): wall time and peak RSS
# (GNU time -v) of the CLI on generated jobs at the scale users run,
#   predict --json         BENCH_LARGE_HOLES holes (default 1,000,000), 1 and 2 threads
#   predict, JSON on stdout  the same job, 2 threads
#   predict --report       the same job, 1 and 2 threads
#   compensate -o --targets  keep, flip-free and stiffest on BENCH_LARGE_COMPENSATE holes (default
#                          1,000,000), 2 threads
#   convert --to D         a BENCH_LARGE_CONVERT_HOLES-hole KRL program (default 300,000: 110 MB)
#                          into rapid, tp, krl, csv and json, and the RAPID and TP programs made
#                          from it back into krl (any dialect into any)
#   map                    1.2 x 1.6 m at 10 mm, 3 feeds (58,443 predictions)
#   plan-test              64,000 candidates (40 x 40 x 40 points, one direction, psi 0), 400
#                          holes chosen for the joint stiffness (--identify stiffness)
# on the KR 120 sample cell (samples/cells/housing-kr120.xml; jobs from scripts/gen-drill-job.py).
# Prints one line per run, "KEY  WALL s  RSS MiB  CPU s CPU" (user + system), as bench-cli.sh does (scripts/bench-table.sh
# reads them). A run that fails is reported and makes the exit code 1.
#
#   scripts/bench-large.sh [ROPREC_BINARY]     (default build/bin/roprec)
#
# BENCH_LARGE_ROWS  which groups to run (default "predict report compensate convert map plan"):
#                   a 1,000,000-hole compensate needs several GB and minutes; leave groups out on a
#                   small machine
# BENCH_DIR         work folder (default a fresh mktemp -d, removed at the end)
set -euo pipefail
export LC_ALL=C
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${1:-$ROOT/build/bin/roprec}"
HOLES="${BENCH_LARGE_HOLES:-1000000}"
COMP="${BENCH_LARGE_COMPENSATE:-1000000}"
CONV="${BENCH_LARGE_CONVERT_HOLES:-300000}"
ROWS=" ${BENCH_LARGE_ROWS:-predict report compensate convert map plan} "
[ -x "$BIN" ] || { echo "bench-large: $BIN is not an executable (build roprec first)" >&2; exit 2; }
# shellcheck source=scripts/lib/measure.sh
source "$ROOT/scripts/lib/measure.sh"
measure_require bench-large
DIR="${BENCH_DIR:-$(mktemp -d)}"
[ -n "${BENCH_DIR:-}" ] || trap 'rm -rf "$DIR"' EXIT
mkdir -p "$DIR"
CELL="$ROOT/samples/cells/housing-kr120.xml"
FAILED=0

want() { [[ "$ROWS" == *" $1 "* ]]; }

run() {  # run KEY ARGS...: one roprec run (stdout to a file) under GNU time: "KEY  WALL s  RSS MiB"
  local key="$1"
  shift
  measure "$DIR" "$BIN" "$@"
  if [ "$MEASURE_RC" -gt 1 ]; then
    echo "bench-large: $key failed (exit $MEASURE_RC):" >&2
    tail -3 "$DIR/err.txt" >&2
    FAILED=1
    return
  fi
  printf '%-44s %8.3f s %8s MiB %8.2f s CPU\n' "$key" "$MEASURE_WALL" "$MEASURE_RSS" "$MEASURE_CPU"
}

gen() { [ -s "$2" ] || python3 "$ROOT/scripts/gen-drill-job.py" "$1" "$2"; }

echo "bench-large: $("$BIN" --version 2>/dev/null | head -1 || echo roprec), $(nproc) cores"
if want predict || want report; then
  gen "$HOLES" "$DIR/job$HOLES.src"
fi
if want predict; then
  for t in 1 2; do
    run "predict $HOLES --json, --threads $t" predict --cell "$CELL" "$DIR/job$HOLES.src" \
      --quiet --json "$DIR/p.json" --threads "$t"
  done
  run "predict $HOLES stdout, --threads 2" predict --cell "$CELL" "$DIR/job$HOLES.src" --quiet \
    --json - --threads 2
fi
if want report; then
  for t in 1 2; do
    run "predict $HOLES --report, --threads $t" predict --cell "$CELL" "$DIR/job$HOLES.src" \
      --quiet --json "$DIR/p.json" --report "$DIR/p.html" --threads "$t"
  done
fi
if want compensate; then
  gen "$COMP" "$DIR/job$COMP.src"
  for o in keep flip-free stiffest; do
    run "compensate $COMP $o, --threads 2" compensate --cell "$CELL" "$DIR/job$COMP.src" --quiet \
      --orientation "$o" -o "$DIR/c.src" --targets "$DIR/c.csv" --threads 2
  done
fi
if want convert; then
  gen "$CONV" "$DIR/conv.src"
  mb() { awk "BEGIN { printf \"%.0f\", $(stat -c %s "$1") / 1e6 }"; }  # the input's size, MB
  for d in rapid tp krl csv json; do
    run "convert $(mb "$DIR/conv.src") MB krl -> $d" convert "$DIR/conv.src" --to "$d" \
      -o "$DIR/out_$d"
  done
  run "convert $(mb "$DIR/out_rapid.mod") MB rapid -> krl" convert "$DIR/out_rapid.mod" --to krl \
    -o "$DIR/back_rapid"
  run "convert $(mb "$DIR/out_tp.ls") MB tp -> krl" convert "$DIR/out_tp.ls" --to krl \
    -o "$DIR/back_tp" --frame 'UFRAME[1]=1350 0 300 0 0 0;UTOOL[1]=0 0 320 0 0 0'
fi
if want map; then
  run "map 1.2 x 1.6 m at 10 mm, 3 feeds" map --cell "$CELL" --region "-600 -800 0 600 800 0" \
    --direction "0 0 -1" --step 10 --feeds "0.05 0.1 0.15" --csv "$DIR/map.csv" --quiet
fi
if want plan; then
  run "plan-test 64,000 candidates x 400 holes" plan-test --cell "$CELL" \
    --region "-150 -150 150 150 150 250" --per-axis 40 --psi 0 --count 400 --identify stiffness \
    -o "$DIR/plan.csv" --quiet
fi
exit "$FAILED"
