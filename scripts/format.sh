#!/usr/bin/env bash
# Applies .clang-format to every C/C++ source of the project, or with --check lists the files
# that are not formatted and exits 1 (CI runs the check).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
if ! command -v clang-format >/dev/null 2>&1; then
  echo "format: installing clang-format"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends clang-format >/dev/null
fi
mapfile -t FILES < <(git ls-files '*.cpp' '*.hpp' '*.h' '*.c')
if [[ "${1:-}" == "--check" ]]; then
  bad=()
  for f in "${FILES[@]}"; do
    if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then bad+=("$f"); fi
  done
  if ((${#bad[@]})); then
    printf 'format: not clang-formatted (run scripts/format.sh):\n' >&2
    printf '  %s\n' "${bad[@]}" >&2
    exit 1
  fi
  echo "format: ${#FILES[@]} files clang-formatted"
else
  clang-format -i "${FILES[@]}"
fi
