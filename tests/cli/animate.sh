#!/usr/bin/env bash
# relief animate: frame k of a film is byte for byte relief render of the scene with that frame's
# keys (an orbit; the sun through a morning with a key varied); the same scene gives the same MP4,
# WebM and GIF bytes, as one tile or as tiles on two processes; the MP4 is H.264 yuv420p with its
# index in front; nights are skipped or named; --resume holds what is left to the scene's [limits];
# bad input (no [animation], an unknown film type, a window all at night, an output that cannot be
# written) and a missing ffmpeg leave nothing.
# Usage: animate.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
command -v ffmpeg >/dev/null || { echo "SKIP: ffmpeg is not installed"; exit 77; }
enter_fresh_work
dem="$src/tests/data/rasters/maungawhau-20m.tif"
cat > orbit.toml <<TOML
[samples]
path = "$dem"
vertical_unit = "m"
[camera]
azimuth_deg = 200
elevation_deg = 35
[render]
width = 480
height = 320
[overlay]
title = "Maungawhau"
[animation]
frames = 4
path = "orbit"
TOML
# probe FILM EXPECTED: the stream's codec, size, pixel format, frame rate and frames, as ffprobe counts them.
probe() {
  local got
  got=$(ffprobe -v error -select_streams v:0 -count_frames \
          -show_entries stream=codec_name,pix_fmt,width,height,r_frame_rate,nb_read_frames -of csv=p=0 "$1")
  [ "$got" = "$2" ] || fail "ffprobe $1: '$got', expected '$2'"
}
# frame_is_still SCENE SIDECAR K FRAME_PNG: relief render of the scene with the keys the film's sidecar gives
# frame K gives the frame's bytes.
frame_is_still() {
  local keys
  mapfile -t keys < <(python3 - "$2" "$3" <<'PY'
import json, sys
f = json.load(open(sys.argv[1]))['frames'][int(sys.argv[2]) - 1]['set']
print('\n'.join(f"--set\n{k}={v}" for k, v in f.items()))
PY
)
  "$relief" render -q "$1" "${keys[@]}" -o "still/$(basename "$2" .json)-$3.png" 2> /dev/null ||
    { fail "frame $3 of $2 as a still"; return; }
  cmp -s "still/$(basename "$2" .json)-$3.png" "$4" || fail "frame $3 of $2 is not relief render with its keys"
}
# Nothing but the outputs asked for: no working folder left beside them.
only() { local want=$1 dir=$2; local got; got=$(cd "$dir" && ls -A | sort | tr '\n' ' '); [ "$got" = "$want" ] || fail "$dir holds '$got', expected '$want'"; }

# 1. An orbit: a quarter turn a frame; frame 2 is the still at 200 + 90 degrees.
"$relief" animate -q orbit.toml -o a/orbit.mp4 --frames a/frames 2> a.txt || { fail "the orbit"; cat a.txt; }
only "frames orbit.json orbit.mp4 " a
[ "$(ls a/frames | tr '\n' ' ')" = "frame-00001.png frame-00002.png frame-00003.png frame-00004.png " ] || fail "frames: $(ls a/frames)"
grep -q '"camera.azimuth_deg": "290"' a/orbit.json || fail "the sidecar does not give frame 2's azimuth"
for k in 1 2 3 4; do frame_is_still orbit.toml a/orbit.json $k "a/frames/frame-0000$k.png"; done
cmp -s a/frames/frame-00002.png a/frames/frame-00001.png && fail "frames 1 and 2 are the same picture"
# The film stands still but for its terrain and its north arrow: one distance and target for every
# frame (no breathing), each item of the furniture in one box (the arrow turning about one centre),
# the arrow whole at every angle.
python3 - still/orbit-{1,2,3,4}.json <<'PY' || fail "the orbit's framing or furniture moves from frame to frame"
import json, sys
frames = [json.load(open(p)) for p in sys.argv[1:]]
ok = True
def same(what, values):
    global ok
    if any(v != values[0] for v in values):
        print(f'FAIL: {what} differs between frames: {values}')
        ok = False
