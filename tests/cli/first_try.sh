#!/usr/bin/env bash
# A DEM on the first try, as a new user types it: `relief render dem.tif` (no scene file),
# `relief init` (the scene written out) rendering to the same PNG bytes, `relief info` (its exact
# output for a small committed raster), a CSV alone, a file that is neither, and the default depth
# for a thumbnail and a poster of the same DEM.
# Usage: first_try.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
dem=$src/tests/data/rasters/maungawhau-20m.tif
expected=$src/tests/cli/first_try

# relief render DEM: the still, its .pov and sidecar, named after the DEM; the sidecar keeps the
# scene relief made.
"$relief" render -q "$dem" -o alone/dem.png 2>render.err
rc=$?
[ "$rc" = 0 ] || { fail "relief render DEM exited $rc"; cat render.err; }
[ -s alone/dem.png ] && [ -s alone/dem.pov ] && [ -s alone/dem.json ] || fail "relief render DEM wrote no still, .pov or sidecar"
grep -q '"scene_made_for_the_data": "# The scene relief makes for maungawhau-20m.tif' alone/dem.json ||
  fail "the sidecar does not keep the scene relief made"
grep -q '^// subdivision.depth: 5 (chosen for the still: ' alone/dem.pov ||
  fail "the .pov header does not say the depth and why: $(grep '^// subdivision.depth' alone/dem.pov)"

# relief init: the commented scene; rendering it gives the same PNG, byte for byte.
"$relief" init -q "$dem" -o scene/dem.toml || fail "relief init exited $?"
diff <(sed 's|^path = .*|path = (the DEM)|' scene/dem.toml) "$expected/init.toml" > init.diff ||
  { fail "relief init wrote another scene:"; cat init.diff; }
"$relief" render -q scene/dem.toml -o fromscene/dem.png || fail "relief render of relief init's scene exited $?"
cmp -s alone/dem.png fromscene/dem.png || fail "relief init + relief render is not the still relief render DEM made"
# init does not replace a file unless asked.
"$relief" init -q "$dem" -o scene/dem.toml 2>exists.err
rc=$?
[ "$rc" = 2 ] && grep -qx "relief: error: scene/dem.toml exists: give another -o, or --force to replace it" exists.err ||
  { fail "relief init over an existing file: exit $rc"; cat exists.err; }

# relief info: the plan and its cost, exactly.
"$relief" info "$dem" 2>/dev/null | sed 's|^\(  memory_mb: [0-9.]* (limit \)[0-9]*)|\1M)|' > info.txt
diff info.txt "$expected/info.txt" > info.diff || { fail "relief info says otherwise:"; cat info.diff; }
# A net finer than the still's pixels: said, with the spacing that would match them.
"$relief" info "$dem" --set net.spacing_m=2 --set render.width=160 --set render.height=100 2> fine.err > /dev/null ||
  fail "relief info of a fine net exited $?"
grep -qE "warning: the net's [0-9]+ x [0-9]+ nodes \(.*\) are more than twice the still's 160 x 100 pixels \(1\.6e\+04\): net\.spacing_m = [0-9.]+ would match them" fine.err ||
  { fail "relief info did not warn of a net finer than the still:"; cat fine.err; }
"$relief" info --json "$dem" 2>/dev/null | grep -q '"depth": 5,' || fail "relief info --json gives no depth 5"

# The default depth follows the still: a thumbnail gets fewer levels than a poster.
depth_for() { "$relief" info "$dem" --set render.width="$1" --set render.height="$2" 2>/dev/null |
                sed -n 's/^  depth: //p'; }
[ "$(depth_for 160 120)" = 2 ] || fail "a 160 x 120 thumbnail got depth $(depth_for 160 120), not 2"
[ "$(depth_for 3840 2160)" = 7 ] || fail "a 3840 x 2160 poster got depth $(depth_for 3840 2160), not 7"

# A CSV of lon,lat,elev alone: gridded onto relief's 64 x 64 net.
"$relief" compile -q "$src/scenes/data/volcano_samples_1000_seed20251124.csv" -o csv/samples.pov 2>csv.err ||
  { fail "relief compile CSV exited $?"; cat csv.err; }
grep -q '^// net.size: 64 rows x 64 cols' csv/samples.pov 2>/dev/null || fail "the CSV's scene has no 64 x 64 net"

# A file that is neither: one line saying what relief reads, exit 2, nothing written.
printf 'no TOML\x00\x01\x02 and no commas\n' > neither.bin
"$relief" render neither.bin -o neither/x.png 2>neither.err
rc=$?
[ "$rc" = 2 ] || fail "a file that is neither exited $rc, not 2"
grep -q '^neither.bin: error: relief reads a scene file (TOML), a raster DEM GDAL opens (GeoTIFF, SRTM .hgt, ESRI ASCII grid, VRT, ...), a folder of such tiles or a CSV of lon,lat,elev samples, and this is none of them (not TOML: ' neither.err ||
  { fail "a file that is neither got another message:"; cat neither.err; }
