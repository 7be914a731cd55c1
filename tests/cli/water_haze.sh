#!/usr/bin/env bash
# [water] level_m and [atmosphere] haze on the topobathy mountains (sea and a lake below 0 m):
# the .pov gets a water surface at the level over the terrain's extent and a distance fog; the
# still changes where the sea is (water) and everywhere (haze).
# Usage: water_haze.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
status=0
# The example scene without its own water and haze, its data where it is.
scene="$work/mountain-gentle-plain.toml"
sed '/^\[water\]/,/^$/d; /^\[atmosphere\]/,/^$/d' "$src/scenes/mountain-gentle.toml" > "$scene"
grep -Eq '^\[(water|atmosphere)\]' "$scene" && { echo "FAIL: the plain scene keeps water or haze"; exit 1; }
size=(--set render.width=320 --set render.height=240 --set subdivision.depth=2
      --set samples.path="$src/scenes/data/topobathy_full.csv")
"$relief" render -q "$scene" "${size[@]}" -o "$work/plain.png" || status=1
"$relief" render -q "$scene" "${size[@]}" --set water.level_m=0 -o "$work/water.png" || status=1
"$relief" render -q "$scene" "${size[@]}" --set atmosphere.haze=0.5 -o "$work/haze.png" || status=1
grep -q '^// Water at 0 m above sea level' "$work/water.pov" || { echo "FAIL: no water in the .pov"; status=1; }
grep -A1 '^box {' "$work/water.pov" | grep -Eq '<-?[0-9.]+, -0\.[0-9]+, -?[0-9.]+>, <-?[0-9.]+, 0(\.0+)?, ' ||
  { echo "FAIL: the water's top is not at y = 0 (UTM, sea level)"; grep -A1 '^box {' "$work/water.pov"; status=1; }
grep -q '^fog { fog_type 1 distance' "$work/haze.pov" || { echo "FAIL: no fog in the .pov"; status=1; }
grep -q '^fog' "$work/water.pov" && { echo "FAIL: fog without haze"; status=1; }
changed() { "$relief" diff "$1" "$2" --fail 0.04 --json | sed -n 's/.*"failing_percent": \([0-9.e+-]*\).*/\1/p'; }
w=$(changed "$work/plain.png" "$work/water.png"); h=$(changed "$work/plain.png" "$work/haze.png")
echo "water changes ${w:-?} % of the pixels, haze ${h:-?} %"
awk -v w="${w:-0}" -v h="${h:-0}" 'BEGIN { exit !(w > 0.5 && w < 30 && h > 50) }' ||
  { echo "FAIL: water should change the sea only (0.5-30 %), haze most of the still"; status=1; }
exit $status