same('the camera distance', [round(f['camera']['distance_m'], 6) for f in frames])
same('the look-at point', [[round(x, 9) for x in f['camera']['look_at_lonlat_h']] for f in frames])
boxes = [f['overlay']['boxes_px'] for f in frames]
for item in ('title', 'credits', 'scale_bar', 'legend'):
    same(f'the {item}\'s box', [b.get(item) for b in boxes])
same('the north arrow\'s centre', [f['overlay'].get('north_arrow_centre_px') for f in frames])
if frames[0]['overlay'].get('north_arrow_centre_px') is None:
    print('FAIL: no north arrow')
    ok = False
angles = [f['overlay']['north_deg_clockwise_from_up'] for f in frames]
for f in frames:
    for t in f['overlay']['texts']:
        x0, y0, x1, y1 = t['box_px']
        if not (x0 >= -0.5 and y0 >= -0.5 and x1 <= 480.5 and y1 <= 320.5):
            print(f'FAIL: {t["text"]!r} at {t["box_px"]} leaves the frame')
            ok = False
if len({round(a) for a in angles}) < 4:
    print(f'FAIL: the arrow did not turn: {angles}')
    ok = False
sys.exit(0 if ok else 1)
PY
probe a/orbit.mp4 h264,480,320,yuv420p,30/1,4
python3 - a/orbit.mp4 <<'PY' || fail "the MP4's index (moov) is not before its data (mdat): no +faststart"
import sys
b = open(sys.argv[1], 'rb').read()
sys.exit(0 if 0 < b.find(b'moov') < b.find(b'mdat') else 1)
PY

# 2. The same film again, as 3 tiles a frame on 2 processes, under another name in another folder
#    (ffmpeg once wrote bytes that depended on the length of the output's name): the same bytes.
renamed="b/a folder with a much longer name/the same orbit, named otherwise.mp4"
"$relief" animate -q orbit.toml -o "$renamed" --tiles 3 --jobs 2 || fail "the orbit in tiles"
cmp -s a/orbit.mp4 "$renamed" || fail "the MP4 differs between runs (1 tile and 3, another name and folder)"
for ext in webm gif; do
  "$relief" animate -q orbit.toml -o "c/orbit.$ext" && "$relief" animate -q orbit.toml -o "d/orbit.$ext" ||
    fail "the .$ext film"
  cmp -s "c/orbit.$ext" "d/orbit.$ext" || fail "the .$ext film differs between runs"
done
[ "$(ffprobe -v error -show_entries stream=codec_name -of csv=p=0 c/orbit.webm)" = vp9 ] || fail "the WebM is not VP9"
[ "$(ffprobe -v error -show_entries stream=codec_name -of csv=p=0 c/orbit.gif)" = gif ] || fail "the GIF is not a GIF"

# 3. The sun through a day with the exaggeration eased from 1 to 3; the evening frame is dark.
sed -e '/^\[camera\]/,/^elevation_deg/d' -e '/^path = "orbit"/d' -e 's/^frames = 4/frames = 3/' orbit.toml > sun.toml
cat >> sun.toml <<'TOML'
sun = { from = "2026-06-21T09:00:00+12:00", to = "2026-06-21T18:00:00+12:00" }
vary = { "vertical.exaggeration" = [1, 3] }
TOML
"$relief" animate -q sun.toml -o night/sun.mp4 2> night.txt; code=$?
[ "$code" = 2 ] || fail "a frame at night: exit $code, expected 2"
grep -q "sun.toml:.*: error: animation.sun: at frame 3 (2026-06-21T18:00:00+12:00) the sun is .* below the horizon" night.txt ||
  { fail "the night frame is not named:"; cat night.txt; }
[ -e night ] && [ -n "$(ls -A night)" ] && fail "a frame at night left files: $(ls -A night)"
echo 'skip_night = true' >> sun.toml
"$relief" animate -q sun.toml -o sun/sun.mp4 --frames sun/frames || fail "the film through the day"
[ "$(ls sun/frames | tr '\n' ' ')" = "frame-00001.png frame-00002.png " ] || fail "skip_night: frames $(ls sun/frames)"
grep -q '"left_out": "night"' sun/sun.json || fail "the sidecar does not say frame 3 was left out"
python3 - sun/sun.json <<'PY' || fail "frame 2's keys are not 13:30 with exaggeration 2"
import json, sys
keys = json.load(open(sys.argv[1]))['frames'][1]['set']
assert keys['lighting.datetime'] == '"2026-06-21T13:30:00+12:00"', keys
assert keys['overlay.subtitle'] == '"2026-06-21 13:30:00 +12:00"', keys
assert float(keys['vertical.exaggeration']) == 2, keys
PY
frame_is_still sun.toml sun/sun.json 2 sun/frames/frame-00002.png
probe sun/sun.mp4 h264,480,320,yuv420p,30/1,2

