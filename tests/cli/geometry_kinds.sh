#!/usr/bin/env bash
# Every geometry kind against the full mesh2 (the reference), on real scenes at their own size:
# the stills must pass relief diff at --fail 0.04 --failpercent 0.5 (no more than 0.5 % of the
# pixels off by over 4 %); the adaptive mesh's triangles and POV-Ray's parse time are printed
# against the mesh2's. Then what auto chooses: the height field for the default scene (a
# mesh2 of 886,600 triangles), the mesh2 for a rough surface (mountain-sharp) and for a small one.
# Holes: in a raster with a hole (tests/cli/data/volcano2-lake.toml), every kind must leave it
# open: each kind's still may differ from the mesh2's by no more than a third of the pixels by
# which the hole changes the mesh2's still (the same scene from the raster without the hole).
# Usage: geometry_kinds.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
status=0
lake="$src/tests/cli/data/volcano2-lake.toml"
for path in "$src"/scenes/{default,mt-eden-lidar,castilla-y-leon,mountain-gentle}.toml "$lake"; do
  scene=$(basename "$path" .toml)
  for kind in mesh2 height_field adaptive; do
    "$relief" render -q "$path" --set geometry.kind=$kind -o "$work/$scene-$kind.png" ||
      { echo "FAIL: $scene ($kind) did not render"; status=1; continue 2; }
  done
  for kind in height_field adaptive; do
    "$relief" diff "$work/$scene-mesh2.png" "$work/$scene-$kind.png" --fail 0.04 --failpercent 0.5 \
      > "$work/$scene-$kind.diff.txt"
    code=$?
    echo "$scene, $kind against mesh2: $(grep -E '^  all ' "$work/$scene-$kind.diff.txt" | awk '{print "max error " $2 ", PSNR " $NF " dB"}');" \
         "$(grep -o '[0-9]* pixels ([0-9.]* %) over fail 0.04' "$work/$scene-$kind.diff.txt")"
    [ "$code" -le 1 ] || { echo "FAIL: $scene: the $kind still is not the mesh2's"; cat "$work/$scene-$kind.diff.txt"; status=1; }
  done
  parse() { sed -n 's/^ *"povray_parse": \([0-9.]*\),*$/\1/p' "$1"; }
  triangles() { sed -n 's/^ *"triangles": \([0-9]*\),*$/\1/p' "$1" | tail -1; }
  echo "$scene, adaptive: $(triangles "$work/$scene-adaptive.json") triangles against $(triangles "$work/$scene-mesh2.json"), POV-Ray parse $(parse "$work/$scene-adaptive.json") s against $(parse "$work/$scene-mesh2.json") s"
done
failing() { "$relief" diff "$1" "$2" --fail 0.04 --json | sed -n 's/.*"failing_pixels": \([0-9]*\).*/\1/p'; }
"$relief" render -q "$lake" --set geometry.kind=mesh2 --set samples.path="$src/scenes/data/rasters/volcano2.tif" \
  -o "$work/volcano2-no-lake.png" || status=1
hole=$(failing "$work/volcano2-lake-mesh2.png" "$work/volcano2-no-lake.png")
echo "the hole changes ${hole:-?} pixels of the mesh2's still"
[ "${hole:-0}" -gt 1000 ] || { echo "FAIL: the hole does not show in the mesh2's still"; status=1; }
for kind in height_field adaptive; do
  off=$(failing "$work/volcano2-lake-mesh2.png" "$work/volcano2-lake-$kind.png")
  echo "volcano2-lake, $kind: ${off:-?} pixels off the mesh2's"
  [ "${off:-999999}" -lt $(( ${hole:-0} / 3 )) ] || { echo "FAIL: the $kind does not leave the hole open"; status=1; }
done
kind_of() { sed -n 's/^ *"kind": "\(.*\)",*$/\1/p' "$1" | head -1; }
"$relief" compile -q "$src/scenes/default.toml" -o "$work/auto/default.pov" || status=1
[ "$(kind_of "$work/auto/default.json")" = height_field ] || { echo "FAIL: auto did not take the height field for the default scene"; status=1; }
[ -s "$work/auto/default.height.png" ] && [ -s "$work/auto/default.drape.png" ] || { echo "FAIL: no height field PNGs"; status=1; }
"$relief" compile -q "$src/scenes/mountain-sharp.toml" -o "$work/auto/sharp.pov" || status=1
[ "$(kind_of "$work/auto/sharp.json")" = mesh2 ] || { echo "FAIL: auto took the height field for a rough surface"; status=1; }
"$relief" compile -q "$src/tests/golden/small/scene.toml" -o "$work/auto/small.pov" || status=1
[ "$(kind_of "$work/auto/small.json")" = mesh2 ] || { echo "FAIL: auto took the height field for a small mesh"; status=1; }
[ "$status" = 0 ] && echo "every height field and adaptive mesh matches its mesh2; auto chose as expected"
exit $status
