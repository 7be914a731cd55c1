#!/usr/bin/env bash
# A flat terrain (every cell 100 m) still renders, as a mesh2 and as a height field, with no 0/0
# anywhere: refining it leaves rounding noise (~1e-13 m) that a colour ramp or 16-bit levels
# spread over their range would show as speckles, so the two stills must match each other and
# the terrain must be one colour.
# Usage: flat_terrain.sh RELIEF WORK_DIR
set -u
relief=$1 work=$2
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
printf 'ncols 20\nnrows 20\nxllcenter 1757000\nyllcenter 5917000\ncellsize 10\nNODATA_value -9999\n' > flat.asc
for r in $(seq 20); do printf '100 %.0s' $(seq 20); echo; done >> flat.asc
printf '[samples]\npath = "flat.asc"\ncrs = "EPSG:2193"\nvertical_unit = "m"\n[render]\nwidth = 200\nheight = 150\n' > flat.toml
status=0
for kind in mesh2 height_field; do
  "$relief" render -q flat.toml --set geometry.kind=$kind -o "$kind.png" || { echo "FAIL: $kind did not render"; status=1; }
done
# A few pixels on the plane's outline may differ (the two kinds' edges anti-alias apart);
# speckles would be hundreds.
"$relief" diff mesh2.png height_field.png --fail 0.004 --failpercent 0.05 > diff.txt
[ $? -le 1 ] || { echo "FAIL: the flat mesh2 and height field differ:"; cat diff.txt; status=1; }
# The terrain's pixels (the centre of the still) are one colour but for the light's falloff
# (0.016 here; the speckles spanned 0.22).
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool (openimageio-tools) is not installed"; exit 1; }
oiiotool mesh2.png --cut 60x40+70+60 --printstats 2>&1 | grep -E "Stats (Min|Max)" > stats.txt
if [ "$(wc -l < stats.txt)" != 2 ]; then
  echo "FAIL: oiiotool gave no statistics of the terrain's pixels"; status=1
else
  read -r _ _ r0 g0 b0 < <(sed -n 1p stats.txt); read -r _ _ r1 g1 b1 < <(sed -n 2p stats.txt)
  awk -v a="$r0 $g0 $b0" -v b="$r1 $g1 $b1" 'BEGIN { split(a, x, " "); split(b, y, " ");
      for (i = 1; i <= 3; i++) if (!(y[i] - x[i] <= 0.05)) exit 1 }' ||
    { echo "FAIL: the flat terrain is not one colour:"; cat stats.txt; status=1; }
fi
[ "$status" = 0 ] && echo "flat terrain: both kinds render, identical, one colour"
exit $status
