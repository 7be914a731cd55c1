#!/usr/bin/env bash
# The panoramic and spherical cameras (camera.projection): POV-Ray's cylinder 1 and spherical from
# a place on Maungawhau, looking level (the horizon across the still's middle: sky in its top row,
# ground in its bottom row); the same bytes from 1 tile and from 3; only the title and the credits
# over them (a legend, a scale bar, a north arrow or labels would not be true on such an image).
# Usage: wide_cameras.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
cp "$src/tests/data/rasters/maungawhau-20m.tif" dem.tif
cat > wide.toml <<'TOML'
[samples]
path = "dem.tif"
vertical_unit = "m"
[subdivision]
depth = 0
[camera]
position = [174.7620, -36.8790, 120]
look_at = [174.7640, -36.8765, 150]
[render]
width = 240
height = 120
antialias = false
[overlay]
enabled = true
title = "Maungawhau"
[[layer]]
path = "summit.geojson"
label = "name"
TOML
cat > summit.geojson <<'JSON'
{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "summit"},
 "geometry": {"type": "Point", "coordinates": [174.7640, -36.8765]}}]}
JSON
for kind in panoramic spherical; do
  "$relief" render -q wide.toml --set "camera.projection=\"$kind\"" -o "$kind/one.png" 2> "$kind.txt" ||
    { fail "the $kind still"; cat "$kind.txt"; continue; }
  "$relief" render -q wide.toml --set "camera.projection=\"$kind\"" --tiles 3 -o "$kind/three.png" ||
    fail "the $kind still in 3 tiles"
  cmp -s "$kind/one.png" "$kind/three.png" || fail "the $kind still differs between 1 tile and 3"
  python3 - "$kind" <<'PY' || fail "the $kind still"
import json, subprocess, sys
kind = sys.argv[1]
pov = open(f'{kind}/one.pov').read()
want = {'panoramic': 'cylinder 1', 'spherical': 'spherical'}[kind]
assert f'\n  {want}\n' in pov, f'no "{want}" camera in the .pov'
j = json.load(open(f'{kind}/one.json'))
assert j['overlay']['drawn'] == ['title', 'credits'], j['overlay']['drawn']
# Level: the sky above the horizon, the ground below it (rows of RGB from oiiotool).
def row(y):
    out = subprocess.run(['oiiotool', f'{kind}/one.png', '--cut', f'240x1+0+{y}', '--ch', 'R,G,B', '-d', 'uint8',
                          '-o', 'row.ppm'], capture_output=True)
    assert out.returncode == 0, out.stderr
    data = open('row.ppm', 'rb').read().split(b'\n', 3)[3]
    return [tuple(data[i:i + 3]) for i in range(0, len(data), 3)]
sky = sum(b > r + 20 for r, g, b in row(0)) / 240  # the top row: above the title
ground = sum(not (b > r + 20) for r, g, b in row(119)) / 240  # the bottom row: below the credits
assert sky > 0.9 and ground > 0.9, (sky, ground)
PY
done
# An orbit film of panoramas wider than 180 degrees: one distance for its frames, placed as the
# default perspective camera would be (its angle once gave a negative distance).
if command -v ffmpeg > /dev/null; then
  sed -e '/^position/d' -e '/^look_at/d' wide.toml > orbit.toml
  printf '[animation]\nframes = 2\npath = "orbit"\n' >> orbit.toml
  "$relief" animate -q orbit.toml --set 'camera.projection="panoramic"' --set camera.fov_deg=200 -o film/orbit.mp4 \
    2> orbit.txt || { fail "an orbit of 200 degree panoramas"; cat orbit.txt; }
fi
# Only a panorama is wider than a perspective camera: fov_deg 200 is refused there, with the way out.
"$relief" compile -q wide.toml --set camera.fov_deg=200 -o bad/x.pov 2> bad.txt; code=$?
[ "$code" = 2 ] && grep -q 'camera.fov_deg = 200 is wider than a perspective camera takes (170): for a wider view use camera.projection = "panoramic"' bad.txt ||
  { fail "fov_deg 200 on a perspective camera: exit $code"; cat bad.txt; }
exit $status
