#!/usr/bin/env bash
# README's "Performance" table from one run of the benchmarks (a
# script, not a timed test): runs
#   build/bin/roprec_bench  (static deviation kernel vs KDL's linear kernel, PredictHole,
#                            the host's filter_target per call (Session),
#                            Compensate1000 keep / flip-free with allocations per hole,
#                            PredictHoles1000 allocations per hole, program ReadWrite per dialect,
#                            the 2 s drilling-cycle transient)
#   scripts/bench-cli.sh    (10,000 holes 1 vs 2 threads, 100,000-hole predict wall and RSS)
#   scripts/bench-large.sh  (1,000,000-hole predict / report / compensate, a 110 MB program
#                            converted between dialects, map, plan-test: wall and peak RSS)
#   scripts/bench-milling.sh  (a BENCH_MILLING_POINTS-point milling path, default 1,000,000,
#                            compensated with every export on 2 threads under 500 MB)
# and prints every row with its goal and whether it is met. Benchmark times are CPU medians of
# BENCH_REPS repetitions (default 3); CLI rows are the least wall time of BENCH_REPEAT runs
# (bench-cli.sh, default 3, 1 and 2 threads alternating), so a machine busy with other work lowers
# the 2-vs-1 speed-up and raises the wall times (say so when quoting).
#
#   scripts/bench-table.sh [BUILD_DIR]      (default build; needs -DROPREC_BUILD_BENCH=ON)
#
# BENCH_REPS  repetitions of each benchmark (default 3)
# BENCH_SKIP_CLI=1  benchmarks only (no bench-cli.sh or bench-large.sh run)
# BENCH_SKIP_LARGE=1  no bench-large.sh run (its BENCH_LARGE_* variables choose sizes and groups)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
BENCH="$BUILD/bin/roprec_bench"
REPS="${BENCH_REPS:-3}"
[ -x "$BENCH" ] || { echo "bench-table: $BENCH missing (configure with -DROPREC_BUILD_BENCH=ON)" >&2; exit 2; }
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT

FILTER='BM_Roprec_StaticDeviation$|BM_KDL_LinearCompliance$|BM_PredictHole$|BM_Session_FilterTargetCellDrill$|BM_PredictHoles1000/1|BM_Compensate1000|BM_ReadWrite|BM_DrillingCycle2s_Default$'
"$BENCH" --benchmark_filter="$FILTER" --benchmark_repetitions="$REPS" \
  --benchmark_report_aggregates_only=true --benchmark_format=json >"$OUT/bench.json" \
  2>"$OUT/bench.err" || { cat "$OUT/bench.err" >&2; exit 1; }
if [ "${BENCH_SKIP_CLI:-0}" != 1 ]; then
  BENCH_SIZES="10000 100000" BENCH_COMPENSATE_MAX=10000 \
    bash "$ROOT/scripts/bench-cli.sh" "$BUILD/bin/roprec" | tee "$OUT/cli.txt"
  if [ "${BENCH_SKIP_LARGE:-0}" != 1 ]; then
    bash "$ROOT/scripts/bench-large.sh" "$BUILD/bin/roprec" | tee -a "$OUT/cli.txt" || true
    BENCH_MILLING_THREADS=2 bash "$ROOT/scripts/bench-milling.sh" \
      "${BENCH_MILLING_POINTS:-1000000}" 500 "$BUILD/bin/roprec" | tee -a "$OUT/cli.txt" || true
  fi
fi

python3 - "$OUT/bench.json" "$OUT/cli.txt" <<'EOF'
import json, os, re, sys

bench = json.load(open(sys.argv[1]))
med = {}  # run name -> the median (or the single run when there is one repetition)
for b in bench["benchmarks"]:
    if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
        continue
    if b.get("run_type") == "iteration" and b["run_name"] in med:
        continue
    med[b["run_name"]] = b

def cpu(name, unit):  # CPU time of a median in `unit` ("us", "ms", "s")
    b = med[name]
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    return b["cpu_time"] * scale[b["time_unit"]] / scale[unit]

