#!/usr/bin/env bash
# [render] quality = "high" (a sun of 2 degrees, sky light, finer antialiasing) on a real DEM:
# the .pov has the area light and the header says so; the still is the same bytes from 3 tiles
# as from one and on a second run; it differs from the report quality's still and is darker
# (sky light only takes light away); "draft" renders without antialiasing; a bad name is an
# error at its key listing the choices, exit 2.
# Usage: quality.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
cp "$src/tests/data/rasters/maungawhau-20m.tif" dem.tif
printf '[samples]\npath = "dem.tif"\nvertical_unit = "m"\n[lighting]\nsun_altitude_deg = 20\nsun_diameter_deg = 2\n[render]\nwidth = 240\nheight = 160\n[overlay]\nenabled = false\n' > s.toml
fail() { echo "FAIL: $*"; exit 1; }
"$relief" render -q s.toml -o report.png || fail "report did not render"
"$relief" render -q s.toml --set 'render.quality="high"' -o high.png || fail "high did not render"
"$relief" render -q s.toml --set 'render.quality="high"' --tiles 3 --jobs 2 -o tiles.png || fail "high in tiles"
"$relief" render -q s.toml --set 'render.quality="high"' -o again.png || fail "high again"
cmp high.png tiles.png || fail "high from 3 tiles is not the still's bytes"
cmp high.png again.png || fail "high differs between runs"
cmp -s high.png report.png && fail "high is the report's still"
grep -q 'area_light' high.pov || fail "no area light in high.pov"
grep -q 'area_light' report.pov && fail "an area light in report.pov"
grep -q '^// render.quality: high: the sun a disc 2 deg wide' high.pov || fail "header: $(grep quality high.pov)"
mean() { ffmpeg -loglevel error -i "$1" -vf format=gray,scale=1:1:flags=area -f rawvideo - | od -An -tu1 | tr -d ' '; }
m_report=$(mean report.png) m_high=$(mean high.png)
[ "$m_high" -lt "$m_report" ] || fail "high (mean $m_high) is not darker than report (mean $m_report)"
"$relief" render -q s.toml --set 'render.quality="draft"' -o draft.png || fail "draft did not render"
grep -q '^// render.quality: draft' draft.pov || fail "draft header"
out=$("$relief" render s.toml --set 'render.quality="best"' -o bad.png 2>&1); code=$?
[ $code -eq 2 ] || fail "bad quality: exit $code"
echo "$out" | grep -q 'render.quality' || fail "bad quality message: $out"
echo "$out" | grep -q 'draft' || fail "bad quality message lists no choices: $out"
[ -e bad.png ] && fail "bad quality left bad.png"
echo "PASS: high $m_high < report $m_report (mean grey), tiles and reruns identical"
