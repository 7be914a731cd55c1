#!/usr/bin/env bash
# Big terrain, scene file to PNG: relief render (the default geometry kind) of a real DEM refined
# to about 2400 x 1650 vertices and of a 2049 x 2049 refined grid, at 1280 x 720 with
# antialiasing, against POV-Ray rendering a bare height_field scene of the same grid (relief's
# 16-bit heights, camera, sun and placement, so the terrain covers the same pixels; a gradient
# pigment instead of the drape, no overlays; the same image size and antialiasing),
# alternating, 3 runs each; prints the medians, the ratio and where relief's time went (its
# sidecar), and the full mesh2's still against relief's (relief diff).
# The DEMs: ../shared/data/rasters/holyroodpark.tif on a 1.7 m net and volcano2hires.tif on a
# 1,025 x 1,025 net, both at depth 1. Needs povray and bc.
# Usage: bench/render_vs_height_field.sh [build/relief] [rasters folder]
source "$(dirname "$0")/common.sh"
relief=$(realpath "${1:-build/relief}")
rasters=$(realpath "${2:-../shared/data/rasters}")
cd "$work"
one_case() {  # name raster net-keys
  local name=$1 raster=$2 net=$3
  printf '[samples]\npath = "%s"\nvertical_unit = "m"\n[net]\n%s\n[subdivision]\nscheme = "four-point-4p"\ndepth = 1\n[render]\nwidth = 1280\nheight = 720\n' \
    "$raster" "$net" > "$name.toml"
  "$relief" render -q "$name.toml" -o "$name.png"
  local size kind
  size=$(sed -n 's/.*"refined.size": "\(.*\)",/\1/p' "$name.json")
  kind=$(sed -n 's/^ *"kind": "\(.*\)",*$/\1/p' "$name.json" | head -1)
  cp "$name.height.png" "$name-hf.png" 2>/dev/null || { echo "$name: relief chose $kind, not a height field"; return; }
  # The same image, bare: relief's camera, sun, sky and height-field placement (so the terrain
  # covers the same pixels), the heights' PNG, a plain gradient pigment; no drape, no overlays.
  {
    printf '#version 3.7;\nglobal_settings { assumed_gamma 1.0 ambient_light rgb <1, 1, 1> }\n'
    awk '/^camera \{/,/^\}/ {print} /^  light_source \{/,/^  \}/ {print} /^sky_sphere \{/,/^\}/ {print}' "$name.pov"
    printf 'height_field { png "%s-hf.png" smooth\n' "$name"
    printf '  pigment { gradient y color_map { [0 color rgb <0.2, 0.45, 0.2>] [1 color rgb <0.9, 0.9, 0.85>] } }\n'
    grep -E '^  (scale|translate) <' "$name.pov"
    printf '}\n'
  } > "$name-hf.pov"
  local r=() p=()
  for run in 1 2 3; do
    r+=("$(time_of "$relief" render -q "$name.toml" -o "$name.png")")
    p+=("$(time_of povray "+I$name-hf.pov" "+O$name-hf-out.png" +W1280 +H720 -D -P +A0.3 +AM2 +R3 -J)")
  done
  local rm pm
  rm=$(median "${r[@]}"); pm=$(median "${p[@]}")
  printf '%s: refined %s, relief chose %s\n' "$name" "$size" "$kind"
  printf '  relief render:            %6.2f s\n  povray height_field scene: %6.2f s\n  ratio:                    %6.2f\n' \
    "$rm" "$pm" "$(echo "$rm / $pm" | bc -l)"
  printf '  relief seconds (sidecar): %s\n' "$(tr -d '\n ' < "$name.json" | sed -n 's/.*"seconds":{\([^}]*\)}.*/\1/p')"
  "$relief" render -q "$name.toml" --set geometry.kind=mesh2 -o "$name-mesh2.png"
  printf '  mesh2 render:             %s; its still against relief'"'"'s: %s\n' \
    "$(tr -d '\n ' < "$name-mesh2.json" | sed -n 's/.*"povray_wall":\([0-9.]*\).*/\1 s/p')" \
    "$("$relief" diff "$name-mesh2.png" "$name.png" --fail 0.04 --failpercent 0.5 | grep -E '^  all|PASS|WARNING|FAILURE' | tr -s ' ' | tr '\n' ' ')"
}
one_case arthurs-seat "$rasters/holyroodpark.tif" 'spacing_m = 1.7'
one_case mt-eden-2049 "$rasters/volcano2hires.tif" $'rows = 1025\ncols = 1025'
