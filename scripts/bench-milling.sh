#!/usr/bin/env bash
# Milling path at CAM size (a benchmark script, not a timed test): generates an N-point wall pass
# (the sample's pass, samples/milling/wall_pass.src, with N feed points over its 120 mm; as a KUKA
# KRL .src, an ABB RAPID .mod with inline targets or a FANUC TP .ls) and runs `roprec compensate`
# on it with every export on — the program, --report and --targets as CSV, then as JSON — with 1
# and 2 threads, under a virtual-memory limit (ulimit -v). Prints one line per run, "KEY  WALL s
# RSS MiB  CPU s CPU  US us/point wall  US us/point CPU" (on a busy machine the CPU figure is the
# steadier one; scripts/bench-large.sh's format; scripts/bench-table.sh reads the "milling N ..."
# rows), and checks that the outputs are the same bytes whatever the thread count. A run that
# fails (e.g. over the limit) makes the exit code 1.
# Goal (issue: CAM-size paths): 1,000,000 points in <= 60 s on 2 cores and <= 500 MB.
#
#   scripts/bench-milling.sh [N=100000] [MEM_LIMIT_MB=4000] [ROPREC_BINARY=build/bin/roprec]
#
# BENCH_MILLING_THREADS  thread counts to run (default "1 2")
# BENCH_MILLING_EXPORTS  which --targets formats (default "csv json")
# BENCH_MILLING_DIALECT  krl (default), rapid or tp: the program's language (the rows' key names
#                        it when not krl); the cell is samples/cells/alu-milling-7075.xml with a
#                        robot of that vendor (KR 120, IRB 6700, R-2000iC/165F)
# BENCH_MILLING_COMMAND  compensate (default) or forces: `roprec forces --program` (its JSON on
#                        stdout; BENCH_MILLING_EXPORTS does not apply, one run per thread count)
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
DIALECT="${BENCH_MILLING_DIALECT:-krl}"
COMMAND="${BENCH_MILLING_COMMAND:-compensate}"
SRC="$ROOT/samples/milling/wall_pass.src"
case "$DIALECT" in
  krl)
    PROG="$WORK/pass.src"
    {
      sed -n '1,/^\$VEL.CP = 0.06000/p' "$SRC"
      awk -v n="$N" 'BEGIN { for (i = 0; i < n; ++i)
        printf "LIN {X %.4f,Y 0.000,Z -5.000,A 0.000,B 0.000,C 180.000} C_DIS\n", -50 + 120.0 * i / n }'
      sed -n '/^LIN {X 70.000/,$p' "$SRC"
    } >"$PROG"
    points=$(grep -c '^LIN' "$PROG")
    ;;
  rapid) # the KRL pass's $TOOL and $BASE as tooldata and wobjdata, inline targets (CAM style)
    PROG="$WORK/pass.mod"
    awk -v n="$N" 'function t(x, z) {
        return sprintf("[[%.4f,0.000,%.3f],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]", x, z) }
      BEGIN {
        a = ", tSpindle \\WObj:=wPart;"
        print "MODULE wall_pass"
        print "  PERS tooldata tSpindle := [TRUE,[[0,0,300],[1,0,0,0]],[30,[0,0,140],[1,0,0,0],0,0,0]];"
        print "  PERS wobjdata wPart := [FALSE,TRUE,\"\",[[1600,0,400],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];"
        print "  PROC wall_pass()"
        print "    MoveJ " t(-60, 50) ", v1000, z10" a
        print "    MoveL " t(-60, -5) ", v250, z1" a
        for (i = 0; i < n; ++i) print "    MoveL " t(-50 + 120.0 * i / n, -5) ", v60, z1" a
        print "    MoveL " t(70, -5) ", v60, z1" a
        print "    MoveL " t(70, 50) ", v250, z10" a
        print "  ENDPROC"
        print "ENDMODULE" }' >"$PROG"
    points=$(grep -c '^    MoveL' "$PROG")
    ;;
  tp) # UFRAME 1 and UTOOL 1 live in the controller: the cell's workobject and tool; P[n] in /POS
    PROG="$WORK/pass.ls"
    awk -v n="$N" 'function pos(k, x, z) {
        printf "P[%d]{\n   GP1:\n\tUF : 1, UT : 1,\t\tCONFIG : '"'"'N U T, 0, 0, 0'"'"',\n", k
        printf "\tX = %9.4f  mm,\tY =     0.000  mm,\tZ = %9.3f  mm,\n", x, z
        printf "\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg\n};\n" }
      BEGIN {
        m = n + 4
        print "/PROG  WALL_PASS"; print "/ATTR"; print "LINE_COUNT\t= " m + 2 ";"; print "/MN"
        print "   1:  UFRAME_NUM=1 ;"; print "   2:  UTOOL_NUM=1 ;"
        print "   3:J P[1] 50% CNT50 ;"; print "   4:L P[2] 250mm/sec CNT10 ;"
        for (i = 0; i < n; ++i) printf "%4d:L P[%d] 60mm/sec CNT100 ;\n", i + 5, i + 3
        printf "%4d:L P[%d] 60mm/sec CNT100 ;\n", n + 5, n + 3
        printf "%4d:L P[%d] 250mm/sec CNT50 ;\n", n + 6, n + 4
        print "/POS"
        pos(1, -60, 50); pos(2, -60, -5)
        for (i = 0; i < n; ++i) pos(i + 3, -50 + 120.0 * i / n, -5)
        pos(n + 3, 70, -5); pos(n + 4, 70, 50)
        print "/END" }' >"$PROG"
    points=$(grep -c '^ *[0-9]*:L ' "$PROG")
    ;;
  *) echo "bench-milling: BENCH_MILLING_DIALECT is krl, rapid or tp, not $DIALECT" >&2; exit 2 ;;
