#!/usr/bin/env bash
# [[layer]]s on the terrain of Maungawhau: points with labels from an attribute, a GPX track, a
# polygon with a hole, a point off the terrain (a warning naming it); the sidecar counts each
# layer's features and gives every label's box; the same layer written in NZTM (EPSG:2193) puts its
# labels where the GeoJSON in WGS84 does; hostile attribute values (markup, SDL, template braces,
# bad UTF-8, 10,000 characters) are text in the PNG, the PDF and the SVG, and never reach the .pov;
# a file GDAL cannot read, a layer or an attribute the file does not have are errors listing what it
# has (exit 2, nothing written); an empty layer is a warning; an over-large layer names its count
# and the limit.
# Usage: layers.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
cp "$src/tests/data/rasters/maungawhau-20m.tif" dem.tif
cp "$src/tests/data/vectors/maungawhau-walk.gpx" walk.gpx
cp "$src/tests/data/vectors/maungawhau-features.geojson" features.geojson
cat > base.toml <<'TOML'
[samples]
path = "dem.tif"
vertical_unit = "m"
[render]
width = 640
height = 420
[overlay]
title = "Maungawhau"
TOML
cat base.toml - > s.toml <<'TOML'
[[layer]]
path = "features.geojson"
label = "name"
legend = "Features"
fill = "#3060ff"
[[layer]]
path = "walk.gpx"
layer = "tracks"
legend = "Walk"
dash_px = [8, 5]
TOML
"$relief" render s.toml -o a/s.png 2> a.txt || { fail "the layers"; cat a.txt; }
grep -q 'warning: layer 1 (features.geojson): feature .* ("Rangitoto") at lon 174.860278, lat -36.786667 is off the terrain' a.txt ||
  { fail "no warning names the point off the terrain:"; cat a.txt; }
python3 - a/s.json <<'PY' || fail "the sidecar's layers and labels"
import json, sys
j = json.load(open(sys.argv[1]))
l1, l2 = j['layers']
assert (l1['features'], l1['points'], l1['polygons'], l1['drawn'], l1['off_terrain']) == (4, 3, 1, 3, 1), l1
assert (l2['layer'], l2['lines'], l2['drawn']) == ('tracks', 1, 1), l2
labels = [l for l in j['overlay']['labels'] if l['layer'] == 1]
assert {l['text'] for l in labels} == {'Maungawhau summit', 'Crater floor'}, labels
boxes = [l['box_px'] for l in j['overlay']['labels'] if 'box_px' in l]
for i, a in enumerate(boxes):
    assert 0 <= a[0] < a[2] <= 640 and 0 <= a[1] < a[3] <= 420, a
    for b in boxes[:i]:
        assert a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1], (a, b)
assert 'layer_legend' in j['overlay']['placement'], j['overlay']['placement']
PY
grep -q '^union {' a/s.pov || fail "no markers in the .pov"
grep -q '\[\[layer\]\] 2: walk.gpx: lines and outlines lying on the surface' a/s.pov || fail "no track in the .pov"

# The same features in NZTM, from a GeoPackage: the labels where the GeoJSON puts them.
ogr2ogr -f GPKG -t_srs EPSG:2193 features.gpkg features.geojson 2> /dev/null || fail "ogr2ogr"
sed 's/features.geojson/features.gpkg/' s.toml > nztm.toml
"$relief" render -q nztm.toml -o b/s.png 2> /dev/null || fail "the layer in NZTM"
python3 - a/s.json b/s.json <<'PY' || fail "the layer in NZTM is not where the one in WGS84 is"
import json, sys
a, b = ([(l['text'], l.get('box_px')) for l in json.load(open(p))['overlay']['labels'] if l['layer'] == 1] for p in sys.argv[1:])
assert len(a) == len(b) == 2, (a, b)
for (ta, ba), (tb, bb) in zip(a, b):
    assert ta == tb and all(abs(x - y) <= 0.2 for x, y in zip(ba, bb)), (ta, ba, tb, bb)
PY

