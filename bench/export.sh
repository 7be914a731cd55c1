#!/usr/bin/env bash
# relief export against relief compile of the same scene (the .pov of the same surface: the
# baseline, in the same run), whole processes, alternating, medians of 5: the default scene to
# every format, and a 53 M-cell raster (volcano2hires.tif on a 2.5 m net, 10,482 x 10,482 nodes)
# to a .glb within the default 2,000,000 triangles (the adaptive mesh).
# Usage: bench/export.sh [build/relief] [shared/data]
source "$(dirname "$0")/common.sh"
relief=$(realpath "${1:-build/relief}")
data=$(realpath "${2:-$(dirname "$0")/../../shared/data}")
scene=$(realpath "$(dirname "$0")/../scenes/default.toml")
cd "$work"
row() {  # label, then the export's arguments after the scene; compile's with --compile-args
  local label=$1 input=$2; shift 2
  local e=() c=()
  for _ in 1 2 3 4 5; do
    c+=("$(time_of "$relief" compile -q "$input" -o c.pov "$@")")
    e+=("$(time_of "$relief" export -q "$input" -o "m.$ext" "$@")")
  done
  printf '| %s | %.2f s | %.2f s | %.2fx |\n' "$label" "$(median "${e[@]}")" "$(median "${c[@]}")" \
    "$(echo "$(median "${e[@]}") / $(median "${c[@]}")" | bc -l)"
}
echo "| case | relief export | relief compile (the .pov) | ratio |"
echo "|---|---|---|---|"
for ext in glb gltf stl obj ply; do row "default scene, .$ext" "$scene"; done
ext=glb
row "volcano2hires.tif, 2.5 m net, .glb" "$data/rasters/volcano2hires.tif" --set net.spacing_m=2.5 --set 'samples.vertical_unit="m"'
