#!/usr/bin/env bash
# The README's sample job (predict: JSON + HTML report; compensate: program, targets export,
# report) run by the Windows package's roprec.exe under wine64 and by the Linux roprec: every
# output file, stdout and stderr must be byte-identical.
#   tests/windows/sample_job_test.sh --linux build/bin/roprec --zip build-windows/roprec-*-win64.zip --source .
set -euo pipefail
while (($#)); do
  case "$1" in
    --linux) LINUX="$(realpath "$2")"; shift 2 ;;
    --zip) ZIP="$(realpath "$2")"; shift 2 ;;
    --source) SRC="$(realpath "$2")"; shift 2 ;;
    *) echo "usage: $0 --linux ROPREC --zip ZIP --source DIR" >&2; exit 2 ;;
  esac
done
WINE="${WINE:-$(command -v wine64 || echo /usr/lib/wine/wine64)}"
[[ -x "$LINUX" ]] || { echo "sample_job_test: no Linux roprec at $LINUX (build it first)" >&2; exit 1; }
WORK="$(mktemp -d)"
trap '[[ -n "${KEEP:-}" ]] || rm -rf "$WORK"' EXIT
(cd "$WORK" && unzip -q "$ZIP")
EXE="$(find "$WORK" -path "*/bin/roprec.exe" | head -1)"
[[ -n "$EXE" ]] || { echo "sample_job_test: no bin/roprec.exe in $ZIP" >&2; exit 1; }

S="$SRC/samples"
JOBS=(
  "predict --cell $S/cells/housing-kr120.xml $S/emotor-housing/housing_kr120.src --holes $S/emotor-housing/holes.csv --json p.json --report p.html"
  "compensate --cell $S/cells/housing-kr120.xml $S/emotor-housing/housing_kr120.src --orientation flip-free -o corrected.src --targets corrected.json --report c.html"
)
mkdir -p "$WORK/linux" "$WORK/windows"
i=0
for job in "${JOBS[@]}"; do
  i=$((i + 1))
  read -r -a args <<<"$job"
  (cd "$WORK/linux" && "$LINUX" "${args[@]}" >"stdout.$i" 2>"stderr.$i"; echo $? >"rc.$i")
  (cd "$WORK/windows" && "$WINE" "$EXE" "${args[@]}" >"stdout.$i" 2>"stderr.$i"; echo $? >"rc.$i")
done
ls "$WORK/linux"
if ! diff -r "$WORK/linux" "$WORK/windows" >"$WORK/diff.txt"; then
  diff -rq "$WORK/linux" "$WORK/windows" >&2 || true
  cut -c1-300 "$WORK/diff.txt" | head -20 >&2
  echo "sample_job_test: the Windows outputs differ from Linux" >&2
  exit 1
fi
echo "sample_job_test: $(ls "$WORK/linux" | wc -l) files byte-identical (predict JSON + report, compensated program, targets, report, stdout/stderr)"