esac
KIND="milling"
[ "$DIALECT" = krl ] || KIND="milling $DIALECT"
# the sample cell with a robot of the program's vendor (compensate writes its configuration)
CELL="$WORK/cell.xml"
case "$DIALECT" in
  krl) ROBOT="kuka-kr120-r2500-pro" ;;
  rapid) ROBOT="abb-irb6700-200-260" ;;
  tp) ROBOT="fanuc-r2000ic-165f" ;;
esac
sed "s|<robot ref=\"[^\"]*\"/>|<robot ref=\"$ROBOT\"/>|" "$ROOT/samples/cells/alu-milling-7075.xml" >"$CELL"
echo "bench-milling: $points linear points ($DIALECT, $COMMAND), memory limit ${MEM_MB} MB," \
  "threads: $THREADS"
status=0
[ "$COMMAND" = forces ] && EXPORTS="json"
for e in $EXPORTS; do
  first=""
  for t in $THREADS; do
    out="$WORK/$e-$t"
    mkdir -p "$out"
    if [ "$COMMAND" = forces ]; then
      MEASURE_STDOUT="$out/f.json" measure "$out" bash -c 'ulimit -v $(('"$MEM_MB"' * 1024)); exec "$@"' \
        _ "$BIN" forces --threads "$t" --cell "$CELL" --program "$PROG"
      key="$KIND $N forces --program, --threads $t"
      outputs=(f.json)
    else
      measure "$out" bash -c 'ulimit -v $(('"$MEM_MB"' * 1024)); exec "$@"' _ "$BIN" compensate \
        --quiet --threads "$t" --cell "$CELL" "$PROG" \
        -o "$out/out.${PROG##*.}" --targets "$out/t.$e" --report "$out/r.html"
      key="$KIND $N --targets $e --report, --threads $t"
      outputs=("out.${PROG##*.}" "t.$e" r.html)
    fi
    # forces exits 1 when a point does not converge or chatters: its JSON is written all the same
    if [ "$MEASURE_RC" -ne 0 ] && ! { [ "$COMMAND" = forces ] && [ "$MEASURE_RC" -eq 1 ]; }; then
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
    else
      for o in "${outputs[@]}"; do
        if ! cmp -s "$first/$o" "$out/$o"; then
          echo "bench-milling: $o with --threads $t differs from the first run's" >&2
          status=1
        fi
      done
    fi
    if [ "$out" != "$first" ]; then
      for o in "${outputs[@]}"; do rm -f "${out:?}/$o"; done
    fi
  done
done
exit "$status"
