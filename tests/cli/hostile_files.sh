#!/usr/bin/env bash
# Every file relief reads may be a FIFO that never ends, a device, a folder or far too large:
# each reader (scene, template, samples, palette, drape image, curve, manifest, images to compare,
# a test's references) refuses it at once, in one line naming the file and what it is, with exit
# code 2 (4 for relief diff) and nothing written; no reader blocks (each run has 20 s). An image to
# compare is held to the pixel limit from its header: a PNG bomb is refused before it is decoded.
# Usage: hostile_files.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
enter_fresh_work
cp "$src/tests/cli/bad/01-toml-syntax/samples.csv" samples.csv
mkfifo fifo
mkdir folder
truncate -s 5M big.toml           # 5 MB of NUL bytes, sparse: a scene of that size is not a scene
ln -s /dev/zero zero.png
mkdir templates && mkfifo templates/scene.pov.in

# expect NAME CODE EXPECTED_STDERR COMMAND...: the exact stderr, the exit code, no output, no hang.
expect() {
  local name=$1 want=$2 text=$3; shift 3
  rm -rf out
  timeout 20 "$@" > stdout.txt 2> stderr.txt
  local code=$?
  [ "$code" = 124 ] && { fail "$name: still running after 20 s"; return; }
  [ "$code" = "$want" ] || fail "$name: exit $code, expected $want"
  if [ "$(cat stderr.txt)" != "$text" ]; then
    fail "$name: stderr differs"; echo "--- expected"; echo "$text"; echo "--- actual"; cat stderr.txt
  fi
  [ -d out ] && [ -n "$(ls -A out)" ] && fail "$name: output written: $(ls -A out)"
}
scene() { printf '[samples]\npath = "%s"\n%s\n' "$1" "${2:-}" > "$3"; }
nothing="relief: 1 error, 0 warnings; nothing written"

expect scene-fifo 2 "fifo: error: cannot read the scene file: it is a FIFO (a named pipe), not a file
$nothing" "$relief" compile -q fifo -o out/x.pov
expect scene-device 2 "/dev/zero: error: cannot read the scene file: it is a device, not a file
$nothing" "$relief" compile -q /dev/zero -o out/x.pov
expect scene-folder 2 "folder: error: relief reads a scene file (TOML), a raster DEM GDAL opens (GeoTIFF, SRTM .hgt, ESRI ASCII grid, VRT, ...), a folder of such tiles or a CSV of lon,lat,elev samples, and this is none of them (the folder holds no raster GDAL reads)
$nothing" "$relief" compile -q folder -o out/x.pov
expect scene-too-big 2 "big.toml: error: cannot read the scene file: it is 5.24 MB, more than the 4 MB such a file may be
$nothing" "$relief" compile -q big.toml -o out/x.pov
scene samples.csv "" ok.toml
expect template-fifo 2 "templates/scene.pov.in: error: cannot read the scene template: it is a FIFO (a named pipe), not a file; give the folder with --templates or set RELIEF_TEMPLATES
$nothing" "$relief" compile -q ok.toml --templates templates -o out/x.pov
scene fifo "" samples-fifo.toml
expect samples-fifo 2 "samples-fifo.toml:2:8: error: samples.path = \"fifo\": it is a FIFO (a named pipe), not a file
$nothing" "$relief" compile -q samples-fifo.toml -o out/x.pov
scene folder "" samples-folder.toml
expect samples-folder 2 "samples-folder.toml:2:8: error: samples.path = \"folder\": the folder holds no raster GDAL reads; give a folder of raster tiles (GeoTIFF, SRTM .hgt, ...), a raster, or a CSV of samples
$nothing" "$relief" compile -q samples-folder.toml -o out/x.pov
scene samples.csv '[texture]
cpt = "fifo"' cpt-fifo.toml
expect palette-fifo 2 "cpt-fifo.toml:4:7: error: texture.cpt = \"fifo\": it is a FIFO (a named pipe), not a file
$nothing" "$relief" compile -q cpt-fifo.toml -o out/x.pov
scene samples.csv '[texture]
image = "zero.png"' image-device.toml
expect drape-device 2 "image-device.toml:4:9: error: texture.image = \"zero.png\": it is a device, not a file
$nothing" "$relief" compile -q image-device.toml -o out/x.pov
expect curve-fifo 2 "fifo: error: cannot read the curve file: it is a FIFO (a named pipe), not a file
$nothing" "$relief" hausdorff fifo "$src/tests/cli/curves/line.json"
expect manifest-fifo 2 "fifo: error: cannot read the manifest: it is a FIFO (a named pipe), not a file
$nothing" "$relief" test fifo --report out/report
expect diff-device 4 "relief: error: zero.png: it is a device, not a file" \
  "$relief" diff zero.png "$src/tests/data/images/a.png"
