#!/usr/bin/env bash
# A still as a print-ready PDF or SVG: the ray-traced image embedded once at its own pixels, the
# overlays as vector graphics and real text over it. pdftotext finds every string drawn (a hostile
# title too, as written), pdffonts says the fonts are embedded, pdfimages lists one image of the
# still's size, the page is the pixels at render.dpi (default 300); the same bytes on a second run
# and from 3 tiles. The SVG parses, holds the image and the strings as text. render.dpi goes into a
# PNG's pHYs chunk; a PNG without it has none. A still of another type is an error, exit 2.
# Usage: still_document.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
command -v pdftotext >/dev/null || { echo "SKIP: poppler-utils is not installed"; exit 77; }
enter_fresh_work
cp "$src/tests/data/rasters/maungawhau-20m.tif" dem.tif
cat > s.toml <<'TOML'
[samples]
path = "dem.tif"
vertical_unit = "m"
attribution = "LINZ CC BY 4.0 </svg> & <b>not bold</b>"
[render]
width = 480
height = 320
[overlay]
title = "Maungawhau </svg> #fopen {{x}}"
subtitle = "Mt Eden, Auckland"
TOML

"$relief" render -q s.toml -o a/still.pdf 2> a.txt || { fail "the PDF still"; cat a.txt; }
[ "$(cd a && ls | tr '\n' ' ')" = "still.drape.png still.height.png still.json still.pdf still.pov " ] ||
  fail "a/ holds $(ls a | tr '\n' ' ')"
text=$(pdftotext a/still.pdf - | tr '\n' ' ')
for want in "Maungawhau </svg> #fopen {{x}}" "Mt Eden, Auckland" "Elevation (m)" "LINZ CC BY 4.0 </svg> & <b>not bold</b>" \
            "at the centre of the view" "N"; do
  case "$text" in *"$want"*) ;; *) fail "pdftotext does not find '$want' in: $text" ;; esac
done
pdffonts a/still.pdf | awk 'NR > 2 && $(NF-4) != "yes" { bad = 1 } END { exit bad }' ||
  fail "a font is not embedded: $(pdffonts a/still.pdf)"
images=$(pdfimages -list a/still.pdf | awk 'NR > 2 { print $4 "x" $5 }' | tr '\n' ' ')
[ "$images" = "480x320 " ] || fail "pdfimages lists '$images', expected one image of 480x320"
# 480 x 320 pixels at 300 dpi: 115.2 x 76.8 points.
pdfinfo a/still.pdf | grep -q "Page size: *115.2 x 76.8 pts" || fail "page: $(pdfinfo a/still.pdf | grep 'Page size')"
grep -q '"pdf": ' a/still.json || fail "the sidecar does not name the PDF"

"$relief" render -q s.toml -o b/still.pdf --tiles 3 --jobs 2 || fail "the PDF from 3 tiles"
cmp -s a/still.pdf b/still.pdf || fail "the PDF differs between runs (1 tile and 3)"
"$relief" render -q s.toml --set render.dpi=96 -o c/still.pdf || fail "the PDF at 96 dpi"
pdfinfo c/still.pdf | grep -q "Page size: *360 x 240 pts" || fail "96 dpi page: $(pdfinfo c/still.pdf | grep 'Page size')"

"$relief" render -q s.toml -o d/still.svg || fail "the SVG still"
"$relief" render -q s.toml -o e/still.svg || fail "the SVG again"
cmp -s d/still.svg e/still.svg || fail "the SVG differs between runs"
python3 - d/still.svg <<'PY' || fail "the SVG does not parse back with its image and its strings as text"
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
ns = '{http://www.w3.org/2000/svg}'
assert root.tag == ns + 'svg', root.tag
assert root.get('width') in ('115.2pt', '115.2'), root.get('width')
images = [e for e in root.iter() if e.tag == ns + 'image']
assert images, 'no image'
texts = [''.join(e.itertext()) for e in root.iter() if e.tag == ns + 'text']
for want in ['Maungawhau </svg> #fopen {{x}}', 'Mt Eden, Auckland', 'Elevation (m)', 'LINZ CC BY 4.0 </svg> & <b>not bold</b>']:
    assert want in texts, (want, texts)
PY

# render.dpi in a PNG: a pHYs chunk of 150 dpi (5906 pixels a metre); none without it.
phys() {
  python3 - "$1" <<'PY'
import struct, sys
b = open(sys.argv[1], 'rb').read()
i = 8
while i < len(b):
    n, kind = struct.unpack('>I4s', b[i:i + 8])
    if kind == b'pHYs':
        x, y, unit = struct.unpack('>IIB', b[i + 8:i + 17])
        print(f'{x} {y} {unit}')
    i += 12 + n
PY
}
"$relief" render -q s.toml --set render.dpi=150 -o f/still.png || fail "the PNG at 150 dpi"
[ "$(phys f/still.png)" = "5906 5906 1" ] || fail "pHYs: '$(phys f/still.png)', expected '5906 5906 1'"
"$relief" render -q s.toml -o g/still.png || fail "the PNG without dpi"
[ -z "$(phys g/still.png)" ] || fail "a PNG without render.dpi has a pHYs chunk"

"$relief" render -q s.toml -o h/still.jpg 2> h.txt; code=$?
[ $code = 2 ] || fail "-o still.jpg: exit $code, expected 2"
grep -qF "h/still.jpg: error: a still is written as .png, .pdf or .svg" h.txt || { fail "-o still.jpg:"; cat h.txt; }
[ -e h ] && [ -n "$(ls -A h)" ] && fail "-o still.jpg left $(ls -A h)"

# Two point layers in the layer legend: each swatch a path of its own in the SVG (before the fix,
# the second swatch's path began with a line from where the first entry's text was drawn).
python3 - "$src/tests/data/vectors/maungawhau-features.geojson" > points.geojson <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
j['features'] = [f for f in j['features'] if f['geometry']['type'] == 'Point']
print(json.dumps(j))
PY
cat s.toml - > layers.toml <<'TOML'
[[layer]]
path = "points.geojson"
color = "#ff00ff"
legend = "Summits"
[[layer]]
path = "points.geojson"
color = "#00ffff"
legend = "Others"
TOML
"$relief" render -q layers.toml -o l/still.svg 2> l.txt || { fail "the SVG with two point layers"; cat l.txt; }
python3 - l/still.svg <<'PY' || fail "the layer legend's point swatches"
import re, sys
svg = open(sys.argv[1]).read()
for colour in ('100%,0%,100%', '0%,100%,100%'):
    paths = [d for style, d in re.findall(r'<path style="([^"]*)" d="([^"]*)"', svg) if f'fill:rgb({colour})' in style]
    assert paths, f'no swatch filled rgb({colour})'
    for d in paths:
        assert ' L ' not in d and d.count('M ') == 1, f'the swatch rgb({colour}) has a stray line: {d}'
PY
exit $status
