#!/usr/bin/env bash
# relief preview in headless Chromium: the page's camera and POV-Ray's agree. For three views
# (oblique, low, straight down) the page is set to the view, its terrain screenshotted against a
# transparent sky at the still's size, "Use this view" pressed; then the still each view wrote into
# the scene file is rendered (background transparent) and the terrain's silhouette in the two
# compared: intersection over union at least 0.98 for every view. Also: the scene file keeps its
# comments with a backup beside it, the token guards every address, nothing listens beyond
# 127.0.0.1, a scene that does not compile is served as its diagnostics, Ctrl-C stops it.
# Usage: preview.sh RELIEF SOURCE_DIR WORK_DIR NODE_MODULES
set -u
relief=$(realpath "$1") src=$(realpath "$2") work=$(realpath -m "$3") node_modules=$(realpath "$4")
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
command -v chromium >/dev/null || { echo "SKIP: chromium is not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work/out" && cd "$work" || exit 1
status=0
fail() { echo "FAIL: $*"; status=1; }

cp "$src/tests/golden/small/samples.csv" "$work/"
cat > "$work/scene.toml" <<'TOML'
# The preview test's scene: Maunga Whau from 300 samples, a block model, seen from the orbit.
[samples]
path = "samples.csv"

[frame]
kind = "utm"

[net]
rows = 12
cols = 9
gridding = "linear"

[vertical]
exaggeration = 2

[subdivision]
depth = 3

[camera]
azimuth_deg = 200     # the author's note on the camera
elevation_deg = 35
fov_deg = 40

[render]
width = 640
height = 400
background = "transparent"

[overlay]
enabled = false       # the terrain's silhouette alone is compared
TOML
cp "$work/scene.toml" "$work/scene.original.toml"

# Started as a user would, its address read from its first line.
start() {  # start SCENE [args]: sets pid and url
  "$relief" preview "$@" --no-open > "$work/preview.url" 2> "$work/preview.log" &
  pid=$!
  for _ in $(seq 1 300); do
    url=$(head -n1 "$work/preview.url" 2>/dev/null)
    [ -n "$url" ] && break
    sleep 0.1
  done
}
start "$work/scene.toml"
echo "preview at $url"
[[ "$url" =~ ^http://127\.0\.0\.1:[0-9]+/[0-9a-f]{32}/$ ]] || fail "the address is not loopback with a 128-bit token: $url"
port=$(echo "$url" | sed -E 's#http://127.0.0.1:([0-9]+)/.*#\1#')
token=$(echo "$url" | sed -E 's#.*/([0-9a-f]{32})/$#\1#')
# Listening on 127.0.0.1 alone.
listen=$(ss -Hltn "sport = :$port" | awk '{print $4}')
echo "listening on: $listen"
[ "$listen" = "127.0.0.1:$port" ] || fail "listens on '$listen', not 127.0.0.1:$port alone"
# Without the token, or with another Host (a rebinding site's name), nothing is served.
code() { curl -s -o /dev/null -w '%{http_code}' "$@"; }
[ "$(code "http://127.0.0.1:$port/")" = 404 ] || fail "the root is served without the token"
[ "$(code "http://127.0.0.1:$port/00000000000000000000000000000000/page.json")" = 404 ] || fail "a wrong token is served"
[ "$(code -H "Host: evil.example:$port" "${url}page.json")" = 404 ] || fail "another Host is served"
[ "$(code "${url}page.json")" = 200 ] || fail "page.json with the token is not served"

NODE_PATH="$node_modules" timeout 300 node "$src/tests/web/preview_views.cjs" "$url" "$work/scene.toml" "$work" \
  > "$work/browser.log" 2>&1 || fail "the browser's script failed"
cat "$work/browser.log"

# Its own writes rebuild nothing (the same model), and a page opened afresh starts from the view used last.
state=$(curl -s "${url}state")
[ "$state" = '{"building":false,"generation":1}' ] || fail "the view's own write rebuilt the preview: $state"
curl -s "${url}page.json" | grep -q '"fovDeg":35.0' || fail "page.json's camera is not the view used last"

# Ctrl-C stops it, with exit code 0.
kill -INT "$pid"; wait "$pid"; rc=$?
[ "$rc" = 0 ] || fail "relief preview exited $rc after SIGINT"
grep -q "wrote the view into" "$work/preview.log" || fail "the terminal did not say the view was written"

# The scene file: the view's keys, the orbit's commented out, the author's comment kept, a backup.
grep -q '^position = \[' "$work/scene.toml" || fail "no camera.position written"
grep -q '^look_at = \[' "$work/scene.toml" || fail "no camera.look_at written"
grep -q '^# azimuth_deg = 200     # the author.s note on the camera' "$work/scene.toml" || fail "the orbit's key not kept as a comment"
grep -q '^fov_deg = 35$' "$work/scene.toml" || fail "fov_deg not replaced in place"
cmp -s "$work/scene.toml.bak" "$work/view-down.toml" || fail "the backup is not the file before the last write (Save path)"

# Each view's still, its silhouette against the preview's.
for v in oblique low down; do
  "$relief" render "$work/view-$v.toml" -q -o "$work/out/still-$v.png" || { fail "render of view $v"; continue; }
  /usr/bin/python3 - "$work/preview-$v.png" "$work/out/still-$v.png" "$v" <<'PY' || fail "view $v: silhouettes differ"
import sys
import numpy as np
from osgeo import gdal
def terrain(path):
    ds = gdal.Open(path)
    a = ds.GetRasterBand(ds.RasterCount).ReadAsArray().astype(float)
    return a / (65535.0 if a.max() > 255 else 255.0) >= 0.5
p, s = terrain(sys.argv[1]), terrain(sys.argv[2])
if p.shape != s.shape:
    print(f"{sys.argv[3]}: preview {p.shape}, still {s.shape}"); sys.exit(1)
iou = (p & s).sum() / max((p | s).sum(), 1)
print(f"{sys.argv[3]}: terrain {p.mean():.1%} of the preview, {s.mean():.1%} of the still; IoU {iou:.4f}")
sys.exit(0 if iou >= 0.98 and 0.02 < s.mean() < 0.98 else 1)
PY
done

# Save path wrote the keyframes as a flyover relief reads.
grep -q '^path = "flyover"$' "$work/scene.toml" || fail "no [animation] path = \"flyover\" written"
grep -q '^waypoints = \[\[' "$work/scene.toml" || fail "no [animation] waypoints written"
grep -q '^frames = 48$' "$work/scene.toml" || fail "no [animation] frames (48 for one leg) where the scene gave none"
"$relief" compile -q "$work/scene.toml" -o "$work/out/path.pov" || fail "the scene with the saved path does not compile"

post() {  # post PATH JSON: the reply's body, then its status on a line of its own
  curl -s -w '\n%{http_code}' -H 'Content-Type: application/json' -d "$2" "${url}$1"
}
view='{"eye": [300, 400, 500], "target": [0, 100, 0], "fovDeg": 30}'

# --print: Use this view prints the keys and leaves the scene as it was.
cp "$work/scene.toml" "$work/before-print.toml"
start "$work/scene.toml" --print
reply=$(post use "$view")
kill -INT "$pid"; wait "$pid"
[ "$(echo "$reply" | tail -n1)" = 200 ] || fail "--print: use replied $reply"
cmp -s "$work/scene.toml" "$work/before-print.toml" || fail "--print changed the scene file"
grep -q '^relief preview: fov_deg = 30$' "$work/preview.log" || fail "--print: the keys are not printed"
# Bad views are refused with a reason. (Overlays on: the furniture's places are in the page's facts.)
start "$work/scene.toml" --print --set overlay.enabled=true
furniture=$(curl -s "${url}page.json" | grep -o '"item":"[a-z_]*"' | sort | tr '\n' ' ')
echo "the furniture's places: $furniture"
[ "$furniture" = '"item":"legend" "item":"north_arrow" "item":"scale_bar" ' ] || fail "the furniture's places: $furniture"
for bad in '{"eye": [1, 2], "target": [0, 0, 0], "fovDeg": 30}' '{"eye": [1, 2, 3], "target": [0, 0, 0], "fovDeg": 300}' 'not json'; do
  reply=$(post use "$bad")
  case "$(echo "$reply" | tail -n1)" in 400|422) ;; *) fail "a bad view ($bad) replied $reply" ;; esac
done
# Render: the still of a view, through relief render, served when done.
reply=$(post render "$view")
[ "$(echo "$reply" | tail -n1)" = 202 ] || fail "render replied $reply"
for _ in $(seq 1 120); do curl -s "${url}still" | grep -q '"running":false' && break; sleep 0.5; done
curl -s "${url}still"; echo
curl -s -o "$work/served-still.png" "${url}still.png"
cmp -s "$work/served-still.png" "$work/out/scene-preview.png" || fail "the served still is not the one written"
# The file changed while it runs: rebuilt, a new generation.
g1=$(curl -s "${url}state")
sed -i 's/^exaggeration = 2$/exaggeration = 3/' "$work/scene.toml"
for _ in $(seq 1 100); do g2=$(curl -s "${url}state"); [ "$g2" != "$g1" ] && echo "$g2" | grep -q '"building":false' && break; sleep 0.2; done
echo "state before the edit: $g1; after: $g2"
[ "$g2" != "$g1" ] || fail "the edited scene was not rebuilt"
kill -INT "$pid"; wait "$pid"

# A DEM alone: Use this view writes relief init's scene for it, here, with the view's camera.
mkdir -p "$work/dem" && cp "$src/scenes/data/rasters/volcano2.tif" "$work/dem/dem.tif"
(cd "$work/dem" && start dem.tif && post use "$view" > reply.txt; kill -INT "$pid"; wait "$pid")
[ "$(tail -n1 "$work/dem/reply.txt")" = 200 ] || fail "a DEM's view: $(cat "$work/dem/reply.txt")"
grep -q '^position = \[' "$work/dem/dem.toml" || fail "a DEM's view did not write dem.toml with its camera"
(cd "$work/dem" && "$relief" compile -q dem.toml -o dem.pov) || fail "the DEM's new scene does not compile"

# A view that would leave a scene relief cannot load (an orbit film's camera placed by position) is
# refused with the reader's reason, the file unchanged.
cp "$work/scene.original.toml" "$work/orbit.toml"
printf '\n[animation]\nframes = 24\npath = "orbit"\nazimuth_from_deg = 0\nazimuth_to_deg = 90\n' >> "$work/orbit.toml"
cp "$work/orbit.toml" "$work/orbit.before.toml"
start "$work/orbit.toml"
reply=$(post use "$view")
kill -INT "$pid"; wait "$pid"
echo "an orbit film's view: $reply"
[ "$(echo "$reply" | tail -n1)" = 422 ] || fail "a view making the scene unreadable replied $reply"
echo "$reply" | grep -q 'not written' || fail "the refusal does not say the view is not written"
cmp -s "$work/orbit.toml" "$work/orbit.before.toml" || fail "a refused view changed the scene file"

# A scene that does not compile: served, its diagnostics in the page's data (as text).
printf '[samples]\npath = "missing.csv"\n' > "$work/broken.toml"
start "$work/broken.toml"
page=$(curl -s "${url}page.json")
kill -INT "$pid"; wait "$pid"
echo "$page" | grep -q '"preview":null' || fail "a broken scene's page has a preview"
echo "$page" | grep -q 'missing.csv' || fail "a broken scene's diagnostics do not name the file: $page"
exit $status
