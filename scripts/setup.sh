#!/usr/bin/env bash
# Installs the Debian 12 packages roprec needs (only the missing ones) and configures +
# builds Release into build/. Idempotent; quiet when everything is present.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libsundials-dev liburdfdom-dev libtinyxml2-dev libnlopt-cxx-dev libnlopt-dev
  nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  liborocos-kdl-dev libkdl-parser-dev
  pybind11-dev python3-pybind11 python3-dev python3-numpy
  locales  # tests/locale_test.cpp compiles a comma-decimal de_DE locale with localedef
  time     # scripts/bench-cli.sh: wall time and peak RSS (GNU time -v)
)
# chromium: tests/report_test.cpp renders the reports headless (a failure under CI=true without it);
# ROPREC_WITH_CHROMIUM=0 leaves it out on a machine that only builds
if [[ "${ROPREC_WITH_CHROMIUM:-1}" == "1" ]]; then PACKAGES+=(chromium); fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

BUILD="${ROPREC_BUILD_DIR:-$ROOT/build}"
GEN=()
if command -v ninja >/dev/null 2>&1; then GEN=(-G Ninja); fi
# ROPREC_CMAKE_ARGS is word-split; ROPREC_CMAKE_ARGV takes one argument per line (for values with
# spaces, e.g. "-DCMAKE_CXX_FLAGS=-fsanitize=address -fno-omit-frame-pointer").
EXTRA_ARGS=()
if [[ -n "${ROPREC_CMAKE_ARGV:-}" ]]; then mapfile -t EXTRA_ARGS <<<"$ROPREC_CMAKE_ARGV"; fi
if [[ ! -f "$BUILD/CMakeCache.txt" ]]; then
  cmake -S "$ROOT" -B "$BUILD" "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release ${ROPREC_CMAKE_ARGS:-} \
    "${EXTRA_ARGS[@]}" >/dev/null
fi
TARGETS=()
for t in ${ROPREC_BUILD_TARGETS:-}; do TARGETS+=(--target "$t"); done
LOG="$BUILD/build.log"
if ! cmake --build "$BUILD" --parallel "$(nproc)" "${TARGETS[@]}" >"$LOG" 2>&1; then
  grep -E "error|FAILED" "$LOG" | head -40 >&2
  echo "setup: build failed (full log: $LOG)" >&2
  exit 1
fi
# The tree builds without a compiler warning (GCC 12, -Wall -Wextra -Wpedantic -Wshadow ...):
# a warning is shown here, and is an error where ROPREC_WARNINGS_FAIL=1 (scripts/test.sh and
# scripts/sanitize.sh, so CI's clean builds keep it at none). Only the files compiled by this run
# are seen.
if grep -q "warning:" "$LOG"; then
  grep -E "warning:" "$LOG" | sort -u | head -40 >&2
  echo "setup: the build printed $(grep -c "warning:" "$LOG") compiler warning(s) (full log: $LOG)" >&2
  if [[ "${ROPREC_WARNINGS_FAIL:-0}" == 1 ]]; then exit 1; fi
fi
