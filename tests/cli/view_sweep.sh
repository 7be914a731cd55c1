#!/usr/bin/env bash
# The view space swept, not one point of it: small stills of Maungawhau with two labelled points and a graticule
# (each its own layer and marker colour) at camera elevation 5, 15, 45, 75, 89 and 90 degrees x
# azimuth 0, 45, ..., 315, perspective and orthographic (96 stills). In every one:
# - each marker is where relief says it is: the marker's colour in the still's pixels beside the
#   label's anchor (the projection relief places labels with agrees with POV-Ray's camera; straight
#   down they once disagreed by the azimuth less 180 degrees);
# - each label stands by its own marker: its box within 12 px of the anchor, or its leader ending
#   on the box; each graticule label on its line (the line's point within 4 px of its box);
# - every furniture item (title, north arrow with its "N", scale bar, credits, legend) and every
#   string drawn is wholly inside the still, and no two items overlap; an item with no free place
#   is left out and the sidecar says what was in its way; the north arrow is in every still;
# - straight down (90) the still is a map: north up (the north arrow within 2 degrees of up: the
#   frame's grid convergence).
# Usage: view_sweep.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
cp "$src/tests/data/rasters/maungawhau-20m.tif" dem.tif
python3 - "$src/tests/data/vectors/maungawhau-features.geojson" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
points = [f for f in j['features'] if f['geometry']['type'] == 'Point' and f['properties']['name'] != 'Rangitoto']
for f, name in zip(points, ('summit', 'crater')):
    json.dump({'type': 'FeatureCollection', 'features': [f]}, open(f'{name}.geojson', 'w'))
PY
cat > s.toml <<'TOML'
[samples]
path = "dem.tif"
vertical_unit = "m"
[subdivision]
depth = 0
[render]
width = 240
height = 160
antialias = false
[overlay]
enabled = true
title = "Mt Eden"
graticule = { step_deg = 0.005 }
[[layer]]
path = "summit.geojson"
label = "name"
color = "#ff00ff"
[[layer]]
path = "crater.geojson"
label = "name"
color = "#00ffff"
TOML
views=()
for el in 5 15 45 75 89 90; do
  for az in 0 45 90 135 180 225 270 315; do
    for proj in perspective orthographic; do views+=("$el $az $proj"); done
  done
done
printf '%s\n' "${views[@]}" | xargs -P 2 -L 1 sh -c '
  "$0" render -q s.toml --set camera.elevation_deg=$1 --set camera.azimuth_deg=$2 --set camera.projection=\"$3\" \
    -o "v/$1-$2-$3.png" 2> "v-$1-$2-$3.txt" || { echo "FAIL: render at elevation $1, azimuth $2, $3:"; cat "v-$1-$2-$3.txt"; }
' "$relief" | grep . && status=1

PYTHONPATH="$src/tests/cli" python3 - "${views[@]}" <<'PY' || fail "the view sweep"
import json, math, sys
from png_pixels import png_rgb

def box_distance(p, b):
    dx = max(b[0] - p[0], 0, p[0] - b[2])
    dy = max(b[1] - p[1], 0, p[1] - b[3])
    return math.hypot(dx, dy)

colours = {1: lambda r, g, b: r > g + 60 and b > g + 60, 2: lambda r, g, b: g > r + 60 and b > r + 60}
problems, labelled, graticule_labels = [], 0, 0
for view in sys.argv[1:]:
    el, az, proj = view.split()
    name = f'v/{el}-{az}-{proj}'
    j = json.load(open(name + '.json'))
    w, h, ch, rows = png_rgb(name + '.png')
    o = j['overlay']
    where = f'elevation {el}, azimuth {az}, {proj}'
    for label in o.get('labels', []):
        if 'box_px' not in label:
            continue
        if label['layer'] == 0:  # a graticule line's: on its line (its point within the box, 4 px at most)
            d = box_distance(label['anchor_px'], label['box_px'])
            if label['leader'] or d > 4:
                problems.append(f'{where}: the graticule label {label["text"]!r} is {d:.1f} px from its line')
            graticule_labels += 1
            continue
        labelled += 1
        ax, ay = label['anchor_px']
        # The marker's colour within a few pixels below its top (a pin's head).
        near = [(x, y) for y in range(int(ay) - 3, int(ay) + 9) for x in range(int(ax) - 4, int(ax) + 5)
                if 0 <= x < w and 0 <= y < h]
        if not any(colours[label['layer']](*rows[y][x * ch:x * ch + 3]) for x, y in near):
            problems.append(f'{where}: no marker of layer {label["layer"]} at the anchor {label["anchor_px"]}')
        d = box_distance(label['leader_end_px'], label['box_px']) if label['leader'] else \
            box_distance(label['anchor_px'], label['box_px'])
        if d > (2 if label['leader'] else 12):
            problems.append(f'{where}: the label {label["text"]!r} is {d:.1f} px from its marker')
    boxes = o['boxes_px']
    for item in ('title', 'north_arrow', 'credits', 'scale_bar', 'legend'):
        if (item in boxes) == (item in o.get('left_out', {})):
            problems.append(f'{where}: the {item} is neither drawn nor said to be left out')
    if 'north_arrow' not in boxes:
        problems.append(f'{where}: no north arrow')
    for item, b in boxes.items():
        if not (0 <= b[0] < b[2] <= w and 0 <= b[1] < b[3] <= h):
            problems.append(f'{where}: the {item} {b} leaves the {w} x {h} still')
    distinct = sorted({tuple(b): item for item, b in boxes.items()}.items())
    for i, (a, ia) in enumerate(distinct):
        for b, ib in distinct[:i]:
            if a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]:
                problems.append(f'{where}: the {ia} {list(a)} overlaps the {ib} {list(b)}')
    for t in o['texts']:
        b = t['box_px']
        if not (-0.5 <= b[0] and b[2] <= w + 0.5 and -0.5 <= b[1] and b[3] <= h + 0.5):
            problems.append(f'{where}: {t["text"]!r} at {b} leaves the still')
    if el == '90':
        if abs(o['north_deg_clockwise_from_up']) > 2:
            problems.append(f'{where}: north is {o["north_deg_clockwise_from_up"]:.1f} degrees from up on a map')
for p in problems:
    print('FAIL:', p)
print(f'{len(sys.argv) - 1} views, {labelled} labels and {graticule_labels} graticule labels placed, {len(problems)} problems')
assert labelled >= 2 * 48, 'too few labels placed for the sweep to mean anything'
assert graticule_labels >= 48, 'too few graticule labels placed for the sweep to mean anything'
sys.exit(1 if problems else 0)
PY
exit $status
