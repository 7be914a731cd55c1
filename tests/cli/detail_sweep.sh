#!/usr/bin/env bash
# The depth chosen for the camera that looks, swept: a camera by azimuth at elevation 5 (low), 35
# and 89 (high), and at a place (on the ground's scale and 2 km up), perspective, orthographic and
# panoramic. In every one the refined net holds at most 4 nodes a pixel of the still (or the net's
# own nodes, never refined, when it alone holds more): no depth beyond what the pixels show, a
# camera among the terrain's heights no longer choosing a depth for a pixel nanometres wide (it
# once took depth 8: 85 M nodes, 34 s and 2.7 GB for an 800 x 600 still). relief info plans
# without subdividing, so the sweep takes seconds.
# Usage: detail_sweep.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
enter_fresh_work
cp "$src/tests/data/rasters/maungawhau-20m.tif" dem.tif
printf '[samples]\npath = "dem.tif"\nvertical_unit = "m"\n[render]\nwidth = 400\nheight = 300\n' > s.toml
views=(
  "camera.elevation_deg=5" "camera.elevation_deg=35" "camera.elevation_deg=89"
  "camera.elevation_deg=35 camera.projection=\"orthographic\""
  "camera.position=[174.7620,-36.8790,120] camera.look_at=[174.7640,-36.8765,150]"
  "camera.position=[174.7620,-36.8790,2000]"
  "camera.position=[174.7620,-36.8790,120] camera.projection=\"panoramic\""
)
for view in "${views[@]}"; do
  sets=()
  for kv in $view; do sets+=(--set "$kv"); done
  "$relief" info --json s.toml "${sets[@]}" > info.json 2> info.txt || { fail "relief info at $view"; cat info.txt; continue; }
  python3 - "$view" <<'PY' || fail "the depth chosen at $view"
import json, sys
j = json.load(open('info.json'))
net, sub, still = j['net'], j['subdivision'], j['still']
nodes = sub['refined_rows'] * sub['refined_cols']
pixels = still['width'] * still['height']
own = net['rows'] * net['cols']
if not (nodes <= max(4 * pixels, own) and (nodes == own or nodes <= 4 * pixels)):
    sys.exit(f'{sys.argv[1]}: depth {sub["depth"]}: {nodes} nodes for {pixels} pixels ({sub["depth_reason"]})')
# The footprint the depth was chosen for: never nanometres (an eye among the terrain's heights once
# measured it at the bounding box's nearest point, the eye itself).
import re
footprint = float(re.search(r'the ([0-9.e+-]+) m one pixel', sub['depth_reason']).group(1))
if footprint < 1e-3:
    sys.exit(f'{sys.argv[1]}: a pixel taken as {footprint} m on the ground ({sub["depth_reason"]})')
print(f'{sys.argv[1]}: depth {sub["depth"]}, {nodes} nodes ({nodes / pixels:.2f} a pixel), a pixel {footprint:.3g} m')
PY
done
# A flyover's net from a pixel's footprint where its eye comes down to (a twentieth of the diagonal
# above the ground): Maungawhau's 2 m LiDAR at the data's own spacing, where a still of the whole
# terrain 160 px wide averages it to 8 m (flyovers once flew over the still's net, hills as blobs).
cp "$src/scenes/data/rasters/volcano2hires.tif" lidar.tif
printf '[samples]\npath = "lidar.tif"\nvertical_unit = "m"\n[render]\nwidth = 160\nheight = 100\n' > still.toml
{ cat still.toml; printf '[animation]\nframes = 4\npath = "flyover"\nwaypoints = [[174.7615, -36.8800], [174.7650, -36.8760]]\n'; } > fly.toml
# Waypoints with heights above the sea: the eye's least height over the ground along the path (here
# 2,000 m up: a pixel 20 m, the net coarser than the data; 150 m, about 40 m over the crater's rim:
# the data's own).
{ cat still.toml; printf '[animation]\nframes = 4\npath = "flyover"\nwaypoints = [[174.7615, -36.8800, 2000], [174.7650, -36.8760, 2000]]\n'; } > high.toml
{ cat still.toml; printf '[animation]\nframes = 4\npath = "flyover"\nwaypoints = [[174.7615, -36.8800, 250], [174.7650, -36.8760, 250]]\n'; } > low.toml
for scene in still fly high low; do "$relief" info --json "$scene.toml" > "$scene.json" 2> "$scene.txt" || { fail "relief info $scene"; cat "$scene.txt"; }; done
python3 - <<'PY' || fail "the flyover's net"
import json
still, fly, high, low = (json.load(open(f'{n}.json'))['net'] for n in ('still', 'fly', 'high', 'low'))
assert still['spacing_m'] > 3 * fly['spacing_m'], (still['spacing_m'], fly['spacing_m'])
assert fly['spacing_reason'] == "the data's own spacing", fly['spacing_reason']
assert high['spacing_m'] > 2 * low['spacing_m'], (high['spacing_m'], low['spacing_m'])
assert low['spacing_reason'] == "the data's own spacing", low['spacing_reason']
print(f"the still's net {still['spacing_m']:.3g} m, the flyover's {fly['spacing_m']:.3g} m (the data's); "
      f"waypoints 2000 m up {high['spacing_m']:.3g} m, 250 m up {low['spacing_m']:.3g} m")
PY
exit $status
