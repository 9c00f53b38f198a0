#!/usr/bin/env bash
# Milling path at CAM size: generates an N-point KRL wall pass (the sample's pass with N feed
# points over 120 mm) and runs `roprec compensate` on it with the CSV export and the report, under
# a virtual-memory limit; prints wall time, peak RSS and the per-point cost (GNU time -v).
# Not a timed test. Usage: scripts/bench-milling.sh [N=100000] [MEM_LIMIT_MB=500] [BUILD=build]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
N="${1:-100000}"
MEM_MB="${2:-500}"
BIN="$ROOT/${3:-build}/bin/roprec"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
SRC="$ROOT/samples/milling/wall_pass.src"
{
  sed -n '1,/^\$VEL.CP = 0.06000/p' "$SRC"
  awk -v n="$N" 'BEGIN { for (i = 0; i < n; ++i)
    printf "LIN {X %.4f,Y 0.000,Z -5.000,A 0.000,B 0.000,C 180.000} C_DIS\n", -50 + 120.0 * i / n }'
  sed -n '/^LIN {X 70.000/,$p' "$SRC"
} > "$WORK/pass.src"
echo "bench-milling: $(grep -c '^LIN' "$WORK/pass.src") linear points, memory limit ${MEM_MB} MB"
status=0
( ulimit -v $((MEM_MB * 1024)); /usr/bin/time -v "$BIN" compensate --quiet \
    --cell "$ROOT/samples/cells/alu-milling-7075.xml" "$WORK/pass.src" -o "$WORK/out.src" \
    --targets "$WORK/t.csv" --report "$WORK/r.html" ) 2> "$WORK/time.txt" || status=$?
grep -E "Elapsed|Maximum resident" "$WORK/time.txt" || true
grep -E "^roprec" "$WORK/time.txt" | head -5 || true
secs=$(awk -F': ' '/Elapsed/ { n = split($2, t, ":"); s = 0; for (i = 1; i <= n; ++i) s = s * 60 + t[i]; print s }' "$WORK/time.txt")
echo "bench-milling: exit $status, $(awk -v s="$secs" -v n="$N" 'BEGIN { printf "%.1f us per point", 1e6 * s / n }')"
exit "$status"
