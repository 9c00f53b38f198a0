#!/usr/bin/env bash
# Runs clang-tidy (.clang-tidy) over the project's own sources with the compile commands of a
# configured build (build/ unless ROPREC_BUILD_DIR says otherwise: run scripts/demo.sh or
# scripts/test.sh first) and exits 1 when it reports anything, listing each warning once.
# Arguments: the files to check (default: every .cpp of compensator/, postproc/, plugin/ and
# tests/; ~10 minutes on 2 cores).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BUILD="${ROPREC_BUILD_DIR:-$ROOT/build}"
if [[ ! -f "$BUILD/compile_commands.json" ]]; then
  echo "tidy: $BUILD/compile_commands.json is missing (configure first: scripts/test.sh)" >&2
  exit 2
fi
if ! command -v run-clang-tidy >/dev/null 2>&1; then
  echo "tidy: installing clang-tidy"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends clang-tidy >/dev/null
fi
if (($#)); then
  PATTERN="$(printf '%s|' "$@" | sed 's/[.]/[.]/g; s/|$//')"
else
  PATTERN="$ROOT/(compensator|postproc|plugin|tests)/.*[.]cpp$"
fi
LOG="$(mktemp)"
trap 'rm -f "$LOG"' EXIT
run-clang-tidy -p "$BUILD" -j "$(nproc)" -quiet "$PATTERN" >"$LOG" 2>&1 || true
mapfile -t FOUND < <(sed 's/\x1b\[[0-9;]*m//g' "$LOG" | grep -E "^$ROOT/[^:]+:[0-9]+:[0-9]+: (warning|error):" | sort -u)
if ((${#FOUND[@]})); then
  printf 'tidy: %d finding(s):\n' "${#FOUND[@]}" >&2
  printf '  %s\n' "${FOUND[@]#"$ROOT/"}" >&2
  exit 1
fi
if grep -q "^Error while processing\|error: unable to" "$LOG"; then
  echo "tidy: clang-tidy failed:" >&2
  grep "^Error while processing\|error: unable to" "$LOG" | sort -u >&2
  exit 2
fi
echo "tidy: no finding"
