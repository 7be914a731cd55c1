#!/usr/bin/env bash
# [render] background: "transparent" gives an RGBA PNG whose sky is alpha 0 and whose terrain is
# opaque; a colour "#rrggbb" fills the sky with exactly that colour (sRGB in, sRGB out).
# Pixels read with oiiotool (openimageio-tools).
# Usage: background.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
command -v oiiotool >/dev/null || { echo "SKIP: oiiotool is not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
status=0
scene="$src/tests/golden/small/scene.toml"
size=(--set render.width=160 --set render.height=120)
"$relief" render -q "$scene" "${size[@]}" --set render.background=transparent -o "$work/t.png" || status=1
"$relief" render -q "$scene" "${size[@]}" --set 'render.background=#ff8000' -o "$work/c.png" || status=1
pixel() { oiiotool --dumpdata "$1" 2>/dev/null | sed -n "s/^ *Pixel ($2): \([0-9 ]*\) (.*/\1/p"; }
[ "$(pixel "$work/t.png" "0, 0")" = "0 0 0 0" ] || { echo "FAIL: the transparent sky is '$(pixel "$work/t.png" "0, 0")'"; status=1; }
opaque=$(oiiotool --dumpdata "$work/t.png" 2>/dev/null | grep -c ' 255 (')
[ "$opaque" -gt 2000 ] || { echo "FAIL: only $opaque opaque pixels: no terrain?"; status=1; }
[ "$(pixel "$work/c.png" "0, 0")" = "255 128 0" ] || { echo "FAIL: the sky is '$(pixel "$work/c.png" "0, 0")', not 255 128 0"; status=1; }
grep -q '^// render.background: transparent' "$work/t.pov" || { echo "FAIL: the .pov header does not say"; status=1; }
[ "$status" = 0 ] && echo "transparent: sky alpha 0, $opaque opaque terrain pixels; #ff8000: sky 255 128 0"
exit $status
