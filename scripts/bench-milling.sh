#!/usr/bin/env bash
# Milling path at CAM size (a benchmark script, not a timed test): generates an N-point KRL wall
# pass (the sample's pass, samples/milling/wall_pass.src, with N feed points over its 120 mm) and
# runs `roprec compensate` on it with every export on — the program, --report and --targets as
# CSV, then as JSON — with 1 and 2 threads, under a virtual-memory limit (ulimit -v). Prints one
# line per run, "KEY  WALL s  RSS MiB  CPU s CPU  US us/point wall  US us/point CPU" (on a busy
# machine the CPU figure is the steadier one; scripts/bench-large.sh's format;
# scripts/bench-table.sh reads the "milling N ..." rows), and checks that the outputs are the same
# bytes whatever the thread count. A run that fails (e.g. over the limit) makes the exit code 1.
# Goal (issue: CAM-size paths): 1,000,000 points in <= 60 s on 2 cores and <= 500 MB.
#
#   scripts/bench-milling.sh [N=100000] [MEM_LIMIT_MB=4000] [ROPREC_BINARY=build/bin/roprec]
#
# BENCH_MILLING_THREADS  thread counts to run (default "1 2")
# BENCH_MILLING_EXPORTS  which --targets formats (default "csv json")
set -euo pipefail
export LC_ALL=C
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
N="${1:-100000}"
MEM_MB="${2:-4000}"
BIN="${3:-$ROOT/build/bin/roprec}"
THREADS="${BENCH_MILLING_THREADS:-1 2}"
EXPORTS="${BENCH_MILLING_EXPORTS:-csv json}"
[ -x "$BIN" ] || { echo "bench-milling: $BIN is not an executable (build roprec first)" >&2; exit 2; }
# shellcheck source=scripts/lib/measure.sh
source "$ROOT/scripts/lib/measure.sh"
measure_require bench-milling
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
SRC="$ROOT/samples/milling/wall_pass.src"
{
  sed -n '1,/^\$VEL.CP = 0.06000/p' "$SRC"
  awk -v n="$N" 'BEGIN { for (i = 0; i < n; ++i)
    printf "LIN {X %.4f,Y 0.000,Z -5.000,A 0.000,B 0.000,C 180.000} C_DIS\n", -50 + 120.0 * i / n }'
  sed -n '/^LIN {X 70.000/,$p' "$SRC"
} >"$WORK/pass.src"
points=$(grep -c '^LIN' "$WORK/pass.src")
echo "bench-milling: $points linear points, memory limit ${MEM_MB} MB, threads: $THREADS"
status=0
for e in $EXPORTS; do
  first=""
  for t in $THREADS; do
    out="$WORK/$e-$t"
    mkdir -p "$out"
    measure "$out" bash -c 'ulimit -v $(('"$MEM_MB"' * 1024)); exec "$@"' _ "$BIN" compensate \
      --quiet --threads "$t" --cell "$ROOT/samples/cells/alu-milling-7075.xml" "$WORK/pass.src" \
      -o "$out/out.src" --targets "$out/t.$e" --report "$out/r.html"
    key="milling $N --targets $e --report, --threads $t"
    if [ "$MEASURE_RC" -ne 0 ]; then
      printf '%-56s FAILED (exit %s): %s\n' "$key" "$MEASURE_RC" "$(head -c 300 "$out/err.txt")"
      status=1
      continue
    fi
    us=$(awk -v s="$MEASURE_WALL" -v n="$points" 'BEGIN { printf "%.1f", 1e6 * s / n }')
    cpu_us=$(awk -v s="$MEASURE_CPU" -v n="$points" 'BEGIN { printf "%.1f", 1e6 * s / n }')
    printf '%-56s %8.3f s %8s MiB %8.2f s CPU %8s us/point wall %8s us/point CPU\n' "$key" \
      "$MEASURE_WALL" "$MEASURE_RSS" "$MEASURE_CPU" "$us" "$cpu_us"
    if [ -z "$first" ]; then
      first="$out"
    elif ! cmp -s "$first/out.src" "$out/out.src" || ! cmp -s "$first/t.$e" "$out/t.$e" ||
      ! cmp -s "$first/r.html" "$out/r.html"; then
      echo "bench-milling: the outputs with --threads $t differ from the first run's" >&2
      status=1
    fi
    [ "$out" = "$first" ] || rm -f "$out"/*.src "$out"/*.html "$out/t.$e"
  done
done
exit "$status"
