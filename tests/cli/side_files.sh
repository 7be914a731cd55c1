#!/usr/bin/env bash
# The files GDAL reads beside a dataset, or inside an archive it opens, are checked before GDAL
# opens it: a shapefile's .dbf that is a FIFO (GDAL would block on it for ever), as a [[layer]] and
# as a flyover's track; an 8 GB sparse .prj (GDAL reads it whole) beside a shapefile and beside an
# ESRI ASCII grid; a .shp.zip whose .prj inflates to 100 MB, and one whose .prj inflates past the
# 145 bytes it declares. Each is refused at once: exit 2, one line naming the file and the fix,
# nothing written (each run has 20 s, under a 2 GB address-space limit). A layer in a geocentric
# CRS (EPSG:4978) lands where the same layer in WGS84 does, with a warning that its heights are
# not used; one without Z there is an error.
# Usage: side_files.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
enter_fresh_work
cp "$src/tests/data/rasters/maungawhau-20m.tif" dem.tif
cp "$src/tests/data/vectors/maungawhau-features.geojson" features.geojson
ogr2ogr -f "ESRI Shapefile" walk.shp "$src/tests/data/vectors/maungawhau-walk.gpx" tracks 2> /dev/null &&
  gdal_translate -q -of AAIGrid dem.tif grid.asc &&
  [ -f walk.dbf ] && [ -f walk.prj ] && [ -f grid.prj ] || { fail "ogr2ogr or gdal_translate"; exit 1; }

# A 2 GB address-space limit, which reading a 600 MB file whole would come near (not under
# AddressSanitizer, whose shadow memory alone is more than that).
limit=(bash -c 'ulimit -v 2000000; exec "$0" "$@"')
"${limit[@]}" "$relief" --version > /dev/null 2>&1 || limit=()
# expect NAME EXPECTED_STDERR relief-arguments...: the exact stderr, exit 2, nothing written, no hang.
expect() {
  local name=$1 text=$2; shift 2
  rm -rf out
  timeout 20 "${limit[@]}" "$relief" "$@" > stdout.txt 2> stderr.txt
  local code=$?
  [ "$code" = 124 ] && { fail "$name: still running after 20 s"; return; }
  [ "$code" = 2 ] || fail "$name: exit $code, expected 2"
  if [ "$(cat stderr.txt)" != "$text" ]; then
    fail "$name: stderr differs"; echo "--- expected"; echo "$text"; echo "--- actual"; cat stderr.txt
  fi
  [ -d out ] && [ -n "$(ls -A out)" ] && fail "$name: output written: $(ls -A out)"
}
layer() {  # layer SCENE PATH: the DEM and one [[layer]] of PATH
  printf '[samples]\npath = "dem.tif"\nvertical_unit = "m"\n[[layer]]\npath = "%s"\n' "$2" > "$1"
}
nothing="relief: 1 error, 0 warnings; nothing written"

# Beside a shapefile: its .dbf a FIFO, as a layer and as a flyover's track.
layer shp.toml walk.shp
"$relief" compile -q shp.toml -o ok/x.pov 2> ok.txt || { fail "the shapefile as a layer:"; cat ok.txt; }
mv walk.dbf walk.dbf.real && mkfifo walk.dbf
expect dbf-fifo "shp.toml:5:8: error: layer.path: walk.shp: the file beside it that GDAL would read with it, walk.dbf, is not a plain file (it is a FIFO (a named pipe), not a file); remove it, or put the real file there
$nothing" compile -q shp.toml -o out/x.pov
cat > track.toml <<'TOML'
[samples]
path = "dem.tif"
vertical_unit = "m"
[render]
width = 240
height = 160
[animation]
frames = 3
path = "flyover"
height_above_terrain_m = 60
track = "walk.shp"
TOML
expect track-dbf-fifo "track.toml:11:9: error: walk.shp: the file beside it that GDAL would read with it, walk.dbf, is not a plain file (it is a FIFO (a named pipe), not a file); remove it, or put the real file there
$nothing" animate -q track.toml -o out/x.mp4
rm walk.dbf && mv walk.dbf.real walk.dbf

# An 8 GB sparse .prj (no disk: truncate writes no block), beside the shapefile and beside an
# ESRI ASCII grid.
mv walk.prj walk.prj.real && truncate -s 8G walk.prj
expect prj-huge "shp.toml:5:8: error: layer.path: walk.shp: the file beside it that GDAL would read whole with it, walk.prj: it is 8.59 GB, more than the 16 MB such a file may be; remove it, or put the real file there
$nothing" compile -q shp.toml -o out/x.pov
rm walk.prj && mv walk.prj.real walk.prj
printf '[samples]\npath = "grid.asc"\nvertical_unit = "m"\n' > asc.toml
"$relief" compile -q asc.toml -o ok/asc.pov 2> ok.txt || { fail "the ASCII grid:"; cat ok.txt; }
truncate -s 8G grid.prj
expect asc-prj-huge "grid.asc: error: samples.path: relief does not read this raster: the file beside it that GDAL would read whole with it, grid.prj: it is 8.59 GB, more than the 16 MB such a file may be; remove it, or put the real file there (what a scene's raster may bring with it: docs/security.md)
$nothing" compile -q asc.toml -o out/x.pov

