#!/usr/bin/env bash
# A DEM alone at any size: `relief render dem.tif` (no scene keys but the path) at 1920 x 1080 on
# rasters of about 1 M, 6 M, 53 M and 200 M cells, made from one shared raster with gdalwarp; for
# each, relief's seconds and peak memory (the largest process: relief or POV-Ray), the seconds
# per stage from the sidecar, and, in the same run, gdal_translate -outsize -r average of the same
# raster to the net's size (reading the file onto the net, the floor any renderer pays), medians
# of three runs each, alternating. Then the refusal of an over-limit job: the largest raster with
# net.spacing_m at its own cell (time to the error). Last, a net at a raster's own cell with and
# without net.spacing_m (no node masked either way: the same geometry, the same seconds), on the
# shared holyroodpark.tif when it is there.
# Needs gdal-bin, bc and GNU time.
# Usage: bench/first_try.sh [build/relief] [raster] [sides...]
#   sides: the rasters' sides in cells (default 1000 2450 7280 14142)
source "$(dirname "$0")/common.sh"
relief=$(realpath "${1:-build/relief}")
own=$(realpath -m "$(dirname "$0")/../../shared/data/rasters/holyroodpark.tif")
raster=$(realpath "${2:-../shared/data/rasters/volcano2hires.tif}")
shift $(( $# > 2 ? 2 : $# ))
sides=("${@:-1000 2450 7280 14142}")
# shellcheck disable=SC2206
sides=(${sides[*]})
cd "$work"
# Seconds and peak resident KB of a command: "S KB".
measured() { /usr/bin/time -f '%e %M' -o t.txt "$@" >/dev/null 2>err.txt || { cat err.txt >&2; return 1; }; cat t.txt; }
json() { sed -n "s/^ *\"$1\": \([0-9.e+-]*\),*$/\1/p" "$2" | head -1; }

printf '| cells | net | depth | geometry | relief render | peak MB | normalize | subdivide | emit | POV-Ray | gdal_translate to the net | ratio normalize / gdal_translate |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|---|\n'
for side in "${sides[@]}"; do
  gdalwarp -q -overwrite -ts "$side" "$side" -r cubic -ot Float32 -co TILED=YES "$raster" "dem-$side.tif"
  sidecar=still-$side.json
  # Three runs each, relief and gdal_translate alternating: medians (the machine is shared).
  times=() kbs=() normalizes=() gts=()
  for _ in 1 2 3; do
    read -r seconds kb < <(measured "$relief" render -q "dem-$side.tif" -o "still-$side.png" \
                             --set render.width=1920 --set render.height=1080)
    times+=("$seconds") kbs+=("$kb") normalizes+=("$(json normalize "$sidecar")")
    rows=$(json rows "$sidecar"); cols=$(sed -n 's/^ *"cols": \([0-9]*\),*$/\1/p' "$sidecar" | head -1)
    read -r gt _ < <(measured gdal_translate -q -outsize "$cols" "$rows" -r average "dem-$side.tif" net.tif)
    gts+=("$gt")
  done
  seconds=$(median "${times[@]}") kb=$(median "${kbs[@]}") normalize=$(median "${normalizes[@]}") gt=$(median "${gts[@]}")
  depth=$(json depth "$sidecar")
  kind=$(sed -n 's/^ *"geometry": "\([a-z_0-9]*\) .*/\1/p' "$sidecar" | head -1)
  povray=$(sed -n 's/^ *"povray_wall": \([0-9.e+-]*\),*$/\1/p' "$sidecar" | head -1)
  povray=${povray:+$(printf '%.2f s' "$povray")}
  printf '| %s M | %s x %s | %s | %s | %.2f s | %.0f | %.2f s | %.2f s | %.2f s | %s | %.2f s | %.2f |\n' \
    "$(echo "$side * $side / 1000000" | bc -l | xargs printf '%.1f')" "$rows" "$cols" "$depth" "$kind" "$seconds" \
    "$(echo "$kb / 1024" | bc -l)" "$normalize" "$(json subdivide "$sidecar")" "$(json emit "$sidecar")" \
    "${povray:-(no POV-Ray time)}" "$gt" "$(echo "$normalize / $gt" | bc -l)"
  last=$side
done

# Over the limits at the raster's own cell: refused from the header, before reading a height.
cell=$(gdalinfo "dem-$last.tif" | sed -n 's/^Pixel Size = (\([0-9.]*\),.*/\1/p')
t0=$(date +%s.%N)
"$relief" compile -q "dem-$last.tif" -o refused.pov --set net.spacing_m="$cell" --set subdivision.depth=2 \
  --set geometry.kind='"mesh2"' 2>refusal.txt && { echo "not refused" >&2; exit 1; }
t1=$(date +%s.%N)
printf '\nrefusal of dem-%s.tif at net.spacing_m = %s, depth 2, mesh2: %.3f s\n  %s\n' "$last" "$cell" \
  "$(echo "$t1 - $t0" | bc -l)" "$(head -1 refusal.txt)"

# The net at the raster's own cell, given and not given: alternating runs, medians of 3.
[ -f "$own" ] || { echo "no $own: the last comparison is not run"; exit 0; }
"$relief" render -q "$own" -o own.png --set render.width=1920 --set render.height=1080 2>err.txt ||
  { cat err.txt >&2; exit 1; }
cell=$(gdalinfo "$own" | sed -n 's/^Pixel Size = (\([0-9.]*\),.*/\1/p')
masked() { sed -n 's/^ *"masked_nodata": \([0-9]*\),*$/\1/p' "$1" | head -1; }
geometry() { sed -n 's/^ *"kind": "\([a-z_0-9]*\)",*$/\1/p' "$1" | head -1; }
without=() with=()
for _ in 1 2 3; do
  without+=("$(time_of "$relief" render -q "$own" -o own.png --set render.width=1920 --set render.height=1080)")
  with+=("$(time_of "$relief" render -q "$own" -o own-spaced.png --set render.width=1920 --set render.height=1080 \
              --set net.spacing_m="$cell")")
done
a=$(median "${without[@]}") b=$(median "${with[@]}")
printf '\n%s at 1920 x 1080, its own %s m cell:\n' "$(basename "$own")" "$cell"
printf '  without net.spacing_m: %.2f s, %s, %s masked nodes\n' "$a" "$(geometry own.json)" "$(masked own.json)"
printf '  net.spacing_m = %s: %.2f s, %s, %s masked nodes; ratio %.2f\n' "$cell" "$b" "$(geometry own-spaced.json)" \
  "$(masked own-spaced.json)" "$(echo "$b / $a" | bc -l)"
