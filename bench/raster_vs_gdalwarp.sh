#!/usr/bin/env bash
# Raster to net: relief compile (depth 0) of a 1,000 x 1,000-cell DEM onto a net of the same
# spacing, against gdalwarp -r bilinear onto the same net (the same UTM frame, origin and size),
# alternating, 5 runs each. Prints the medians of the whole processes, relief's own resampling
# stage (the sidecar's seconds.normalize) and the ratios. The DEM is
# ../shared/data/rasters/volcano2hires.tif (Mt Eden LiDAR, NZTM, 708 x 708 cells of 2.03 m)
# resampled to 1,000 x 1,000 cells of 1.44 m (cubic) in its own CRS.
# Needs gdal-bin (gdalwarp, gdalinfo) and bc, which relief itself does not.
# Usage: bench/raster_vs_gdalwarp.sh [build/relief] [raster]
source "$(dirname "$0")/common.sh"
relief=$(realpath "${1:-build/relief}")
raster=$(realpath "${2:-../shared/data/rasters/volcano2hires.tif}")
cd "$work"
gdalwarp -q -ts 1000 1000 -r cubic "$raster" dem.tif
cell=$(gdalinfo dem.tif | sed -n 's/^Pixel Size = (\([0-9.]*\),.*/\1/p')
printf '[samples]\npath = "dem.tif"\n[net]\nspacing_m = %s\n[subdivision]\ndepth = 0\n' "$cell" > scene.toml
"$relief" compile -q scene.toml -o net.pov 2>/dev/null  # the net relief builds: its frame, origin and size
read -r x0 y0 < <(sed -n 's/.*"net.origin_m": "\(.*\), \(.*\)",/\1 \2/p' net.json)
rows=$(sed -n 's/^ *"rows": \([0-9]*\),/\1/p' net.json | head -1)
cols=$(sed -n 's/^ *"cols": \([0-9]*\),/\1/p' net.json | head -1)
zone=$(sed -n 's/.*"frame": "UTM zone \([0-9]*\)\([NS]\)".*/\1 \2/p' net.json | head -1)
epsg=$(awk -v z="${zone% *}" -v h="${zone#* }" 'BEGIN {print (h == "N" ? 32600 : 32700) + z}')
ext=$(awk -v x0="$x0" -v y0="$y0" -v r="$rows" -v c="$cols" -v d="$cell" \
      'BEGIN {printf "%.6f %.6f %.6f %.6f", x0 - d / 2, y0 - d / 2, x0 + (c - 0.5) * d, y0 + (r - 0.5) * d}')
r=(); s=(); g=()
for run in 1 2 3 4 5; do
  r+=("$(time_of "$relief" compile -q scene.toml -o run.pov)")
  s+=("$(sed -n 's/^ *"normalize": \([0-9.e-]*\),*/\1/p' run.json)")
  # shellcheck disable=SC2086
  g+=("$(time_of gdalwarp -q -overwrite -t_srs "EPSG:$epsg" -te $ext -ts "$cols" "$rows" -r bilinear -ot Float64 dem.tif warped.tif)")
done
rm=$(median "${r[@]}"); sm=$(median "${s[@]}"); gm=$(median "${g[@]}")
printf '1000 x 1000 cells of %s m onto %s x %s nodes (EPSG:%s)\n' "$cell" "$rows" "$cols" "$epsg"
printf 'relief compile (depth 0), whole process: %.3f s (its .pov: %s bytes)\n' "$rm" "$(stat -c %s run.pov)"
printf 'relief resampling stage (sidecar):      %.3f s\n' "$sm"
printf 'gdalwarp -r bilinear, whole process:     %.3f s\n' "$gm"
printf 'ratio relief stage / gdalwarp:   %.2f\nratio relief whole / gdalwarp:   %.2f\n' \
  "$(echo "$sm / $gm" | bc -l)" "$(echo "$rm / $gm" | bc -l)"