# 2b. Interrupted once frame 2 is rendered, the working folder is kept (nothing else), and
# --resume renders the rest: the same MP4 bytes as a film made in one run.
sed -e 's/^frames = 4/frames = 6/' -e 's/^width = 480/width = 240/' -e 's/^height = 320/height = 160/' orbit.toml > six.toml
"$relief" animate -q six.toml -o whole/six.mp4 || fail "the six-frame orbit"
"$relief" animate -q six.toml -o cut/six.mp4 --jobs 1 2> cut.txt & pid=$!
for _ in $(seq 1 300); do [ -e cut/six.film/frame-00002.plan/tiles/tile-0000.png ] && break; sleep 0.1; done
kill -INT $pid; wait $pid; code=$?
if [ $code = 0 ]; then
  echo "NOTE: the film ended before it could be interrupted; --resume is not tested this run"
else
  [ $code = 130 ] || fail "interrupted: exit $code, expected 130"
  grep -q "relief animate --resume .*cut/six.film.* renders what is missing" cut.txt || { fail "no word of --resume:"; cat cut.txt; }
  only "six.film " cut
  "$relief" animate --resume cut/six.film 2> resume.txt || { fail "--resume"; cat resume.txt; }
  grep -q "of 6 frames were rendered before" resume.txt || { fail "--resume rendered every frame again:"; cat resume.txt; }
  only "six.json six.mp4 " cut
  cmp -s whole/six.mp4 cut/six.mp4 || fail "the resumed film is not the one-run film's bytes"
fi
mkdir -p notafilm
"$relief" animate --resume notafilm 2> notafilm.txt; code=$?
[ $code = 2 ] || fail "--resume of a folder that is no film's: exit $code"
grep -qF "notafilm/film.json: error: not a film's working folder (no film.json)" notafilm.txt || { fail "--resume notafilm:"; cat notafilm.txt; }

# 2c. --resume holds the frames still to render to the scene's [limits]. A film whose first frame's
# POV-Ray failed (a povray on PATH that always fails) keeps its folder; resumed, it is refused by
# limits.max_film_s at the scene's own line, exit 2, and the folder is kept, the frame rendered,
# to be resumed again. A record whose limits are out of the scene's ranges is damaged.
mkdir -p failing
printf '#!/bin/sh\n[ "$1" = --version ] && exec %s "$@"\necho "povray: this one always fails" >&2\nexit 1\n' \
  "$(command -v povray)" > failing/povray && chmod +x failing/povray
{ cat six.toml; printf '[limits]\nmax_film_s = 0.01\n'; } > limited.toml
line=$(grep -n '^max_film_s' limited.toml | cut -d: -f1)
PATH="$work/failing:$PATH" "$relief" animate -q limited.toml -o lim/six.mp4 --no-sandbox 2> lim1.txt; code=$?
[ $code = 3 ] || { fail "a film whose POV-Ray fails: exit $code, expected 3"; cat lim1.txt; }
only "six.film " lim
"$relief" animate -q --resume lim/six.film 2> lim2.txt; code=$?
[ $code = 2 ] || { fail "--resume over limits.max_film_s: exit $code, expected 2"; cat lim2.txt; }
grep -qE "^limited.toml:$line:[0-9]+: error: the film would take about [0-9.]+ s to render .*> limits.max_film_s = 0.01: share the rest out" lim2.txt ||
  { fail "--resume over limits.max_film_s: not refused at the scene's key:"; cat lim2.txt; }