def real(name, unit):
    b = med[name]
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    return b["real_time"] * scale[b["time_unit"]] / scale[unit]

cli = {}
if os.path.exists(sys.argv[2]):
    for line in open(sys.argv[2]):
        m = re.match(r"(.+?)\s{2,}([\d.]+) s\s+(\d+) MiB", line)
        if m:
            cli[m.group(1).strip()] = (float(m.group(2)), int(m.group(3)))
        m = re.match(r"(.+?: 2 vs 1 threads)\s+([\d.]+)x", line)
        if m:
            cli[m.group(1).strip()] = float(m.group(2))

rows = []
def row(what, now, ok, goal):  # ok None: a row shown without a goal
    rows.append((what, now, goal, "" if ok is None else "met" if ok else "NOT met"))

k = cpu("BM_Roprec_StaticDeviation", "us")
kdl = cpu("BM_KDL_LinearCompliance", "us")
row("static deviation kernel / KDL linear kernel", "%.2f us / %.2f us = %.2fx" % (k, kdl, k / kdl),
    k / kdl <= 0.5, "<= 0.5x")
ph = cpu("BM_PredictHole", "us")
row("IK + full prediction per hole (PredictHole)", "%.2f us" % ph, ph <= 5.0, "<= 5 us")
ft = cpu("BM_Session_FilterTargetCellDrill", "us")
row("host filter_target per call (Session)", "%.2f us" % ft, ft <= 8.0, "<= 8 us")
c1 = real("BM_Compensate1000/1/iterations:1", "s")
row("1,000-hole compensation flip-free, one core", "%.3f s" % c1, c1 <= 0.15, "<= 0.15 s")
s = cli.get("compensate 10000: 2 vs 1 threads")
row("compensate 10000 holes, 2 vs 1 threads (CLI)", "%.2fx" % s if s else "not run",
    bool(s) and s >= 1.7, ">= 1.7x")
# a 0.1 s run: shown for reference, without a goal (the large predict rows carry the goal)
s = cli.get("predict 10000: 2 vs 1 threads")
row("predict 10000 holes, 2 vs 1 threads (CLI)", "%.2fx" % s if s else "not run", None, "-")
p = cli.get("predict 100000 holes, --threads 1")
p2 = cli.get("predict 100000 holes, --threads 2")
# the goal's 200 MB is 200e6 bytes = 190.7 MiB; 1 and 2 threads must both meet it
RSS_GOAL_MIB = 200e6 / 2**20
if p and p2:
    row("predict 100,000 holes: wall / peak RSS (CLI)",
        "%.2f s / %d MiB (1 thread); %.2f s / %d MiB (2)" % (p + p2),
        all(w <= 2.0 and m <= RSS_GOAL_MIB for w, m in (p, p2)), "<= 2 s / <= 200 MB (190.7 MiB)")
else:
    row("predict 100,000 holes: wall / peak RSS (CLI)", "not run", False,
        "<= 2 s / <= 200 MB (190.7 MiB)")
names = {0: "KRL", 1: "RAPID", 2: "TP", 3: "CSV", 4: "JSON"}
rates = []
for d in range(5):
    b = med.get("BM_ReadWrite/%d" % d)
    if b:
        rates.append((names[d], b["bytes_per_second"] / 1e6))
row("program read + write", ", ".join("%s %.0f" % r for r in rates) + " MB/s",
    all(r[1] >= 100 for r in rates) and len(rates) == 5, ">= 100 MB/s each")
t = real("BM_DrillingCycle2s_Default", "s")
row("drilling-cycle transient (2 s cycle)", "%.1f ms = %.0fx real time" % (t * 1e3, 2.0 / t),
    2.0 / t >= 200, ">= 200x")