[ -z "$(find . -path './neither/*' -type f)" ] || fail "a file that is neither left $(find neither -type f) behind"

# Tiles of one DEM (gdal_translate -srcwin): two halves render to the still the whole makes; three
# quarters warn of the gap; a tile in another CRS is an error naming both.
command -v gdal_translate >/dev/null || { fail "gdal_translate (gdal-bin) is not installed"; exit 1; }
mkdir -p tiles
cut() { gdal_translate -q "$dem" "tiles/$1.tif" -srcwin "$2" "$3" "$4" "$5" "${@:6}"; }
cut west 0 0 16 44 && cut east 16 0 15 44 && cut nw 0 0 16 22 && cut sw 0 22 16 22 && cut se 16 22 15 22 &&
  cut utm 16 0 15 44 -a_srs EPSG:32760 || fail "gdal_translate could not cut the tiles"
printf '[samples]\npath = ["west.tif", "east.tif"]\n[overlay]\ntitle = "Maungawhau / Mt Eden"\n' > tiles/halves.toml
"$relief" render -q tiles/halves.toml -o tiles/halves.png 2>tiles.err || { fail "two tiles did not render"; cat tiles.err; }
cmp -s alone/dem.png tiles/halves.png || fail "two tiles of the DEM did not make the still the whole DEM makes"
# A folder of tiles, as path or alone: the same still (side files of GDAL's and other files in it left out).
mkdir -p tiles/folder && cp tiles/west.tif tiles/east.tif tiles/folder/ && echo "LiDAR tiles" > tiles/folder/README.txt &&
  gdaladdo -q -ro tiles/folder/west.tif 2 || fail "could not make the folder of tiles"
printf '[samples]\npath = "folder"\n[overlay]\ntitle = "Maungawhau / Mt Eden"\n' > tiles/folder.toml
"$relief" render -q tiles/folder.toml -o tiles/folder.png 2>tiles.err || { fail "a folder of tiles did not render"; cat tiles.err; }
cmp -s alone/dem.png tiles/folder.png || fail "a folder of tiles did not make the still the whole DEM makes"
"$relief" render -q tiles/folder/ -o tiles/alone/folder.png 2>tiles.err && [ -s tiles/alone/folder.png ] ||
  { fail "relief render FOLDER did not render"; cat tiles.err; }
# A folder of more tiles than a process may hold files open (352 tiles of 2 x 2 cells, 256 files):
# the same still, the tiles opened one at a time.
mkdir -p tiles/many
for x in $(seq 0 2 30); do for y in $(seq 0 2 42); do
  gdal_translate -q "$dem" "tiles/many/t-$x-$y.tif" -srcwin "$x" "$y" "$(( x < 30 ? 2 : 1 ))" 2 || fail "could not cut tile $x $y"
done; done
printf '[samples]\npath = "many"\n[overlay]\ntitle = "Maungawhau / Mt Eden"\n' > tiles/many.toml
(ulimit -n 256 && "$relief" render -q tiles/many.toml -o tiles/many.png 2>many.err) ||
  { fail "352 tiles did not render with 256 files open at most"; cat many.err; }
cmp -s alone/dem.png tiles/many.png || fail "352 tiles of the DEM did not make the still the whole DEM makes"
printf '[samples]\npath = ["nw.tif", "sw.tif", "se.tif"]\nvertical_unit = "m"\n' > tiles/gap.toml
"$relief" compile -q tiles/gap.toml -o tiles/gap.pov 2>gap.err || fail "three tiles with a gap exited $?"
grep -qx 'tiles/gap.toml:2:8: warning: samples.path: the 3 tiles cover 75.8 % of their bounding box; the rest has no data (samples.nodata says what becomes of it): is a tile missing?' gap.err ||
  { fail "three tiles with a gap: no warning, or another:"; cat gap.err; }
printf '[samples]\npath = ["west.tif", "utm.tif"]\n' > tiles/crs.toml
"$relief" compile tiles/crs.toml -o tiles/crs.pov 2>crs.err
rc=$?
[ "$rc" = 2 ] && grep -qx 'tiles/crs.toml:2:8: error: samples.path: the tiles west.tif (NZGD2000 / New Zealand Transverse Mercator 2000) and utm.tif (WGS 84 / UTM zone 60S) are in different CRSs: reproject one into the other'"'"'s (gdalwarp -t_srs) so that all are in one' crs.err ||
  { fail "tiles in two CRSs: exit $rc, or another message:"; cat crs.err; }

[ "$status" = 0 ] && echo "first try: render, init (same bytes), info, CSV, neither, depth for the still, tiles, a folder of tiles"
exit $status
