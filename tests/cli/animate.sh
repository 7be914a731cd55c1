#!/usr/bin/env bash
# relief animate: frame k of a film is byte for byte relief render of the scene with that frame's
# keys (an orbit; the sun through a morning with a key varied); the same scene gives the same MP4,
# WebM and GIF bytes, as one tile or as tiles on two processes; the MP4 is H.264 yuv420p with its
# index in front; nights are skipped or named; bad input (no [animation], an unknown film type, a
# window all at night, an output that cannot be written) and a missing ffmpeg leave nothing.
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
# Nothing but the outputs asked for: no working folder left beside them.
only() { local want=$1 dir=$2; local got; got=$(cd "$dir" && ls -A | sort | tr '\n' ' '); [ "$got" = "$want" ] || fail "$dir holds '$got', expected '$want'"; }

# 1. An orbit: a quarter turn a frame; frame 2 is the still at 200 + 90 degrees.
"$relief" animate -q orbit.toml -o a/orbit.mp4 --frames a/frames 2> a.txt || { fail "the orbit"; cat a.txt; }
only "frames orbit.json orbit.mp4 " a
[ "$(ls a/frames | tr '\n' ' ')" = "frame-00001.png frame-00002.png frame-00003.png frame-00004.png " ] || fail "frames: $(ls a/frames)"
"$relief" render -q orbit.toml --set camera.azimuth_deg=290 -o still/az290.png || fail "the still at 290 degrees"
cmp -s still/az290.png a/frames/frame-00002.png || fail "frame 2 is not relief render at camera.azimuth_deg=290"
cmp -s still/az290.png a/frames/frame-00001.png && fail "frames 1 and 2 are the same picture"
grep -q '"camera.azimuth_deg": "290"' a/orbit.json || fail "the sidecar does not give frame 2's azimuth"
probe=$(ffprobe -v error -select_streams v:0 -count_frames \
          -show_entries stream=codec_name,pix_fmt,width,height,nb_read_frames -of csv=p=0 a/orbit.mp4)
[ "$probe" = "h264,480,320,yuv420p,4" ] || fail "ffprobe: '$probe', expected h264,480,320,yuv420p,4"
python3 - a/orbit.mp4 <<'PY' || fail "the MP4's index (moov) is not before its data (mdat): no +faststart"
import sys
b = open(sys.argv[1], 'rb').read()
sys.exit(0 if 0 < b.find(b'moov') < b.find(b'mdat') else 1)
PY

# 2. The same film again, as 3 tiles a frame on 2 processes: the same bytes.
"$relief" animate -q orbit.toml -o b/orbit.mp4 --tiles 3 --jobs 2 || fail "the orbit in tiles"
cmp -s a/orbit.mp4 b/orbit.mp4 || fail "the MP4 differs between runs (1 tile and 3)"
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
"$relief" render -q sun.toml --set 'lighting.datetime="2026-06-21T13:30:00+12:00"' \
  --set 'overlay.subtitle="2026-06-21 13:30:00 +12:00"' --set vertical.exaggeration=2 -o still/noon.png ||
  fail "the still at 13:30"
cmp -s still/noon.png sun/frames/frame-00002.png || fail "frame 2 is not relief render at 13:30 with exaggeration 2"

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
touch file
bad unwritable "file: error: cannot be made as the folder of x.mp4" orbit.toml -o file/x.mp4

# 5. No ffmpeg: exit 3 naming the package, nothing written.
mkdir -p nopath && PATH="$work/nopath" "$relief" animate -q orbit.toml -o noffmpeg/x.mp4 2> noffmpeg.txt; code=$?
[ "$code" = 3 ] || fail "without ffmpeg: exit $code, expected 3"
grep -q "apt-get install ffmpeg" noffmpeg.txt || { fail "without ffmpeg:"; cat noffmpeg.txt; }
[ -e noffmpeg ] && fail "without ffmpeg, files were written"
exit $status
