#!/usr/bin/env bash
# net.gridding = "fit" from the command line: the surface rendered passes through the scattered
# samples (to a centimetre, when asked to stay that close) where linear gridding, refined by the
# same approximating scheme, misses them by decimetres; the header and sidecar say how it was fitted. The peak loss is the highest
# sample on the net when an extent leaves the highest of all off it. depth = "auto" is chosen on a
# linear gridding, not on the nearest-sample net a fit otherwise starts from. A raster is not
# gridded: a fit asked of one is a warning saying what to use.
# Usage: fit.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
enter_fresh_work
cp "$src/scenes/data/volcano_samples_1000_seed20251124.csv" s.csv
scene() {  # scene NAME GRIDDING [EXTRA NET KEYS]
  printf '[samples]\npath = "s.csv"\n[net]\ngridding = "%s"\n%s\n[render]\nwidth = 160\nheight = 120\n' "$2" "${3:-}" > "$1.toml"
}
# The RMSE (m) of a dumped surface (x,y,z on a regular grid) at the samples, bilinear between its nodes.
misfit() {
  python3 - "$1" s.csv "$2" <<'PY'
import csv, math, sys
rows = list(csv.reader(open(sys.argv[1])))[1:]
xs = sorted({float(r[0]) for r in rows}); ys = sorted({float(r[1]) for r in rows})
z = {(float(r[0]), float(r[1])): float(r[2]) for r in rows}
x0, dx, y0, dy = xs[0], xs[1] - xs[0], ys[0], ys[1] - ys[0]
pts = [tuple(map(float, l.split(','))) for l in open(sys.argv[3]).read().split()]
err = []
for x, y, h in pts:
    i = min(int((x - x0) / dx), len(xs) - 2); j = min(int((y - y0) / dy), len(ys) - 2)
    fx = (x - xs[i]) / (xs[i + 1] - xs[i]); fy = (y - ys[j]) / (ys[j + 1] - ys[j])
    s = ((1 - fx) * (1 - fy) * z[xs[i], ys[j]] + fx * (1 - fy) * z[xs[i + 1], ys[j]] +
         (1 - fx) * fy * z[xs[i], ys[j + 1]] + fx * fy * z[xs[i + 1], ys[j + 1]])
    err.append((s - h) ** 2)
print(f"{math.sqrt(sum(err) / len(err)):.4f}")
PY
}
json() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"; }

scene fit fit
scene close fit 'smoothing = 1e-6'
scene linear linear
for s in fit close linear; do
  "$relief" compile -q $s.toml -o $s.pov --dump-surface $s-surface.csv 2> $s.txt || { fail "compile $s"; cat $s.txt; }
done
# The samples in the frame's metres (UTM zone 60 south, as the header says).
grep -q '^// frame: UTM zone 60S' fit.pov || fail "the frame: $(grep '^// frame' fit.pov)"
tail -n +2 s.csv | tr ',' ' ' | gdaltransform -s_srs EPSG:4326 -t_srs EPSG:32760 -output_xy > xy.txt
tail -n +2 s.csv | cut -d, -f3 | paste -d' ' xy.txt - | tr ' ' ',' > samples-m.txt
# The samples are whole metres: cross-validation smooths their rounding (a quarter of a metre's
# spread) and stays closer than linear gridding, refined, does; a fit asked to stay close does.
fitted=$(misfit fit-surface.csv samples-m.txt) close=$(misfit close-surface.csv samples-m.txt)
linear=$(misfit linear-surface.csv samples-m.txt)
echo "RMSE at the samples: fit (GCV) $fitted m, fit (smoothing 1e-6) $close m, linear gridding $linear m"
python3 -c "import sys; sys.exit(0 if $close < 0.01 and 0.05 < $fitted < 0.3 and $linear > 0.3 else 1)" ||
  fail "RMSE at the samples: fit (GCV) $fitted m, fit (smoothing 1e-6) $close m, linear gridding $linear m"
grep -q '^// net.fit: 1000 samples fitted at depth 2: RMSE' fit.pov || fail "no net.fit line in the header"
[ "$(json fit.json "j['net']['fit']['samples'], j['net']['fit']['smoothing_chosen_by']")" = \
  "1000 generalized cross-validation" ] || fail "the sidecar's fit: $(json fit.json "j['net']['fit']")"
[ "$(json fit.json "j['peak_loss']['data_peak_m'][2]")" = 193.0 ] || fail "the peak is not the highest sample"

# An extent east of the summit: the peak is the highest sample on the net, the surface beside it.
scene east fit $'extent_lonlat = [174.7660, -36.8796, 174.7690, -36.8760]\nspacing_m = 10'
"$relief" compile -q east.toml -o east.pov 2> east.txt || { fail "compile east"; cat east.txt; }
[ "$(json east.json "j['peak_loss']['data_peak_m'][2], abs(j['peak_loss']['loss_m']) < 5")" = "168.0 True" ] ||
  fail "the peak loss east of the summit: $(json east.json "j['peak_loss']")"
grep -q '^// peak_loss_m: -\?[0-9.]* (the data.s highest point 168.00 m, the surface.s near it 1[67][0-9].[0-9][0-9] m)$' east.pov ||
  fail "the header's peak loss: $(grep peak_loss east.pov)"

# depth = "auto" measures the net's own curves, so a net to be fitted is gridded linearly before the
# fit: the depth is linear gridding's (2 here), not that of the nearest-sample staircase (4).
for g in fit linear nearest; do
  scene auto-$g $g $'[subdivision]\ndepth = "auto"\ntolerance_m = 0.5'
  "$relief" compile -q auto-$g.toml -o auto-$g.pov 2> auto-$g.txt || { fail "compile auto-$g"; cat auto-$g.txt; }
