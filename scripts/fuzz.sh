#!/usr/bin/env bash
# Builds a libFuzzer harness per robot-program reader (clang, ASan + UBSan) and runs each one.
# Not part of CI. FUZZ_SECONDS (default 600 = 10 min) per reader; FUZZ_JOBS parallel workers
# (default 1). Seeds: tests/fuzz/seeds/<dialect>/; crashes are copied to tests/fuzz/crashes/.
# Usage: scripts/fuzz.sh [krl|rapid|tp|csv|json ...]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SECONDS_PER="${FUZZ_SECONDS:-600}"
JOBS="${FUZZ_JOBS:-1}"
CXX="${FUZZ_CXX:-clang++}"
OUT="${FUZZ_BUILD:-$ROOT/build-fuzz}"
mkdir -p "$OUT" "$ROOT/tests/fuzz/crashes"
readers=("$@")
[ ${#readers[@]} -eq 0 ] && readers=(krl rapid tp csv json)
SRC=("$ROOT"/postproc/*.cpp "$ROOT/compensator/support/rotation.cpp" "$ROOT/compensator/support/error.cpp" "$ROOT/compensator/support/atomic_file.cpp")
FLAGS=(-std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
       -I"$ROOT" -I/usr/include/eigen3)
declare -A NUM=([krl]=0 [rapid]=1 [tp]=2 [csv]=3 [json]=4)
for r in "${readers[@]}"; do
  n="${NUM[$r]:?unknown reader $r}"
  bin="$OUT/fuzz_$r"
  echo "== building $bin"
  "$CXX" "${FLAGS[@]}" -DROPREC_FUZZ_DIALECT="$n" "${SRC[@]}" "$ROOT/tests/fuzz/postproc_fuzz.cpp" -o "$bin"
  corpus="$OUT/corpus_$r"
  mkdir -p "$corpus"
  rm -f "$OUT"/artifact_"${r}"_*
  echo "== fuzzing $r for ${SECONDS_PER}s"
  set +e
  work="$OUT/work_$r"  # libFuzzer's -jobs writes fuzz-N.log into the cwd: one folder per reader
  mkdir -p "$work"
  rm -f "$work"/fuzz-*.log
  (cd "$work" && "$bin" "$corpus" "$ROOT/tests/fuzz/seeds/$r" -max_total_time="$SECONDS_PER" -max_len=16384 \
     -timeout=10 -rss_limit_mb=2048 -jobs="$JOBS" -workers="$JOBS" -artifact_prefix="$OUT/artifact_${r}_" \
     -print_final_stats=1 2>&1 | tail -n 25)
  rc=${PIPESTATUS[0]}
  set -e
  if ls "$OUT"/artifact_"${r}"_* >/dev/null 2>&1; then
    for a in "$OUT"/artifact_"${r}"_*; do cp "$a" "$ROOT/tests/fuzz/crashes/$r-$(basename "$a" | sed "s/^artifact_${r}_//")"; done
    echo "== $r: crash/timeout artifacts copied to tests/fuzz/crashes/"
    exit 1
  fi
  echo "== $r: no crash (libFuzzer exit $rc)"
done
