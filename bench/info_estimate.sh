#!/usr/bin/env bash
# relief info on a 53 M-cell raster with a net finer than the still (net.spacing_m = 2.5: 10482 x
# 10482 nodes), which it estimates without reading the net, against relief init of the same
# (which plans on the net read: what relief info did before), alternating, 3 runs each. Prints the
# medians of the whole processes, their peak memory (GNU time's maximum resident set) and the ratio.
# The raster is ../shared/data/rasters/volcano2hires.tif (Mt Eden LiDAR, NZTM) resampled to
# 7280 x 7280 cells (cubic) and given cells of 3.6 m.
# Needs gdal-bin (gdalwarp, gdal_edit.py), GNU time and bc, which relief itself does not.
# Usage: bench/info_estimate.sh [build/relief] [raster]
source "$(dirname "$0")/common.sh"
relief=$(realpath "${1:-build/relief}")
raster=$(realpath "${2:-../shared/data/rasters/volcano2hires.tif}")
cd "$work"
gdalwarp -q -ts 7280 7280 -r cubic "$raster" big.tif
read -r x0 y1 < <(gdalinfo big.tif | sed -n 's/^Upper Left *( *\([0-9.]*\), *\([0-9.]*\)).*/\1 \2/p')
gdal_edit.py -a_ullr "$x0" "$y1" "$(echo "$x0 + 7280 * 3.6" | bc -l)" "$(echo "$y1 - 7280 * 3.6" | bc -l)" big.tif
peak() { /usr/bin/time -f %M "$@" 2>&1 >/dev/null | tail -1; }
i=(); n=()
for run in 1 2 3; do
  i+=("$(time_of "$relief" info big.tif --set net.spacing_m=2.5)")
  n+=("$(time_of "$relief" init big.tif --set net.spacing_m=2.5 --force -q -o init.toml)")
done
im=$(median "${i[@]}"); nm=$(median "${n[@]}")
printf '7280 x 7280 cells of 3.6 m, net.spacing_m = 2.5 (10482 x 10482 nodes)\n'
printf 'relief info (estimated), whole process: %.2f s, %s kB peak\n' "$im" "$(peak "$relief" info big.tif --set net.spacing_m=2.5)"
printf 'relief init (net read), whole process:  %.2f s, %s kB peak\n' "$nm" \
  "$(peak "$relief" init big.tif --set net.spacing_m=2.5 --force -q -o init.toml)"
printf 'ratio info / init: %.3f\n' "$(echo "$im / $nm" | bc -l)"
