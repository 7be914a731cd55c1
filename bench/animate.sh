#!/usr/bin/env bash
# Films and high-quality stills, whole processes, in one run (bench/RESULTS.md):
#  1. a FRAMES-frame (default 240) 1280 x 720 orbit of scenes/default.toml with --jobs 1: its seconds
#     a frame against one relief render of a frame of it (median of 3); the terrain is compiled
#     once, so a frame should cost at most 1.1x a still. Then the same film with --jobs 2 against
#     --jobs 1 (the same bytes, checked).
#  2. render.quality = "high" against "report" for scenes/default.toml at 1920 x 1080, alternating,
#     medians of 3.
# The sky-view factor of a 2001 x 2001 grid is a Google Benchmark: BM_SkyView in bench_main.cpp.
# Usage: bench/animate.sh [build/relief] [FRAMES]
source "$(dirname "$0")/common.sh"
relief=$(realpath "${1:-build/relief}")
frames=${2:-240}
src=$(cd "$(dirname "$0")/.." && pwd)
scene="$src/scenes/default.toml"
cd "$work"
ratio() { echo "scale=3; $1 / $2" | bc -l; }
film=(--set render.width=1280 --set render.height=720 --set animation.frames="$frames" --set 'animation.path="orbit"')

# The default scene has no [animation]: a copy with one.
cp "$scene" orbit.toml
sed -i "s|^path = \"data/|path = \"$src/scenes/data/|" orbit.toml
printf '\n[animation]\nframes = 1\npath = "orbit"\n' >> orbit.toml

stills=()
for run in 1 2 3; do stills+=("$(time_of "$relief" render -q orbit.toml "${film[@]:0:4}" -o still/s.png)"); done
still=$(median "${stills[@]}")
one=$(time_of "$relief" animate -q orbit.toml "${film[@]}" --jobs 1 -o one/orbit.mp4)
two=$(time_of "$relief" animate -q orbit.toml "${film[@]}" --jobs 2 -o two/orbit.mp4)
cmp -s one/orbit.mp4 two/orbit.mp4 || echo "warning: the films of --jobs 1 and 2 differ"
perframe=$(echo "$one / $frames" | bc -l)
echo "a 1280 x 720 still of the default scene: $still s (median of 3)"
printf 'the %d-frame orbit, --jobs 1: %.1f s, %.3f s a frame = %.3fx a still\n' "$frames" "$one" "$perframe" "$(ratio "$perframe" "$still")"
printf 'the same film, --jobs 2: %.1f s = %.3fx --jobs 1\n' "$two" "$(ratio "$two" "$one")"
grep -A4 '"seconds"' one/orbit.json | tr -d '\n ' ; echo

report() { time_of "$relief" render -q "$scene" --set render.width=1920 --set render.height=1080 -o r/report.png; }
high() { time_of "$relief" render -q "$scene" --set render.width=1920 --set render.height=1080 --set 'render.quality="high"' -o h/high.png; }
a=() b=()
for run in 1 2 3; do a+=("$(report)"); b+=("$(high)"); done
mr=$(median "${a[@]}") mh=$(median "${b[@]}")
echo "1920 x 1080 default still: report $mr s, high $mh s, ratio $(ratio "$mh" "$mr")"
for f in r/report.json h/high.json; do
  echo "  $f: $(grep -o '"povray_parse": [0-9.e+-]*\|"povray_trace": [0-9.e+-]*' "$f" | head -2 | tr '\n' ' ')"
done
