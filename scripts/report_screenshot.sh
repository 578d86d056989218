#!/bin/sh
# report_screenshot.sh OFFBENCH OUT.png - the picture of the nightly
# report (make report-screenshot): the synthetic five-night history of the
# browser test (tests/e2e/report_fixture.sh: one quality and one time step,
# one failed night) through scripts/report.py, photographed by headless
# Chromium (Debian chromium-headless-shell or chromium: OB_DEPS_BROWSER=1
# make deps; OB_CHROMIUM=PATH picks another).  Exit 2 without a browser.
set -eu
OB=$1 PNG=$2
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CHROME=${OB_CHROMIUM:-$(command -v chromium-headless-shell || command -v chromium || true)}
[ -n "$CHROME" ] || { echo "report_screenshot: no chromium-headless-shell or chromium (OB_DEPS_BROWSER=1 make deps)" >&2; exit 2; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
sh "$ROOT/tests/e2e/report_fixture.sh" "$OB" "$T/history" "$T/scratch"
/usr/bin/python3 "$ROOT/scripts/report.py" "$T/history" --out "$T/site"
timeout 90 "$CHROME" --headless --no-sandbox --disable-gpu --user-data-dir="$T/ud" --hide-scrollbars \
    --window-size=1100,1180 --screenshot="$T/shot.png" "file://$T/site/index.html" >/dev/null 2>&1
[ -s "$T/shot.png" ] || { echo "report_screenshot: $CHROME wrote no screenshot" >&2; exit 2; }
cp "$T/shot.png" "$PNG"
echo "report_screenshot: wrote $PNG ($(wc -c < "$PNG") bytes)" >&2