# Hostile attribute values: text wherever the still is written, never in the .pov.
long=$(head -c 10000 /dev/zero | tr '\0' 'x')
printf 'lon,lat,name\n174.7644,-36.8767,"</svg> & <b>bold</b>"\n174.7630,-36.8745,"#fopen(""/etc/passwd"") {{terrain}}"\n174.7655,-36.8776,"bad \377 byte"\n174.7652,-36.8758,"%s"\n' "$long" > hostile.csv
cat base.toml - > hostile.toml <<'TOML'
[[layer]]
path = "hostile.csv"
label = "name"
TOML
for ext in png pdf svg; do
  "$relief" render -q hostile.toml -o "h/still.$ext" 2> "h-$ext.txt" || { fail "hostile labels to .$ext"; cat "h-$ext.txt"; }
done
grep -c -e '</svg>' -e 'fopen' -e '{{terrain}}' -e 'bold' h/still.pov | grep -qx 0 || fail "a label reached the .pov"
text=$(pdftotext h/still.pdf - 2> /dev/null | tr '\n' ' ')
for want in "</svg> & <b>bold</b>" '#fopen("/etc/passwd") {{terrain}}' "bad � byte" "xxxxxxxxxxxxxxxxxxxx"; do
  case "$text" in *"$want"*) ;; *) fail "pdftotext does not find '$want': $text" ;; esac
done
python3 - h/still.svg <<'PY' || fail "the SVG with hostile labels does not parse back with them as text"
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
texts = [''.join(e.itertext()) for e in root.iter('{http://www.w3.org/2000/svg}text')]
assert '</svg> & <b>bold</b>' in texts, texts
assert any(t.startswith('xxxxxxxx') and len(t) < 100 for t in texts), [t[:20] for t in texts]
PY

# Bad layers: exit 2, the error at the layer's key listing what the file has, nothing written.
bad() {  # bad NAME EXPECTED relief-arguments...
  local name=$1 want=$2; shift 2
  "$relief" render -q "$@" -o "bad-$name/x.png" 2> "$name.txt"; local code=$?
  [ "$code" = 2 ] || fail "$name: exit $code, expected 2"
  grep -qF -- "$want" "$name.txt" || { fail "$name: expected '$want', got:"; cat "$name.txt"; }
  [ -e "bad-$name" ] && [ -n "$(ls -A "bad-$name")" ] && fail "$name: left $(ls -A "bad-$name")"
}
echo "not a vector file" > notvector.geojson
printf '[[layer]]\npath = "notvector.geojson"\n' | cat base.toml - > notvector.toml
bad unreadable "notvector.toml:10:8: error: layer.path: notvector.geojson: GDAL reads no vector data in it" notvector.toml
printf '[[layer]]\npath = "walk.gpx"\nlayer = "track"\n' | cat base.toml - > nolayer.toml
bad no-layer 'walk.gpx has no layer "track"; its layers: "waypoints", "routes", "tracks", "route_points", "track_points"' nolayer.toml
printf '[[layer]]\npath = "features.geojson"\nlabel = "nmae"\n' | cat base.toml - > noattr.toml
bad no-attribute 'layer.label: layer "features" of features.geojson has no attribute "nmae"; its attributes: "name", "ele"' noattr.toml
printf '[[layer]]\npath = "features.geojson"\n[limits]\nmax_layer_vertices = 5\n' | cat base.toml - > big.toml
bad over-limit "layer 1 (features.geojson): more than 5 vertices, over limits.max_layer_vertices = 5" big.toml
printf '{"type": "FeatureCollection", "features": []}' > empty.geojson
printf '[[layer]]\npath = "empty.geojson"\n' | cat base.toml - > empty.toml
"$relief" render -q empty.toml -o e/x.png 2> empty.txt || { fail "an empty layer is not an error"; cat empty.txt; }
grep -q 'warning: layer 1 (empty.geojson, layer "empty") holds no feature to draw' empty.txt || { fail "empty layer:"; cat empty.txt; }
exit $status
