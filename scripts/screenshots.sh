#!/usr/bin/env bash
# The README's screenshots: the demo's prediction report (maps in the part frame, verdict
# outlines, failing ids, t/2 on the bars) and a `roprec map` work-area report, rendered with
# headless Chromium (installed by scripts/setup.sh) into docs/img/report.png and docs/img/map.png.
#
# Builds nothing: uses build/bin/roprec, or the binary named by ROPREC=path.
# Usage: scripts/screenshots.sh            (writes docs/img/*.png, each checked < 400 kB)
#        OUT=/tmp/shots scripts/screenshots.sh   (writes there instead; for a look first)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${ROPREC:-$ROOT/build/bin/roprec}"
OUT="${OUT:-$ROOT/docs/img}"
MAX_BYTES=400000
if [[ ! -x "$BIN" ]]; then
  echo "screenshots.sh: no roprec binary at $BIN: build it (scripts/demo.sh) or set ROPREC=path" >&2
  exit 2
fi
CHROMIUM="$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)"
if [[ -z "$CHROMIUM" ]]; then
  echo "screenshots.sh: chromium not found: run scripts/setup.sh (installs it) or install chromium" >&2
  exit 2
fi
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
mkdir -p "$OUT"
CELL="$ROOT/samples/cells/housing-kr120.xml"
PROG="$ROOT/samples/emotor-housing/housing_kr120.src"
HOLES="$ROOT/samples/emotor-housing/holes.csv"

# 1. the demo's prediction report (scripts/demo.sh step 1; exit 1 = some holes listed, written)
set +e
"$BIN" predict --cell "$CELL" "$PROG" --holes "$HOLES" --quiet --json "$WORK/p.json" \
  --report "$WORK/report.html" >/dev/null 2>&1
rc=$?
"$BIN" map --cell "$CELL" --region "-300 -300 250 300 300 250" --direction "0 0 -1" \
  --feeds "0.1 0.2" --step 50 --report "$WORK/map.html" --quiet >/dev/null
rc_map=$?
set -e
if [[ $rc -gt 1 || $rc_map -gt 1 || ! -f "$WORK/report.html" || ! -f "$WORK/map.html" ]]; then
  echo "screenshots.sh: roprec failed (predict exit $rc, map exit $rc_map)" >&2
  exit 1
fi

# 2. headless Chromium, 1400 x 1000 CSS px. The page is shown in a 1400 x 1000 iframe of a
#    wrapper page so that a fragment (#maps: the prediction report's maps, below its header)
#    scrolls it; the report itself is not changed.
shot() {  # shot PAGE.html[#fragment] OUT.png
  local frame
  frame="$WORK/frame-$(basename "$2" .png).html"
  printf '%s\n' '<!DOCTYPE html><html><head><meta charset="utf-8"><style>html,body{margin:0;overflow:hidden}' \
    'iframe{border:0;width:1400px;height:1000px;display:block}</style></head><body>' \
    "<iframe src=\"file://$1\"></iframe></body></html>" >"$frame"
  "$CHROMIUM" --headless --no-sandbox --disable-gpu --no-first-run --hide-scrollbars \
    --window-size=1400,1000 --virtual-time-budget=5000 --screenshot="$2" "file://$frame" \
    >/dev/null 2>&1
  [[ -s "$2" ]] || { echo "screenshots.sh: chromium wrote no $2" >&2; exit 1; }
  if command -v pngquant >/dev/null; then  # optional: a palette PNG is a third of the size
    pngquant --force --skip-if-larger --output "$2" -- "$2" || true
  fi
  local bytes
  bytes=$(stat -c %s "$2")
  if [[ $bytes -ge $MAX_BYTES ]]; then
    echo "screenshots.sh: $2 is $bytes bytes (limit $MAX_BYTES)" >&2
    exit 1
  fi
  echo "$2 ($bytes bytes)"
}
shot "$WORK/report.html#maps" "$OUT/report.png"
shot "$WORK/map.html" "$OUT/map.png"
