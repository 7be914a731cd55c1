#!/usr/bin/env bash
# A still rendered as tiles is the still rendered whole, byte for byte: every geometry kind,
# antialiasing on and off, overlays, contours, the block model, a transparent background; the
# render's steps run by hand (relief plan, render-tile, finish) give the same bytes; a render
# interrupted (Ctrl-C) writes nothing, keeps its plan, stops every POV-Ray, and --resume
# finishes it to the same bytes; a tile from another plan or another POV-Ray is refused by name;
# a tile that fails stops the render naming the tile and POV-Ray's message.
# Usage: tiles.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
size=(--set render.width=480 --set render.height=320)   # overlays from 480 px on

# 1. Tiles against the whole, scene by scene.
n=0
while IFS='|' read -r name scene sets; do
  [ -z "$name" ] && continue
  n=$((n + 1))
  eval "extra=($sets)"
  # One name in two folders: the .pov names its PNGs after itself.
  "$relief" render -q "$src/$scene" "${size[@]}" "${extra[@]}" -o "$name/whole/still.png" || { fail "$name: the whole still"; continue; }
  "$relief" render -q "$src/$scene" "${size[@]}" "${extra[@]}" --tiles 7 --jobs 2 -o "$name/tiles/still.png" ||
    { fail "$name: the tiled still"; continue; }
  for f in png pov; do cmp -s "$name/whole/still.$f" "$name/tiles/still.$f" || fail "$name: 7 tiles give another .$f than 1"; done
  [ -e "$name/tiles/still.plan" ] && fail "$name: the plan was left after a render that succeeded"
done <<'EOF'
mesh2|scenes/mountain-sharp.toml|
adaptive|scenes/castilla-y-leon.toml|--set geometry.kind=\"adaptive\"
height-field-block|scenes/default.toml|
no-antialias|scenes/mt-eden-map.toml|--set render.antialias=false
contours|scenes/mt-eden-lidar-5m.toml|--set overlay.contours={interval_m=10}
transparent|scenes/mountain-gentle.toml|--set render.background=\"transparent\"
EOF
[ "$n" = 6 ] || fail "only $n scenes were tried"

# 2. The steps by hand: plan, each tile, finish.
scene="$src/scenes/mountain-sharp.toml"
plan=$("$relief" plan -q "$scene" "${size[@]}" --tiles 3 -o steps/still.png) || fail "relief plan"
[ "$plan" = "$work/steps/still.plan" ] || fail "relief plan printed '$plan'"
for k in 0 1 2; do "$relief" render-tile "$plan" --tile "$k" || fail "render-tile $k"; done
"$relief" finish "$plan" 2> finish.txt || { fail "relief finish"; cat finish.txt; }
cmp -s steps/still.png mesh2/whole/still.png || fail "plan, render-tile, finish: another still than relief render"
[ -e "$plan" ] && fail "relief finish left the plan"

# 3. Interrupted, then resumed.
"$relief" render -q "$scene" "${size[@]}" --tiles 6 --jobs 2 -o resumed/still.png 2> interrupted.txt &
pid=$!
for _ in $(seq 100); do pgrep -f "relief-povray-.*-$pid-" >/dev/null && break; sleep 0.05; done
kill -INT "$pid"; wait "$pid"; code=$?
[ "$code" = 130 ] || fail "interrupted: exit $code, expected 130"
grep -q "^relief: interrupted; nothing written$" interrupted.txt || { fail "interrupted:"; cat interrupted.txt; }
grep -q "relief render --resume $work/resumed/still.plan renders what is missing" interrupted.txt || fail "no resume hint"
# SIGKILL reaches the POV-Rays in their sandboxes' namespaces at once; a loaded machine may take a
# moment to tear down processes of hundreds of MB.
for _ in $(seq 50); do pgrep -f "relief-povray-.*-$pid-" >/dev/null || break; sleep 0.1; done
pgrep -f "relief-povray-.*-$pid-" >/dev/null && fail "interrupted: POV-Ray still runs 5 s after relief ended"
[ -e resumed/still.png ] && fail "interrupted: a still was written"
"$relief" render -q --resume resumed/still.plan || fail "resume"
cmp -s resumed/still.png mesh2/whole/still.png || fail "resumed: another still than relief render"

# 4. A tile from another plan, or from another POV-Ray, is refused by name.
a=$("$relief" plan -q "$scene" "${size[@]}" --tiles 3 -o mix/a.png)
b=$("$relief" plan -q "$scene" "${size[@]}" --tiles 3 --set subdivision.omega=0.31 -o mix/b.png)
for k in 0 1 2; do "$relief" render-tile "$a" --tile "$k"; "$relief" render-tile "$b" --tile "$k"; done
cp "$b/tiles/tile-0001.png" "$b/tiles/tile-0001.json" "$a/tiles/"
"$relief" finish "$a" 2> mixed.txt; code=$?
[ "$code" = 2 ] || fail "a tile of another plan: exit $code, expected 2"
grep -q "plan.json: error: tile 2 of 3: it was rendered from another plan (sha256:" mixed.txt || { fail "another plan:"; cat mixed.txt; }
[ -e mix/a.png ] && fail "a tile of another plan: a still was written"
"$relief" render-tile "$a" --tile 1
sed -i 's/"povray_version": "[^"]*"/"povray_version": "9.9"/' "$a/tiles/tile-0002.json"
"$relief" finish "$a" 2> version.txt; code=$?
[ "$code" = 2 ] || fail "another POV-Ray: exit $code, expected 2"
grep -q "tile 3 of 3: it was rendered by POV-Ray 9.9 on .*, the plan made for " version.txt || { fail "version:"; cat version.txt; }
rm "$a/tiles/tile-0002.json"
"$relief" finish "$a" 2> missing.txt; code=$?
[ "$code" = 2 ] || fail "a missing tile: exit $code, expected 2"
grep -q "relief: error: 1 of the plan's 3 tiles are not rendered (the first: --tile 2)" missing.txt || { fail "missing:"; cat missing.txt; }

# 5. A tile that fails: the render stops, naming the tile and POV-Ray's words; nothing written.
mkdir -p bad && sed 's/^#version 3.7;/#version 3.7;\nsphere { <0,0,0>, 1 pigment { colour Nonexistent } }/' \
  "$src/templates/scene.pov.in" > bad/scene.pov.in
"$relief" render -q "$src/tests/golden/small/scene.toml" --templates bad --tiles 3 --jobs 1 -o failed/x.png 2> failed.txt
code=$?
[ "$code" = 3 ] || fail "a failing tile: exit $code, expected 3"
grep -q "^tile 1 of 3 (rows 1..40 of x.png): File 'scene.pov' line [0-9]*: Parse Error: No matching } in 'pigment'" failed.txt ||
  { fail "a failing tile:"; cat failed.txt; }
grep -q "relief render --resume $work/failed/x.plan" failed.txt || fail "a failing tile: no resume hint"
[ -e failed/x.png ] && fail "a failing tile: a still was written"

[ "$status" = 0 ] && echo "tiles stitched to the same bytes; steps, resume and refusals as they should"
exit $status
