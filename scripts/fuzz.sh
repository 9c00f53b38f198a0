#!/usr/bin/env bash
# The libFuzzer campaign: one harness per reader (tests/fuzz/<reader>_fuzz.cpp; the program
# dialects share tests/fuzz/postproc_fuzz.cpp), built through CMake with clang and ROPREC_FUZZ=ON
# in build-fuzz/ (every object with -fsanitize=fuzzer-no-link,address,undefined, the harnesses
# linked with -fsanitize=fuzzer), then each one run for FUZZ_SECONDS.
#
#   scripts/fuzz.sh [READER...]   readers: hole_list measured cell robot_card urdf krl rapid tp csv json
#
# FUZZ_SECONDS   seconds per harness (default 60)
# FUZZ_JOBS      parallel libFuzzer workers per harness (default 1)
# FUZZ_BUILD     build folder (default build-fuzz/)
# FUZZ_BUILD_JOBS  compile jobs (default nproc)
# FUZZ_NO_BUILD=1  run the binaries already in FUZZ_BUILD (no configure, no build)
# FUZZ_KEEP_GOING=1  do not stop at the first finding (libFuzzer -fork=JOBS -ignore_crashes=1 ...):
#                  collects every distinct finding of the FUZZ_SECONDS
#
# Inputs: tests/fuzz/seeds/<reader>/ (read only) plus the growing corpus build-fuzz/corpus/<reader>/.
# A crash, sanitizer report, undocumented exception, timeout (> 10 s per input) or out-of-memory
# is copied to tests/fuzz/crashes/<reader>/ (the three smallest; all stay in build-fuzz/artifacts/); replay it with build-fuzz/bin/fuzz_<reader> FILE
# (or the ctest build's bin/fuzz_seed_<reader> FILE). Exit 1 when any harness found something.
# Not part of CI (.ci/run); CI replays the seeds as the ctests fuzz_seed_<reader>.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SECONDS_PER="${FUZZ_SECONDS:-60}"
JOBS="${FUZZ_JOBS:-1}"
BUILD="${FUZZ_BUILD:-$ROOT/build-fuzz}"
ALL=(hole_list measured cell robot_card urdf krl rapid tp csv json)
readers=("$@")
[ ${#readers[@]} -eq 0 ] && readers=("${ALL[@]}")
for r in "${readers[@]}"; do
  [[ " ${ALL[*]} " == *" $r "* ]] || { echo "fuzz: unknown reader '$r' (readers: ${ALL[*]})" >&2; exit 2; }
done
command -v clang++ >/dev/null || { echo "fuzz: clang++ not found (apt-get install clang)" >&2; exit 2; }

ARGS=(
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DROPREC_FUZZ=ON
  -DCMAKE_BUILD_TYPE=RelWithDebInfo
  # -O1 with line tables and assertions (Eigen's bounds checks are on): fast enough to fuzz,
  # useful stacks.
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1"
  -DROPREC_BUILD_BENCH=OFF -DROPREC_BUILD_PYTHON=OFF
)
if command -v ccache >/dev/null 2>&1; then
  ARGS+=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
if [ -z "${FUZZ_NO_BUILD:-}" ]; then
  cmake -S "$ROOT" -B "$BUILD" "${ARGS[@]}" >/dev/null
  targets=()
  for r in "${readers[@]}"; do targets+=("fuzz_$r"); done
  cmake --build "$BUILD" --parallel "${FUZZ_BUILD_JOBS:-$(nproc)}" --target "${targets[@]}"
fi

export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
found=()
summary=()
for r in "${readers[@]}"; do
  bin="$BUILD/bin/fuzz_$r"
  corpus="$BUILD/corpus/$r"
  art="$BUILD/artifacts/$r"
  work="$BUILD/work/$r"  # libFuzzer's -jobs writes fuzz-N.log into the cwd
  log="$BUILD/logs/$r.log"
  mkdir -p "$corpus" "$art" "$work" "$(dirname "$log")"
  rm -f "$art"/* "$work"/fuzz-*.log
  par=()
  if [ -n "${FUZZ_KEEP_GOING:-}" ]; then
    par=(-fork="$JOBS" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  elif [ "$JOBS" -gt 1 ]; then
    par=(-jobs="$JOBS" -workers="$JOBS")
  fi
  echo "== fuzzing $r for ${SECONDS_PER}s ($bin)"
  set +e
  (cd "$work" && "$bin" "$corpus" "$ROOT/tests/fuzz/seeds/$r" -max_total_time="$SECONDS_PER" \
     -max_len=16384 -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$art/" -print_final_stats=1 \
     "${par[@]}" >"$log" 2>&1)
  rc=$?
  set -e
  if [ "$JOBS" -gt 1 ]; then cat "$work"/fuzz-*.log >>"$log" 2>/dev/null || true; fi
  execs=$( (grep -h 'stat::number_of_executed_units' "$log" || true) | awk '{s += $2} END {print s + 0}')
  if [ "$execs" = 0 ]; then  # fork mode prints no final stats: the last "#N" progress line
    execs=$( (grep -oE '^#[0-9]+' "$log" || true) | tail -n 1 | tr -d '#')
    execs=${execs:-0}
  fi
  ncorp=$(find "$corpus" -type f | wc -l)
  if compgen -G "$art/*" >/dev/null; then
    mkdir -p "$ROOT/tests/fuzz/crashes/$r"
    # the three smallest reproducers (FUZZ_KEEP_GOING can collect many of the same finding)
    ls -S -r "$art"/* | head -n 3 | xargs -I{} cp {} "$ROOT/tests/fuzz/crashes/$r/"
    grep -hE 'ERROR: |runtime error|==[0-9]+==|^    #[0-9] ' "$log" | head -n 20 || true
    nart=$(ls "$art" | wc -l)
    echo "== $r: FOUND $nart reproducer(s) in $art -> tests/fuzz/crashes/$r/ (log $log)"
    found+=("$r")
    summary+=("$(printf '%-11s %5ss %10s execs %6s corpus  FOUND: %s reproducer(s)' "$r" "$SECONDS_PER" "$execs" "$ncorp" "$nart")")
  else
    echo "== $r: no finding (libFuzzer exit $rc, $execs executions, corpus $ncorp files)"
    summary+=("$(printf '%-11s %5ss %10s execs %6s corpus  no finding' "$r" "$SECONDS_PER" "$execs" "$ncorp")")
  fi
done
echo "== summary"
printf '%s\n' "${summary[@]}"
if [ ${#found[@]} -gt 0 ]; then
  echo "fuzz: findings in: ${found[*]}" >&2
  exit 1
fi