done
depths=$(for g in fit linear nearest; do grep -o '^// subdivision.depth: [0-9]*' auto-$g.pov | grep -o '[0-9]*$'; done | tr '\n' ' ')
[ "$depths" = "2 2 4 " ] || fail "depth = \"auto\" (fit, linear, nearest): $depths, expected 2 2 4"

# A raster's nodes are the net: a fit asked of one is not done, and the warning says so.
cp "$src/scenes/data/rasters/volcano2.tif" .
printf '[samples]\npath = "volcano2.tif"\n[net]\ngridding = "fit"\n[render]\nwidth = 160\nheight = 120\n' > raster.toml
"$relief" compile -q raster.toml -o raster.pov 2> raster.txt || { fail "compile raster"; cat raster.txt; }
grep -qF 'raster.toml:4:12: warning: net.gridding = "fit" is not used: the samples are a raster or a lattice' raster.txt ||
  { fail "no word that a raster is not fitted:"; cat raster.txt; }
# Samples in two strips across the volcano 670 m apart (two survey lines' worth of the shared
# set): cross-validation by blocks chooses, most of the net is farther than twice the samples'
# spacing from any of them, and that is a warning; net.unsupported = "mask" leaves those nodes out
# (as many as the sidecar's share says) and does not warn; "show" keeps them without the warning;
# "fade" keeps the surface as it is and washes its colour out between the strips, towards grey.
{ head -1 s.csv; awk -F, 'NR > 1 && (($2 > -36.8734 && $2 < -36.8726) || ($2 > -36.8794 && $2 < -36.8786))' s.csv; } > strip.csv
for mode in default mask show fade; do
  keys='' && [ $mode != default ] && keys="unsupported = \"$mode\""
  printf '[samples]\npath = "strip.csv"\n[net]\ngridding = "fit"\nrows = 9\ncols = 9\n%s\n[subdivision]\ndepth = 1\n' "$keys" > strip-$mode.toml
  "$relief" compile -q strip-$mode.toml -o strip-$mode.pov 2> strip-$mode.txt || { fail "compile strip-$mode"; cat strip-$mode.txt; }
done
echo "a strip of $(($(wc -l < strip.csv) - 1)) samples: $(json strip-default.json "j['net']['fit']['smoothing_chosen_by'], j['net']['fit']['unsupported_share']")"
json strip-default.json "j['net']['fit']['smoothing_chosen_by']" | grep -q '^cross-validation by blocks' ||
  fail "the strip's penalty: $(json strip-default.json "j['net']['fit']['smoothing_chosen_by']")"
grep -q 'warning: net.gridding = "fit": [0-9]* % of the net is farther than .* from any sample' strip-default.txt ||
  { fail "no warning of the nodes no sample reaches:"; cat strip-default.txt; }
for mode in mask show fade; do
  [ ! -s strip-$mode.txt ] || { fail "net.unsupported = $mode warned:"; cat strip-$mode.txt; }
done
[ "$(json strip-mask.json "j['net']['masked_nodata'] == round(j['net']['fit']['unsupported_share'] * 81) > 20, j['net']['fit']['unsupported']")" = "True mask" ] ||
  fail "masked: $(json strip-mask.json "j['net']['masked_nodata'], j['net']['fit']['unsupported_share']")"
[ "$(json strip-show.json "j['net']['masked_nodata'], j['net']['fit']['unsupported']")" = "0 show" ] ||
  fail "shown: $(json strip-show.json "j['net']['masked_nodata'], j['net']['fit']['unsupported']")"
[ "$(json strip-fade.json "j['net']['masked_nodata'], j['net']['fit']['unsupported']")" = "0 fade" ] ||
  fail "faded: $(json strip-fade.json "j['net']['masked_nodata'], j['net']['fit']['unsupported']")"
vertices() { sed -n '/vertex_vectors/,/}/p' "$1"; }
cmp -s <(vertices strip-show.pov) <(vertices strip-fade.pov) || fail "the faded surface's vertices are not the shown one's"
# Rendered, the pixels that differ are the band between the strips, and are less saturated than
# where it is shown (all but the silhouette's antialiased few: 57 of 4,238 are not).
needs_povray
for mode in show fade; do
  "$relief" render -q strip-$mode.toml -o strip-$mode.png --set render.width=160 --set render.height=120 2> render-$mode.txt ||
    { fail "render strip-$mode"; cat render-$mode.txt; }
  oiiotool --dumpdata strip-$mode.png > strip-$mode.txt
done
verdict=$(python3 - strip-show.txt strip-fade.txt <<'PY'
import re, sys
px = [[tuple(map(int, m)) for m in re.findall(r"Pixel \(\d+, \d+\): (\d+) (\d+) (\d+)", open(f).read())] for f in sys.argv[1:]]
saturation = lambda p: (max(p) - min(p)) / max(max(p), 1)
differ = [(a, b) for a, b in zip(*px) if a != b]
greyer = sum(saturation(b) < saturation(a) for a, b in differ)
print(f"{len(differ)} of {len(px[0])} pixels differ, {greyer} of them less saturated")
ok = 0.05 * len(px[0]) < len(differ) < 0.6 * len(px[0]) and greyer >= 0.97 * len(differ)
print("ok" if ok else "wrong")
PY
)
echo "faded: $verdict"
case "$verdict" in *ok) ;; *) fail "net.unsupported = \"fade\": $verdict" ;; esac
exit $status