# Zipped shapefiles: a good one is read; one whose .prj inflates to 100 MB (a 100 kB bomb) and one
# whose .prj says 145 bytes but inflates to 100 MB are refused before GDAL inflates them.
python3 - <<'PY' || fail "the archives"
import struct, zipfile
def archive(name, prj):
    with zipfile.ZipFile(name, 'w', zipfile.ZIP_DEFLATED) as z:
        for ext in ('shp', 'shx', 'dbf'):
            z.write('walk.' + ext)
        z.writestr('walk.prj', prj)
archive('good.shp.zip', open('walk.prj', 'rb').read())
archive('bomb.shp.zip', bytes(100 << 20))
# The liar: the .prj's sizes in its local header and in the central directory set to 145 bytes.
archive('liar.shp.zip', bytes(100 << 20))
data = bytearray(open('liar.shp.zip', 'rb').read())
for signature, name_length_at, size_at, name_at in ((b'PK\x03\x04', 26, 22, 30), (b'PK\x01\x02', 28, 24, 46)):
    i = data.find(signature)
    while i >= 0:
        n = struct.unpack_from('<H', data, i + name_length_at)[0]
        if data[i + name_at:i + name_at + n] == b'walk.prj':
            struct.pack_into('<I', data, i + size_at, 145)
        i = data.find(signature, i + 4)
open('liar.shp.zip', 'wb').write(data)
PY
layer zip.toml good.shp.zip
"$relief" compile -q zip.toml -o ok/zip.pov 2> ok.txt || { fail "the zipped shapefile:"; cat ok.txt; }
layer bomb.toml bomb.shp.zip
expect zip-bomb "bomb.toml:5:8: error: layer.path: bomb.shp.zip: its file walk.prj, which GDAL reads whole, inflates to 105 MB, more than the 16 MB such a file may be; remove it from the archive, or give the real files
$nothing" compile -q bomb.toml -o out/x.pov
layer liar.toml liar.shp.zip
expect zip-liar "liar.toml:5:8: error: layer.path: liar.shp.zip: its file walk.prj inflates to more than the 145 bytes it declares: the archive is damaged or forged; give the real files
$nothing" compile -q liar.toml -o out/x.pov

# A geocentric CRS: the features land where they do in WGS84 (the same point off the terrain, no
# other), and a warning says their heights are not used; without Z, an error.
ogr2ogr -f GPKG -t_srs EPSG:4978 -dim XYZ ecef.gpkg features.geojson 2> /dev/null &&
  ogr2ogr -f GPKG -t_srs EPSG:4978 -dim XY ecef2d.gpkg features.geojson 2> /dev/null || fail "ogr2ogr to EPSG:4978"
layer wgs84.toml features.geojson
layer ecef.toml ecef.gpkg
"$relief" compile -q wgs84.toml -o ok/wgs84.pov 2> wgs84.txt || { fail "the layer in WGS84:"; cat wgs84.txt; }
"$relief" compile -q ecef.toml -o ok/ecef.pov 2> ecef.txt || { fail "the layer in EPSG:4978:"; cat ecef.txt; }
grep -q "^ecef.toml:5:8: warning: layer 1 (ecef.gpkg): its CRS is geocentric (X, Y, Z from the Earth's centre): each vertex is placed from all three, and its height is not used (a layer lies on the surface)$" ecef.txt ||
  { fail "no warning that the geocentric layer's heights are not used:"; cat ecef.txt; }
[ "$(grep -c 'off the terrain' wgs84.txt)" = 1 ] && [ "$(grep -c 'off the terrain' ecef.txt)" = 1 ] ||
  { fail "the geocentric layer is not where the WGS84 one is:"; cat wgs84.txt ecef.txt; }
layer ecef2d.toml ecef2d.gpkg
"$relief" compile -q ecef2d.toml -o out/x.pov 2> ecef2d.txt; code=$?
[ "$code" = 2 ] || fail "a geocentric layer without Z: exit $code, expected 2"
grep -q "ecef2d.toml:5:8: error: ecef2d.gpkg: feature 1 has no Z: in a geocentric CRS (X, Y, Z from the Earth's centre) a vertex needs all three to be a place; give the layer with its Z or in longitude and latitude$" ecef2d.txt ||
  { fail "a geocentric layer without Z:"; cat ecef2d.txt; }

[ "$status" = 0 ] && echo "the files GDAL reads beside a dataset or in an archive were checked first"
exit $status
