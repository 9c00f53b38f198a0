# shellcheck shell=bash
# One run of a command under GNU time -v, for the benchmark scripts (bench-cli.sh, bench-large.sh,
# check-memory.sh source this file):
#
#   measure_require NAME         exits 2 with a message naming the script NAME without GNU time
#   measure DIR CMD ARGS...      runs CMD ARGS... with stdout to $MEASURE_STDOUT (default
#                                DIR/stdout.txt) and stderr to DIR/err.txt, then sets
#     MEASURE_RC    its exit code
#     MEASURE_WALL  wall time in s (bash's µs clock; GNU time's is 10 ms), 4 decimals
#     MEASURE_RSS   peak RSS in MiB (GNU time's "Maximum resident set size" is in KiB)
#     MEASURE_CPU   user + system CPU time in s (on a busy machine a steadier figure than the wall
#                   time: a one-thread run's wall time is about its CPU time on an idle one)

measure_require() {
  [ -x /usr/bin/time ] || {
    echo "$1: needs GNU time (/usr/bin/time; scripts/setup.sh installs it)" >&2
    exit 2
  }
}

measure() {
  local dir="$1"
  shift
  MEASURE_RC=0
  local t0=$EPOCHREALTIME
  /usr/bin/time -v -o "$dir/time.txt" "$@" >"${MEASURE_STDOUT:-$dir/stdout.txt}" \
    2>"$dir/err.txt" || MEASURE_RC=$?
  local t1=$EPOCHREALTIME
  MEASURE_WALL=$(LC_ALL=C awk "BEGIN { printf \"%.4f\", $t1 - $t0 }")
  MEASURE_RSS=$(awk -F': ' '/Maximum resident set size/ { printf "%.0f", $2 / 1024 }' "$dir/time.txt")
  MEASURE_CPU=$(LC_ALL=C awk -F': ' '/(User|System) time \(seconds\)/ { s += $2 } END { print s }' \
    "$dir/time.txt")
}