only "six.film " lim
[ -e lim/six.film/frame-00001.plan/tiles/tile-0000.png ] || fail "refused on --resume, the frame it rendered was not kept"
# The same limit given by --set: kept with the film, told at the scene file.
PATH="$work/failing:$PATH" "$relief" animate -q six.toml --set limits.max_film_s=0.01 -o limset/six.mp4 --no-sandbox 2> /dev/null
"$relief" animate -q --resume limset/six.film 2> limset.txt; code=$?
[ $code = 2 ] && grep -q "^six.toml: error: the film would take about .*> limits.max_film_s = 0.01" limset.txt ||
  { fail "--resume over a limits.max_film_s given by --set: exit $code"; cat limset.txt; }
sed -i 's/"max_film_s": 0.01/"max_film_s": -1/' lim/six.film/film.json
"$relief" animate -q --resume lim/six.film 2> lim3.txt; code=$?
[ $code = 2 ] && grep -q "film.json: error: the film's record is damaged" lim3.txt ||
  { fail "a record with max_film_s = -1: exit $code"; cat lim3.txt; }

# 2d. A frame counter in the subtitle: frame 2 is relief render with its keys.
sed -e 's/^frames = 4/frames = 2/' -e 's/^path = "orbit"/path = "orbit"\ncounter = true/' orbit.toml > counter.toml
"$relief" animate -q counter.toml -o counter/c.mp4 --frames counter/frames || fail "the film with a counter"
grep -q '"overlay.subtitle": "\\"frame 2 of 2\\""' counter/c.json || fail "the counter is not frame 2's subtitle"
frame_is_still counter.toml counter/c.json 2 counter/frames/frame-00002.png

# 4. Bad input: exit 2, one line naming the file or key, nothing written.
bad() {  # bad NAME EXPECTED_LINE relief-arguments...
  local name=$1 want=$2; shift 2
  "$relief" animate -q "$@" 2> "$name.txt"; local code=$?
  [ "$code" = 2 ] || fail "$name: exit $code, expected 2"
  grep -qF -- "$want" "$name.txt" || { fail "$name: expected '$want', got:"; cat "$name.txt"; }
  [ -e "bad-$name" ] && [ -n "$(ls -A "bad-$name")" ] && fail "$name: left $(ls -A "bad-$name")"
}
sed '/^\[animation\]/,$d' orbit.toml > still.toml
bad no-section "still.toml: error: the scene has no [animation] section" still.toml -o bad-no-section/x.mp4
bad extension "bad-extension/x.avi: error: a film is written as .mp4 (H.264), .webm (VP9) or .gif" orbit.toml -o bad-extension/x.avi
bad frames "error: animation.frames = 0 is outside [1, 10000] frames" orbit.toml --set animation.frames=0 -o bad-frames/x.mp4
bad over-time "error: the film would take about" orbit.toml --set limits.max_film_s=0.001 -o bad-over-time/x.mp4
[ -e bad-over-time ] && [ -n "$(ls -A bad-over-time)" ] && fail "a film over limits.max_film_s left $(ls -A bad-over-time)"
sed -e 's/^frames = 4/frames = 2/' -e '/^path = "orbit"/d' orbit.toml > night.toml
echo 'sun = { from = "2026-06-21T20:00:00+12:00", to = "2026-06-21T23:00:00+12:00" }' >> night.toml
echo 'skip_night = true' >> night.toml
bad all-night "night.toml:14:7: error: animation.sun: the sun is below the horizon over the terrain's centre at every frame: choose a window in daylight" night.toml -o bad-all-night/x.mp4
touch file
bad unwritable "file: error: cannot be made as the folder of x.mp4" orbit.toml -o file/x.mp4

