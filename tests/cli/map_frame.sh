#!/usr/bin/env bash
# [overlay] frame swept over what a map is made of: a LiDAR DEM in NZTM (seconds of arc), a
# Pseudo-Mercator continent (degrees), a geographic raster put in UTM, framed in degrees and in
# metres, landscape and portrait, with a title, a subtitle or none. In every still:
# - the neat line is drawn where the sidecar says the map is (its pixels dark), the terrain inside it;
# - every annotation is centred on its tick and outside the map on its own side, inside the still,
#   clear of every other annotation and of every furniture item; each side has one at least;
# - every furniture item is drawn (none left out) and inside the still.
# Usage: map_frame.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
stills=(
  "nztm $src/tests/data/rasters/maungawhau-20m.tif 960 600 degrees title"
  "nztm-metres $src/tests/data/rasters/maungawhau-20m.tif 600 800 metres none"
  "asia $src/scenes/data/rasters/asia.tif 800 500 degrees subtitle"
  "cyl $src/scenes/data/rasters/cyl_elev.tif 960 600 degrees title"
  "cyl-metres $src/scenes/data/rasters/cyl_elev.tif 600 800 metres subtitle"
)
for still in "${stills[@]}"; do
  read -r name dem w h units words <<< "$still"
  sets=(--set overlay.enabled=true --set overlay.frame=true --set "overlay.frame_units=\"$units\""
        --set render.width="$w" --set render.height="$h" --set render.antialias=false --set subdivision.depth=0
        --set samples.vertical_unit=\"m\")
  [ "$words" = title ] && sets+=(--set 'overlay.title="A map"')
  [ "$words" = subtitle ] && sets+=(--set 'overlay.subtitle="framed as GMT frames one"')
  "$relief" render -q "$dem" "${sets[@]}" -o "$name.png" 2> "$name.err" || { fail "render $name"; cat "$name.err"; }
  grep -q "left out" "$name.err" && { fail "$name: an item left out"; cat "$name.err"; }
done

PYTHONPATH="$src/tests/cli" python3 - "${stills[@]}" <<'PY' || fail "the framed maps"
import json, sys
from png_pixels import png_rgb

def meets(a, b):
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]

problems, annotations = [], 0
for still in sys.argv[1:]:
    name = still.split()[0]
    j = json.load(open(name + '.json'))
    w, h, ch, rows = png_rgb(name + '.png')
    o = j['overlay']
    f = o.get('frame')
    if f is None:
        problems.append(f'{name}: no frame in the sidecar')
        continue
    m = f['map_px']
    if not (0 <= m[0] < m[2] <= w and 0 <= m[1] < m[3] <= h):
        problems.append(f'{name}: the map {m} leaves the {w} x {h} still')
        continue
    pixel = lambda x, y: rows[int(y)][int(x) * ch:int(x) * ch + 3]
    background = pixel(1, h // 2)
    cx, cy = (m[0] + m[2]) / 2, (m[1] + m[3]) / 2
    for x, y, where in ((cx, m[1], 'top'), (cx, m[3], 'bottom'), (m[0], cy, 'left'), (m[2], cy, 'right')):
        near = [pixel(min(max(x + dx, 0), w - 1), min(max(y + dy, 0), h - 1)) for dx in (-1, 0, 1) for dy in (-1, 0, 1)]
        if min(max(p) for p in near) > 80:
            problems.append(f'{name}: no neat line at the map\'s {where} edge ({x:.1f}, {y:.1f})')
    for x, y, where in ((cx, m[1] + 5, 'top'), (cx, m[3] - 5, 'bottom'), (m[0] + 5, cy, 'left'), (m[2] - 5, cy, 'right')):
        if max(abs(a - b) for a, b in zip(pixel(x, y), background)) < 12:
            problems.append(f'{name}: background, not terrain, inside the map\'s {where} edge')
    furniture = {k: b for k, b in o['boxes_px'].items() if k != 'frame'}
    sides = set()
    placed = []
    for a in f['annotations']:
        annotations += 1
        b, side, t = a['box_px'], a['side'], a['tick_px']
        sides.add(side)
        centre = (b[0] + b[2]) / 2 if side in ('bottom', 'top') else (b[1] + b[3]) / 2
        if abs(centre - t) > 1:
            problems.append(f'{name}: {a["text"]!r} is centred {centre - t:+.1f} px off its tick')
        outside = {'bottom': b[1] >= m[3], 'top': b[3] <= m[1], 'left': b[2] <= m[0], 'right': b[0] >= m[2]}[side]
        if not outside:
            problems.append(f'{name}: {a["text"]!r} {b} is not outside the map {m} on its {side}')
        if not (0 <= b[0] and b[2] <= w and 0 <= b[1] and b[3] <= h):
            problems.append(f'{name}: {a["text"]!r} {b} leaves the still')
        for other in placed:
            if meets(b, other['box_px']):
                problems.append(f'{name}: {a["text"]!r} meets {other["text"]!r}')
        for item, fb in furniture.items():
            if meets(b, fb):
                problems.append(f'{name}: {a["text"]!r} {b} meets the {item} {fb}')
        placed.append(a)
    if sides != {'bottom', 'top', 'left', 'right'}:
        problems.append(f'{name}: annotations on {sorted(sides)} only')
    for item, b in furniture.items():
        if not (0 <= b[0] < b[2] <= w and 0 <= b[1] < b[3] <= h):
            problems.append(f'{name}: the {item} {b} leaves the still')
for p in problems:
    print('FAIL:', p)
print(f'{len(sys.argv) - 1} framed maps, {annotations} annotations, {len(problems)} problems')
sys.exit(1 if problems else 0)
PY
exit $status