expect diff-fifo 4 "relief: error: fifo: it is a FIFO (a named pipe), not a file" \
  "$relief" diff fifo "$src/tests/data/images/a.png"
# A 177-byte PNG that says it is 12000 x 12000 pixels: refused from its header, under a 2 GB
# address-space limit that decoding it would break (not under AddressSanitizer, whose shadow
# memory alone is more than that).
limit=(bash -c 'ulimit -v 2000000; exec "$0" "$@"')
"${limit[@]}" "$relief" diff --help >/dev/null 2>&1 || limit=()
expect diff-huge-header 4 "relief: error: $src/tests/data/images/huge-header.png: it says it is 12000 x 12000 pixels, more than its 177 bytes can hold: the file is damaged" \
  "${limit[@]}" "$relief" diff "$src/tests/data/images/huge-header.png" "$src/tests/data/images/huge-header.png"
# A decompression bomb: a 12000 x 12000 PNG of zeros in about 140 kB, which its bytes can hold.
# Refused from its header by the pixel limit, before either image or the difference image is
# allocated (it passed the memory budget and died of SIGFPE after 20 s), under the same limit.
python3 - bomb.png <<'PY' || fail "the bomb"
import struct, sys, zlib
def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))
width = height = 12000
deflate = zlib.compressobj(9)
rows = b''.join(deflate.compress(bytes(width + 1)) for _ in range(height)) + deflate.flush()
header = struct.pack('>IIBBBBB', width, height, 8, 0, 0, 0, 0)  # 8-bit grey
open(sys.argv[1], 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', header) + chunk(b'IDAT', rows) + chunk(b'IEND', b''))
PY
expect diff-bomb 4 "relief: error: bomb.png: it says it is 12000 x 12000 pixels (144 Mpixels), more than the 40 Mpixels relief compares: compare smaller images, or crops of these" \
  "${limit[@]}" "$relief" diff bomb.png bomb.png --diff-image out/heat.png
# A truncated PNG: one line of relief's, none of libpng's.
expect diff-truncated 4 "relief: error: $src/tests/data/images/truncated.png: it is a damaged or truncated PNG (Read Error)" \
  "$relief" diff "$src/tests/data/images/truncated.png" "$src/tests/data/images/a.png"

# A scene's [render] output through a link out of the current folder: refused before any work.
rm -rf "$work.elsewhere" && mkdir -p "$work.elsewhere" && ln -s "$work.elsewhere" linkout
scene samples.csv '[render]
output = "linkout/x.png"' linked-output.toml
expect output-through-link 2 "linked-output.toml:4:10: error: render.output = \"linkout/x.png\" leads out of the current folder through a link; give -o to write there
$nothing" "$relief" render -q linked-output.toml
[ -n "$(ls -A "$work.elsewhere")" ] && fail "output-through-link: written through the link: $(ls -A "$work.elsewhere")"
rm -rf "$work.elsewhere"

# A test case whose reference "image" is a FIFO: that case fails with the reason, the run goes on.
if command -v povray >/dev/null; then
  mkdir -p refs && mkfifo refs/ref.png
  printf '[[case]]\nname = "fifo-ref"\nscene = "%s"\nreferences = "refs/"\n' "$src/tests/golden/small/scene.toml" > m.toml
  timeout 60 "$relief" test m.toml --report report > test.txt 2>&1
  code=$?
  [ "$code" = 1 ] || fail "reference-fifo: exit $code, expected 1"
  grep -q "refs/ref.png: it is a FIFO (a named pipe), not a file" test.txt || { fail "reference-fifo:"; cat test.txt; }
fi

[ "$status" = 0 ] && echo "every reader refused FIFOs, devices, folders and oversized files at once"
exit $status
