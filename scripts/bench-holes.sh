#!/usr/bin/env bash
# Scaling check of `--holes` matching (not a timed test): generates a 67,500-hole
# job as a CSV program (drill cycles of targets) and as a CSV hole list, and a 20,000-row hole
# list for it, then times
#   roprec predict --cell CELL PROGRAM.csv [--holes LIST.csv] (a CSV program: position matching)
#   roprec predict --cell CELL HOLES.csv [--holes LIST.csv]   (a hole-list job: id matching)
# with and without the list. Measured at full size (67,500 x 20,000, 2 shared cores):
#   before (O(n m) scans): program 5.9 s -> 60.3 s with --holes; hole-list job 4.9 -> 8.4 s
#   after (ids through a hash, positions through a direction-bucketed grid, postproc::matchHoles):
#                          program 6.1 s -> 6.2 s;               hole-list job 5.2 -> 5.3 s
#
#   scripts/bench-holes.sh [ROPREC_BINARY]     (default build/bin/roprec)
#
# BENCH_HOLES  holes in the job (default 67500)   BENCH_LIST  rows of the list (default 20000)
# BENCH_DIR    work folder (default a fresh mktemp -d, removed at the end)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${1:-$ROOT/build/bin/roprec}"
N="${BENCH_HOLES:-67500}"
M="${BENCH_LIST:-20000}"
[ -x "$BIN" ] || { echo "bench-holes: $BIN is not an executable (build roprec first)" >&2; exit 2; }
DIR="${BENCH_DIR:-$(mktemp -d)}"
[ -n "${BENCH_DIR:-}" ] || trap 'rm -rf "$DIR"' EXIT
mkdir -p "$DIR"
CELL="$ROOT/samples/cells/housing-kr120.xml"

python3 - "$DIR" "$N" "$M" <<'EOF'
import math, sys
out, n, m = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
# a grid on the top face of the sample housing (workobject frame, mm), 1.2 mm pitch
cols = int(math.ceil(math.sqrt(n * 1.2)))
holes = []
for k in range(n):
    x = -160.0 + 1.2 * (k % cols)
    y = -150.0 + 1.2 * (k // cols)
    holes.append(("B%05d" % (k + 1), x, y, 250.0))
with open(out + "/job.csv", "w") as f:
    f.write("id,x,y,z,i,j,k,diameter,depth,tolerance\n")
    for h in holes:
        f.write("%s,%.3f,%.3f,%.3f,0,0,-1,6.8,16,0.2\n" % h)
# every n/m-th hole is in the list (same id and position)
step = n / m
with open(out + "/list.csv", "w") as f:
    f.write("id,x,y,z,i,j,k,diameter,depth,tolerance\n")
    for r in range(m):
        h = holes[int(r * step)]
        f.write("%s,%.3f,%.3f,%.3f,0,0,-1,6.8,16,0.2\n" % h)
# the same job as a CSV program: one drill cycle per hole (approach, feed at 20 mm/s, retract;
# target names unlike the list's ids, so the list is matched by position)
with open(out + "/job_program.csv", "w") as f:
    f.write("id,x,y,z,a,b,c,move,speed\n")
    for (i, x, y, z) in holes:
        for (tag, zz, mv, v) in (("a", z + 50, "PTP", 250), ("e", z + 2, "LIN", 250),
                                 ("b", z - 16, "LIN", 20), ("r", z + 50, "LIN", 250)):
            f.write("P%s%s,%.3f,%.3f,%.3f,0,0,180,%s,%d\n" % (i[1:], tag, x, y, zz, mv, v))
EOF

run() {  # run LABEL ARGS...: wall time of one roprec run (exit 0 or 1 expected)
  local label="$1"
  shift
  local t0 t1 rc=0
  t0=$(date +%s.%N)
  "$BIN" "$@" >"$DIR/out.txt" 2>"$DIR/err.txt" || rc=$?
  t1=$(date +%s.%N)
  if [ "$rc" -gt 1 ]; then
    echo "bench-holes: $label failed (exit $rc):" >&2
    tail -3 "$DIR/err.txt" >&2
    exit 1
  fi
  printf '%-44s %8.2f s\n' "$label" "$(awk "BEGIN { print $t1 - $t0 }")"
}

echo "bench-holes: $N holes, a $M-row list ($("$BIN" --version 2>/dev/null | head -1 || echo roprec))"
run "predict job_program.csv" predict --cell "$CELL" "$DIR/job_program.csv" --quiet \
  --json "$DIR/a.json"
run "predict job_program.csv --holes list.csv" predict --cell "$CELL" "$DIR/job_program.csv" \
  --quiet --holes "$DIR/list.csv" --json "$DIR/b.json"
run "predict job.csv" predict --cell "$CELL" "$DIR/job.csv" --quiet --json "$DIR/a.json"
run "predict job.csv --holes list.csv" predict --cell "$CELL" "$DIR/job.csv" --quiet \
  --holes "$DIR/list.csv" --json "$DIR/b.json"
