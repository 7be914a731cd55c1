#!/usr/bin/env bash
# `relief test` on a manifest with one passing and one failing case, then the
# HTML report opened from disk in headless Chromium: the DOM must show both
# cases (the failing one first), four images each, the passing case's four
# geometry checks with a plot of each curve, and the bless command; a
# screenshot is written for a person to look at.
# Usage: report_browser.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
command -v chromium >/dev/null || { echo "SKIP: chromium is not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
"$relief" test "$src/tests/cli/report/manifest.toml" --report "$work/report" > "$work/stdout.txt"
code=$?
cat "$work/stdout.txt"
status=0
fail() { echo "FAIL: $*"; status=1; }
[ "$code" = 1 ] || fail "exit code $code, expected 1"
grep -q '^1 passed, 1 failed$' "$work/stdout.txt" || fail "summary line"
grep -q '<failure message="FAIL">' "$work/report/junit.xml" || fail "junit.xml has no failure"
grep -q '"failed": 1' "$work/report/summary.json" || fail "summary.json"

chrome=(chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run
        --disable-background-networking --disable-component-update --disable-sync
        --user-data-dir="$work/chrome-profile")
timeout 120 "${chrome[@]}" --dump-dom "file://$work/report/index.html" > "$work/dom.html" 2>"$work/chrome.log"
cases=$(grep -o 'class="case [a-z]*"' "$work/dom.html" | tr '\n' ' ')
echo "cases in the DOM: $cases"
[ "$cases" = 'class="case fail" class="case pass" ' ] || fail "expected the failing case first, then the passing one"
images=$(grep -o '<img ' "$work/dom.html" | wc -l)
echo "images in the DOM: $images"
[ "$images" = 11 ] || fail "expected 11 images (new, hover reference, reference, difference per case; 3 plots)"
checks=$(grep -o '<tr class="check">' "$work/dom.html" | wc -l)
[ "$checks" = 4 ] || fail "expected 4 geometry checks in the DOM, found $checks"
grep -q '<td>profile 174.7618,-36.8760:174.7680,-36.8760</td><td>0.000 m</td><td>0.010 m</td><td>pass</td>' "$work/dom.html" ||
  fail "the profile's check is not shown with its distance, tolerance and verdict"
[ "$(grep -o 'class="geometry-plot"' "$work/dom.html" | wc -l)" = 3 ] || fail "expected 3 plots of curves"
grep -q 'id="bless"' "$work/dom.html" || fail "no bless command line"
grep -q '1 passed, 1 failed, 2 cases' "$work/dom.html" || fail "summary paragraph"
for img in $(grep -o 'src="[^"]*"' "$work/dom.html" | cut -d'"' -f2 | sort -u); do
  [ -s "$work/report/$img" ] || fail "image $img missing from the report folder"
done
timeout 120 "${chrome[@]}" --window-size=1100,1300 --screenshot="$work/screenshot.png" \
  "file://$work/report/index.html" 2>>"$work/chrome.log"
[ -s "$work/screenshot.png" ] || fail "no screenshot"
echo "screenshot: $work/screenshot.png"
exit $status
