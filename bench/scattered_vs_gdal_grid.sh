#!/usr/bin/env bash
# Scattered points at real size: relief compile (depth 0) of the 458,845 valid cells of
# ../shared/data/rasters/holyroodpark.tif written as a lon,lat,elev CSV, onto a 2.5 m UTM net of
# 574 x 822 nodes, against gdal_grid -a linear on the same points (in UTM 30N) and the same net,
# alternating, 5 runs each; prints each median and the ratio of the medians.
# Needs gdal-bin (gdal_translate, gdaltransform, gdal_grid), which relief itself does not.
# Usage: bench/scattered_vs_gdal_grid.sh [build/relief] [raster]
source "$(dirname "$0")/common.sh"
relief=$(realpath "${1:-build/relief}")
raster=$(realpath "${2:-../shared/data/rasters/holyroodpark.tif}")
cd "$work"
gdal_translate -q -of XYZ "$raster" cells.xyz
awk '$3 != "nan" && $3 != "-nan"' cells.xyz > valid.xyz
awk '{print $1, $2}' valid.xyz | gdaltransform -s_srs EPSG:27700 -t_srs EPSG:4326 -output_xy > lonlat.txt
(echo lon,lat,elev; paste -d' ' lonlat.txt <(awk '{print $3}' valid.xyz) |
   awk '{printf "%.8f,%.8f,%.3f\n", $1, $2, $3}') > points.csv
printf '[samples]\npath = "points.csv"\n[net]\nspacing_m = 2.5\n[subdivision]\ndepth = 0\n' > scene.toml
"$relief" compile -q scene.toml -o net.pov    # the net relief builds: its origin and size
read -r x0 y0 < <(sed -n 's/.*"net.origin_m": "\(.*\), \(.*\)",/\1 \2/p' net.json)
rows=$(sed -n 's/^ *"rows": \([0-9]*\),/\1/p' net.json | head -1)
cols=$(sed -n 's/^ *"cols": \([0-9]*\),/\1/p' net.json | head -1)
(echo x,y,z; tail -n +2 points.csv | tr ',' ' ' | gdaltransform -s_srs EPSG:4326 -t_srs EPSG:32630 |
   awk '{printf "%.4f,%.4f,%s\n", $1, $2, $3}') > utm.csv
printf '<OGRVRTDataSource><OGRVRTLayer name="utm"><SrcDataSource>%s/utm.csv</SrcDataSource><GeometryType>wkbPoint</GeometryType><GeometryField encoding="PointFromColumns" x="x" y="y" z="z"/></OGRVRTLayer></OGRVRTDataSource>\n' "$work" > utm.vrt
ext=$(awk -v x0="$x0" -v y0="$y0" -v r="$rows" -v c="$cols" \
      'BEGIN {printf "-txe %.6f %.6f -tye %.6f %.6f", x0 - 1.25, x0 + (c - 0.5) * 2.5, y0 - 1.25, y0 + (r - 0.5) * 2.5}')
r=(); g=()
for run in 1 2 3 4 5; do
  r+=("$(time_of "$relief" compile -q scene.toml -o run.pov)")
  # shellcheck disable=SC2086
  g+=("$(time_of gdal_grid -q -a linear:radius=0 $ext -outsize "$cols" "$rows" -ot Float64 utm.vrt grid.tif)")
done
rm=$(median "${r[@]}"); gm=$(median "${g[@]}")
printf '%d points onto %s x %s nodes\nrelief compile (depth 0): %.2f s\ngdal_grid -a linear:     %.2f s\nratio relief / gdal_grid: %.2f\n' \
  "$(($(wc -l < points.csv) - 1))" "$rows" "$cols" "$rm" "$gm" "$(echo "$rm / $gm" | bc -l)"