# 5. No ffmpeg: exit 3 naming the package, nothing written.
mkdir -p nopath && PATH="$work/nopath" "$relief" animate -q orbit.toml -o noffmpeg/x.mp4 2> noffmpeg.txt; code=$?
[ "$code" = 3 ] || fail "without ffmpeg: exit $code, expected 3"
grep -q "apt-get install ffmpeg" noffmpeg.txt || { fail "without ffmpeg:"; cat noffmpeg.txt; }
[ -e noffmpeg ] && fail "without ffmpeg, files were written"
# 6. A flyover: through waypoints at 60 m above the ground, and along a GPX track's line, which
# lands where it belongs when the same line is read from a GeoPackage in NZTM (EPSG:2193).
sed -e '/^\[animation\]/,$d' -e 's/^width = 480/width = 240/' -e 's/^height = 320/height = 160/' orbit.toml > fly.toml
cat >> fly.toml <<TOML
[animation]
frames = 3
path = "flyover"
height_above_terrain_m = 60
TOML
cp fly.toml track.toml
echo 'waypoints = [[174.7622, -36.8733], [174.7644, -36.8767], [174.7667, -36.8785]]' >> fly.toml
"$relief" animate -q fly.toml -o f/fly.mp4 --frames f/frames 2> f.txt || { fail "the flyover"; cat f.txt; }
frame_is_still fly.toml f/fly.json 2 f/frames/frame-00002.png
probe f/fly.mp4 h264,240,160,yuv420p,30/1,3
python3 - f/fly.json <<'PY' || fail "the flyover's eye: not along the waypoints at the ends, or not looking ahead"
import json, sys
frames = json.load(open(sys.argv[1]))['frames']
pos = [json.loads(f['set']['camera.position']) for f in frames]
look = [json.loads(f['set']['camera.look_at']) for f in frames]
assert abs(pos[0][0] - 174.7622) < 1e-9 and abs(pos[0][1] + 36.8733) < 1e-9, pos[0]
assert abs(pos[2][0] - 174.7667) < 1e-9 and abs(pos[2][1] + 36.8785) < 1e-9, pos[2]
for p, l in zip(pos, look):   # ahead: south-east of the eye, and below it
    assert l[0] > p[0] and l[1] < p[1] and l[2] < p[2], (p, l)
PY
echo 'track = "walk.gpx"' >> track.toml
cp "$src/tests/data/vectors/maungawhau-walk.gpx" walk.gpx
ogr2ogr -f GPKG -t_srs EPSG:2193 walk.gpkg walk.gpx tracks 2> /dev/null || fail "ogr2ogr"
sed 's/walk.gpx/walk.gpkg/' track.toml > track-nztm.toml
"$relief" animate -q track.toml -o t/walk.mp4 --frames t/frames 2> t.txt || { fail "the flyover along a GPX track"; cat t.txt; }
frame_is_still track.toml t/walk.json 3 t/frames/frame-00003.png
probe t/walk.mp4 h264,240,160,yuv420p,30/1,3
"$relief" animate -q track-nztm.toml -o t/walk-nztm.mp4 2> t.txt || { fail "the track from a GeoPackage"; cat t.txt; }
python3 - t/walk.json t/walk-nztm.json <<'PY' || fail "the track in NZTM does not land where the GPX does"
import json, sys
a, b = ([json.loads(f['set']['camera.position']) for f in json.load(open(p))['frames']] for p in sys.argv[1:])
assert abs(a[0][0] - 174.7622) < 1e-9 and abs(a[0][1] + 36.8733) < 1e-9, a[0]
for p, q in zip(a, b):
    assert abs(p[0] - q[0]) < 1e-7 and abs(p[1] - q[1]) < 1e-7 and abs(p[2] - q[2]) < 0.01, (p, q)
PY
cat > points.geojson <<'JSON'
{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "summit"},
 "geometry": {"type": "Point", "coordinates": [174.7644, -36.8767]}}]}
JSON
sed 's/walk.gpx/points.geojson/' track.toml > noline.toml
bad track-no-line "points.geojson holds no line (a LineString or MultiLineString with two vertices or more) in any layer" noline.toml -o bad-track-no-line/x.mp4
bad track-layer 'has no layer "track"; its layers: "waypoints", "routes", "tracks", "route_points", "track_points"' track.toml --set 'animation.track_layer="track"' -o bad-track-layer/x.mp4
bad waypoint-off "animation.waypoints: waypoint 2 (lon 174.8, lat -36.8767) is off the terrain (lon 174.7613 .. 174.7682, lat -36.8799 .. -36.8720)" fly.toml --set 'animation.waypoints=[[174.7622, -36.8733], [174.8, -36.8767]]' -o bad-waypoint-off/x.mp4
grep -v height_above_terrain_m fly.toml > above-sea.toml
bad under-ground "animation.waypoints: at frame 2 the eye (lon 174.76" above-sea.toml --set 'animation.waypoints=[[174.7622, -36.8733, 300], [174.7644, -36.8767, 100], [174.7667, -36.8785, 300]]' -o bad-under-ground/x.mp4

exit $status
