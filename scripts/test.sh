#!/usr/bin/env bash
# Same set-up as demo.sh (packages + Release build; here a compiler warning fails it), then the
# whole test suite but the benchmark scripts (label perf: `ctest -L perf`).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ROPREC_WITH_CHROMIUM=1 ROPREC_WARNINGS_FAIL=1 "$ROOT/scripts/setup.sh"
cd "$ROOT/build"
ctest --output-on-failure --parallel "$(nproc)" --timeout 900 -LE '^perf$'
