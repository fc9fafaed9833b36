#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Screenshots for the docs, taken with Debian's headless Chromium (apt-get install -y chromium):
#   docs/screenshots/contact-sheet.png  the contact sheet of the bundled example frame, shown 1:1
#                                       on a page the way a browser shows the PNG
#   docs/screenshots/report.png         docs/report/index.html (summary table, plot, crops)
#   docs/screenshots/report-plot.png    docs/report/runtime-vs-error.svg alone
# Usage: bash scripts/screenshots.sh [AFNTOOL]   (default build/cli/afntool; run from anywhere)
# The report itself is regenerated with the command in docs/metrics.md, not here.
set -euo pipefail
cd "$(dirname "$0")/.."
AFNTOOL=${1:-build/cli/afntool}
CHROMIUM=${CHROMIUM:-chromium}
command -v "$CHROMIUM" >/dev/null || { echo "screenshots: $CHROMIUM not found (apt-get install -y chromium)"; exit 1; }
out=docs/screenshots
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

shot() { # shot URL FILE WIDTH HEIGHT
  "$CHROMIUM" --headless --no-sandbox --disable-gpu --hide-scrollbars --force-device-scale-factor=1 \
    --screenshot="$PWD/$2" --window-size="$3,$4" "$1" 2>/dev/null
}

# Contact sheet of the bundled example frame, on a page of its own size.
"$AFNTOOL" examples/sequence/frame.0000.exr --contact-sheet "$tmp/sheet.png" -q
size=$(oiiotool --info "$tmp/sheet.png" | sed -E 's/.*: *([0-9]+) x +([0-9]+),.*/\1 \2/')
read -r w h <<<"$size"
printf '<!DOCTYPE html><html><body style="margin:0;background:#333">%s</body></html>\n' \
  "<img src=\"sheet.png\" width=\"$w\" height=\"$h\" style=\"display:block;image-rendering:pixelated\">" \
  >"$tmp/sheet.html"
shot "file://$tmp/sheet.html" "$out/contact-sheet.png" "$w" "$h"

# The report page (first screens: summary, plot, crops) and the plot alone.
shot "file://$PWD/docs/report/index.html" "$out/report.png" 1400 2300
svg_w=$(sed -nE 's/^<svg[^>]* width="([0-9.]+)".*/\1/p' docs/report/runtime-vs-error.svg | cut -d. -f1)
svg_h=$(sed -nE 's/^<svg[^>]* height="([0-9.]+)".*/\1/p' docs/report/runtime-vs-error.svg | cut -d. -f1)
shot "file://$PWD/docs/report/runtime-vs-error.svg" "$out/report-plot.png" "$svg_w" "$svg_h"
echo "screenshots: wrote $out/contact-sheet.png, $out/report.png, $out/report-plot.png"
