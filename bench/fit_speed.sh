#!/usr/bin/env bash
# net.gridding = "fit" against gdal_grid -a linear, whole processes, alternating, medians of 3:
#  1. 8,000 samples (random cells of volcano2hires.tif) onto a 129 x 129 net;
#  2. 770,000 samples (every cell of holyroodpark.tif resampled to 1050 x 733) onto 129 x 129.
# relief's time is `relief compile` (reading, fitting with GCV, refining once, writing the .pov);
# the sidecar's net.fit.seconds is the fit alone. Needs /usr/bin/python3 with numpy and GDAL.
# Usage: bench/fit_speed.sh [build/relief] [shared/data]
source "$(dirname "$0")/common.sh"
relief=$(realpath "${1:-build/relief}")
data=$(realpath "${2:-$(dirname "$0")/../../shared/data}")
cd "$work"
/usr/bin/python3 - "$data" <<'PY'
import sys, numpy as np
from osgeo import gdal, osr
gdal.UseExceptions()
def samples(raster, out, n=None, size=None):
    ds = gdal.Open(raster)
    if size: ds = gdal.Translate('', ds, format='MEM', width=size[0], height=size[1], resampleAlg='bilinear')
    a = ds.GetRasterBand(1).ReadAsArray().astype(float)
    gt = ds.GetGeoTransform()
    rows, cols = a.shape
    idx = np.arange(rows * cols) if n is None else np.random.default_rng(1).choice(rows * cols, n, replace=False)
    r, c = idx // cols, idx % cols
    x, y = gt[0] + (c + 0.5) * gt[1], gt[3] + (r + 0.5) * gt[5]
    s = osr.SpatialReference(); s.ImportFromWkt(ds.GetProjection()); s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    t = osr.SpatialReference(); t.ImportFromEPSG(4326); t.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    ll = np.array(osr.CoordinateTransformation(s, t).TransformPoints(np.c_[x, y].tolist()))
    u = osr.SpatialReference(); u.ImportFromEPSG(int(sys.argv[2]) if len(sys.argv) > 2 else 32760)
    np.savetxt(out, np.c_[ll[:, :2], a[r, c]], fmt=['%.8f', '%.8f', '%.3f'], delimiter=',', header='lon,lat,elev', comments='')
samples(sys.argv[1] + '/rasters/volcano2hires.tif', 's8k.csv', n=8000)
samples(sys.argv[1] + '/rasters/holyroodpark.tif', 's770k.csv', size=(1050, 733))
PY
for name in s8k s770k; do
  printf '[samples]\npath = "%s.csv"\n[net]\nrows = 129\ncols = 129\ngridding = "fit"\n[subdivision]\nscheme = "dlg4"\ndepth = 1\n' "$name" > "$name.toml"
  # gdal_grid on the same net: the samples in the frame relief chose, over the extent it chose.
  "$relief" compile -q "$name.toml" -o "$name.pov" --dump-net "$name.net.csv"
  read -r x0 y0 x1 y1 < <(awk -F, 'NR > 1 { if (NR == 2 || $1 < a) a = $1; if (NR == 2 || $1 > c) c = $1; if (NR == 2 || $2 < b) b = $2; if (NR == 2 || $2 > d) d = $2 } END { print a, b, c, d }' "$name.net.csv")
  frame=$(grep -o '"frame": "UTM zone [0-9]*[NS]"' "$name.json" | head -1 | grep -o '[0-9]*[NS]')
  zone=${frame%[NS]}
  if [ "${frame: -1}" = N ]; then epsg=$((32600 + zone)); else epsg=$((32700 + zone)); fi
  ogr2ogr -f CSV -s_srs EPSG:4326 -t_srs "EPSG:$epsg" -lco GEOMETRY=AS_XY "$name.utm.csv" "$name.csv" -oo X_POSSIBLE_NAMES=lon -oo Y_POSSIBLE_NAMES=lat 2> /dev/null
  printf '<OGRVRTDataSource><OGRVRTLayer name="p"><SrcDataSource>%s</SrcDataSource><SrcLayer>%s</SrcLayer><GeometryType>wkbPoint</GeometryType><GeometryField encoding="PointFromColumns" x="X" y="Y" z="elev"/></OGRVRTLayer></OGRVRTDataSource>' "$work/$name.utm.csv" "$name.utm" > "$name.vrt"
  dx=$(echo "($x1 - $x0) / 128" | bc -l)
  fit() { time_of "$relief" compile -q "$name.toml" -o "$name.pov"; }
  linear() { time_of gdal_grid -q -a linear -txe "$(echo "$x0 - $dx / 2" | bc -l)" "$(echo "$x1 + $dx / 2" | bc -l)" \
               -tye "$(echo "$y1 + $dx / 2" | bc -l)" "$(echo "$y0 - $dx / 2" | bc -l)" -outsize 129 129 -l p "$name.vrt" "$name.tif"; }
  a=() b=()
  for run in 1 2 3; do a+=("$(fit)"); b+=("$(linear)"); done
  ma=$(median "${a[@]}") mb=$(median "${b[@]}")
  # A gdal_grid that read no point writes zeros quickly: not a time to compare with.
  gdalinfo -stats "$name.tif" 2>/dev/null | grep -q 'Maximum=0.000, Mean=0.000' && { echo "gdal_grid read no point of $name.vrt" >&2; exit 1; }
  fitted=$(/usr/bin/python3 -c "import json, sys; print(round(json.load(open(sys.argv[1]))['net']['fit']['seconds'], 2))" "$name.json")
  echo "$name ($(($(wc -l < "$name.csv") - 1)) samples) onto 129 x 129: relief compile (fit, GCV) $ma s (the fit $fitted s), gdal_grid -a linear $mb s, ratio $(echo "scale=3; $ma / $mb" | bc -l)"
done
