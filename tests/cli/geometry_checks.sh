#!/usr/bin/env bash
# Geometry checks in relief test: a case with a profile, two contour levels and the peak loss is new
# until --update keeps its curves beside its image; then it passes. A scheme parameter changed so
# little that the still passes at --fail 0.04 moves a profile by more than its tolerance: the case
# fails by its geometry (exit 1), and the report, summary.json and junit.xml say which check, by how
# much, against what tolerance, with a plot of both curves. A kept geometry.json that cannot be
# read (huge coordinates, not JSON, a FIFO, too big) makes the case an error, which --update leaves
# alone. Bad geometry keys are errors at their lines (exit 2).
# Usage: geometry_checks.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
mkdir suite
cp "$src/tests/golden/small/samples.csv" suite/
sed -e 's/^omega = "1\/32"/omega = 0.03125/' "$src/tests/golden/small/scene.toml" > suite/scene.toml
cat > suite/manifest.toml <<'TOML'
[defaults]
fail = 0.04           # loose: a change too small to see passes by its pixels
failpercent = 0.1
hardfail = 1

[[case]]
name = "maungawhau"
scene = "scene.toml"
references = "ref"
profile = "174.7618,-36.8760:174.7680,-36.8760"
levels = [140, 170]
tolerance_m = 0.05
peak_loss_tolerance_m = 0.05
TOML

"$relief" test suite/manifest.toml --report r1 > r1.txt 2>&1; code=$?
[ $code = 1 ] || fail "a case without references: exit $code, expected 1"
grep -q "NEW .*geometry: no kept curves" r1.txt || { fail "the new case does not say its curves are not kept:"; cat r1.txt; }

"$relief" test suite/manifest.toml --update --report r2 > r2.txt 2>&1
[ -f suite/ref/ref.png ] && [ -f suite/ref/geometry.json ] || fail "--update kept $(ls suite/ref 2>/dev/null | tr '\n' ' ')"
"$relief" test suite/manifest.toml --report r3 > r3.txt 2>&1 || { fail "the blessed case does not pass:"; cat r3.txt; }
grep -q "PASS .*geometry: 4 checks within their tolerances" r3.txt || { fail "no geometry verdict:"; cat r3.txt; }

# Kept curves that cannot be read are an error naming the file, never "no curves kept": the case
# errs (exit 1, not NEW), and --update leaves the file and the image as they are (shown for two). A
# coordinate of 1e300 (which crashed relief test), a file that is not JSON, one of another shape, a
# FIFO (taken for no curves, and replaced by --update), one over the 64 MB a curve file may be.
kept=suite/ref/geometry.json
cp "$kept" kept.json && cp suite/ref/ref.png kept.png
python3 - kept.json huge.json <<'PY' || fail "the geometry file with a coordinate of 1e300"
import json, sys
j = json.load(open(sys.argv[1]))
j['profiles'][0]['points'][3] = [1e300, 0]
json.dump(j, open(sys.argv[2], 'w'))
PY
damaged() {  # damaged NAME EXPECTED_PROBLEM [--update]: the case with the kept file the caller made
  local name=$1 want=$2 line
  line="[1/1] ERROR   maungawhau: geometry: $kept: $want; remove it, and relief test --update keeps the new curves there"
  for update in "" ${3:-}; do
    timeout 60 "$relief" test suite/manifest.toml $update --report "d-$name" > "d-$name.txt" 2>&1; local code=$?
    [ $code = "$([ -z "$update" ] && echo 1 || echo 0)" ] || fail "$name $update: exit $code"
    [ "$(grep maungawhau "d-$name.txt" | sed 's/ ([0-9.]* s):/:/')" = "$line" ] ||
      { fail "$name $update: the case is not an error naming the file:"; cat "d-$name.txt"; }
  done
  cmp -s suite/ref/ref.png kept.png || fail "$name: --update replaced the image"
}
cp huge.json "$kept"
damaged huge-coordinate "profiles[0].points[3] = [1e+300, 0] is beyond the 1e+15 a coordinate may be (in metres, 1e15 is a thousand times the distance to the Sun)" --update
cmp -s huge.json "$kept" || fail "huge-coordinate: --update replaced the kept curves"
head -c 100 kept.json > "$kept"
damaged not-json "it is not JSON"
echo '{"relief_geometry": 1, "frame": "utm", "profiles": {}, "levels": [], "peak_loss_m": 0}' > "$kept"
damaged other-shape "it is not the geometry file relief test writes"
rm "$kept" && mkfifo "$kept"
damaged fifo "it is a FIFO (a named pipe), not a file" --update
[ -p "$kept" ] || fail "fifo: --update replaced the FIFO"
rm "$kept" && truncate -s 65000001 "$kept"
damaged too-big "it is 65 MB, more than the 64 MB such a file may be"
cp kept.json "$kept"

# omega 1/32 -> 0.034: the still within --fail 0.04, the profile moved by more than 5 cm.
sed -i 's/^omega = 0.03125/omega = 0.034/' suite/scene.toml
"$relief" test suite/manifest.toml --report r4 > r4.txt 2>&1; code=$?
[ $code = 1 ] || { fail "a case that fails by its geometry: exit $code, expected 1"; cat r4.txt; }
grep -q "FAIL .*ref.png: .* (0.0[0-9]* %) over 0.04; geometry: profile 174.7618,-36.8760:174.7680,-36.8760 moved [0-9.]* m > 0.050 m" r4.txt ||
  { fail "the failing check is not named with its distance and tolerance:"; cat r4.txt; }
python3 - r4/summary.json <<'PY' || fail "summary.json: the pixels pass and the profile fails"
import json, sys
case = json.load(open(sys.argv[1]))['cases'][0]
assert case['status'] == 'FAIL', case['status']
assert case['metrics']['failing_percent'] < 0.1, case['metrics']  # the pixels pass
profile = [g for g in case['geometry'] if g['check'].startswith('profile')][0]
assert not profile['pass'] and profile['distance_m'] > 0.05, profile
PY
grep -q 'class="metrics geometry"' r4/index.html || fail "the report has no geometry table"
grep -q 'geometry-plot' r4/index.html || fail "the report has no plot of the curves"
ls r4/images/maungawhau.geometry-1.svg > /dev/null || fail "no plot beside the report's images"
python3 -c "import xml.etree.ElementTree as E, sys; E.parse(sys.argv[1])" r4/images/maungawhau.geometry-1.svg ||
  fail "the plot is not SVG"
grep -q 'geometry: profile' r4/junit.xml || fail "junit.xml does not name the geometry failure"

# Bad keys: exit 2 at their lines.
cat > suite/bad.toml <<'TOML'
[[case]]
name = "bad"
scene = "scene.toml"
references = "ref"
profile = "174.76 -36.87 to 174.77"
levels = ["high"]
TOML
"$relief" test suite/bad.toml --report r5 > r5.txt 2>&1; code=$?
[ $code = 2 ] || fail "bad geometry keys: exit $code, expected 2"
grep -q 'bad.toml:5:11: error: profile "174.76 -36.87 to 174.77" is not "LON,LAT:LON,LAT"' r5.txt || { fail "bad profile:"; cat r5.txt; }
grep -q 'bad.toml:6:10: error: levels must be a list of elevations' r5.txt || { fail "bad levels:"; cat r5.txt; }
exit $status