# ---- large jobs (bench-large.sh): wall time and peak RSS against the goal of each workload; a
# row measured on a smaller job than the goal's (BENCH_LARGE_*) is shown but not met
MB, GB = 1e6 / 2**20, 1e9 / 2**20  # MiB per MB and per GB
# The goals are for the 2-core machine: a row is judged on its 2-thread runs (its 1-thread run,
# where there is one, is shown beside them). Runs of the goal's size are preferred to smaller ones
# (bench-cli.sh's 10,000-hole runs match the same names).
def large(what, pattern, wall_goal, rss_goal_mib, goal_text, size=None):
    got = [(k, cli[k]) for k in sorted(cli) if re.match(pattern, k) and isinstance(cli[k], tuple)]
    if size is not None and any(k.split()[1] == str(size) for k, _ in got):
        got = [(k, v) for k, v in got if k.split()[1] == str(size)]
    if not got:
        row(what, "not run", False, goal_text)
        return
    text = "; ".join("%.2f s / %d MiB (%s)" % (w, m, k.split(" ", 1)[1]) for k, (w, m) in got)
    judged = [(k, v) for k, v in got if k.endswith("--threads 2")] or got
    ok = all(w <= wall_goal and m <= rss_goal_mib for _, (w, m) in judged)
    if size is not None:
        ok = ok and all(k.split()[1] == str(size) for k, _ in judged)
    row(what, text, ok, goal_text)

large("predict 1,000,000 holes --json", r"predict \d+ --json", 10, 500 * MB,
      "<= 10 s / <= 500 MB", 1000000)
large("predict 1,000,000 holes, JSON on stdout", r"predict \d+ stdout", 10, 500 * MB,
      "<= 10 s / <= 500 MB", 1000000)
large("predict 1,000,000 holes --report", r"predict \d+ --report", 15, 2 * GB,
      "<= 15 s / <= 2 GB", 1000000)
for o in ("keep", "flip-free", "stiffest"):
    large("compensate 1,000,000 holes %s" % o, r"compensate \d+ %s," % o, 15, 3 * GB,
          "<= 15 s / <= 3 GB", 1000000)
large("compensate a 1,000,000-point milling path, every export, 2 threads",
      r"milling \d+ --targets \w+ --report, --threads 2", 60, 500 * MB, "<= 60 s / <= 500 MB",
      1000000)
conv = [k for k in sorted(cli) if k.startswith("convert ") and isinstance(cli[k], tuple)]
if conv:
    speeds = [(k.split(" MB ")[1], float(k.split()[1]) / cli[k][0], cli[k][1]) for k in conv]
    row("convert a 110 MB program, dialect -> dialect (MB of input/s)",
        ", ".join("%s %.0f MB/s %d MiB" % s for s in speeds),
        all(s >= 40 for _, s, _ in speeds), ">= 40 MB/s each")
else:
    row("convert a 110 MB program, dialect -> dialect", "not run", False, ">= 40 MB/s each")
large("map 1.2 x 1.6 m at 10 mm, 3 feeds", r"map ", float("inf"), float("inf"),
      "runs (cap >= 250,000 predictions)")
large("plan-test 64,000 candidates x 400 holes", r"plan-test ", 1.5, float("inf"), "<= 1.5 s")

pa = med.get("BM_PredictHoles1000/1/real_time", {}).get("allocs_per_hole")
ka = med.get("BM_Compensate1000/0/iterations:1", {}).get("allocs_per_hole")
fa = med.get("BM_Compensate1000/1/iterations:1", {}).get("allocs_per_hole")
fmt = lambda v: "?" if v is None else "%.2f" % v
row("heap allocations per hole: predict / keep / flip-free",
    "%s / %s / %s" % (fmt(pa), fmt(ka), fmt(fa)),
    all(v is not None and v < 0.01 for v in (pa, ka, fa)), "0 / 0 / 0")

w = max(len(r[0]) for r in rows)
g = max(len(r[2]) for r in rows)
print()
print("%-*s  %-52s %-*s  %s" % (w, "what", "measured", g, "goal", ""))
for r in rows:
    print("%-*s  %-52s %-*s  %s" % (w, r[0], r[1], g, r[2], r[3]))
EOF
