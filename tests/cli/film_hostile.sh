#!/usr/bin/env bash
# A film's working folder is trusted for nothing (docs/security.md), and names are never patterns:
#  1. a film whose names hold % (ffmpeg's image-sequence patterns) is made, and its bytes are the
#     same film's under other names and folders: ffmpeg sees fixed names in the working folder
#  2. a kept working folder resumed: a link planted as its frames/, as a frame's tiles/ or as a
#     frame's plan is an error naming it, and nothing is written through it
#  3. film.json names no folder outside its own: a film whose first run kept its frames is resumed
#     with --frames again (and refused without it); a film.json naming a film elsewhere is refused
# Usage: film_hostile.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
command -v ffmpeg >/dev/null || { echo "SKIP: ffmpeg is not installed"; exit 77; }
enter_fresh_work
cat > film.toml <<TOML
[samples]
path = "$src/tests/data/rasters/maungawhau-20m.tif"
vertical_unit = "m"
[render]
width = 160
height = 100
[animation]
frames = 3
path = "orbit"
TOML
mkdir -p outside

# 1. Names with %, and the same bytes under any names.
"$relief" animate -q film.toml -o "plain/a.mp4" 2> plain.txt || { fail "the plain film"; cat plain.txt; }
"$relief" animate -q film.toml -o "per%d cent %s/a much longer name%05d.mp4" --frames "per%d cent %s/fr%x" 2> pct.txt ||
  { fail "a film in a folder named with %"; cat pct.txt; }
cmp -s plain/a.mp4 "per%d cent %s/a much longer name%05d.mp4" || fail "the film's bytes depend on its names"
[ "$(ls "per%d cent %s/fr%x" | wc -l)" = 3 ] || fail "--frames in a folder named with %: $(ls "per%d cent %s/fr%x")"

# keep NAME: a film whose POV-Ray fails (a povray on PATH that always fails) keeps its working folder.
mkdir -p failing
printf '#!/bin/sh\n[ "$1" = --version ] && exec %s "$@"\necho "povray: this one always fails" >&2\nexit 1\n' \
  "$(command -v povray)" > failing/povray && chmod +x failing/povray
keep() {
  PATH="$work/failing:$PATH" "$relief" animate -q film.toml -o "$1/f.mp4" --no-sandbox "${@:2}" 2> /dev/null
  [ -d "$1/f.film" ] || fail "$1: the failing film kept no working folder"
}
refused() {  # refused NAME PATTERN command...: exit 2, saying PATTERN
  local name=$1 pattern=$2; shift 2
  "$@" > "$name.out" 2> "$name.txt"; local code=$?
  [ "$code" = 2 ] || { fail "$name: exit $code, expected 2"; cat "$name.txt"; return; }
  grep -qE -- "$pattern" "$name.txt" || { fail "$name: not '$pattern':"; cat "$name.txt"; }
}

# 2. Planted links.
keep frames-link
mkdir -p outside/frames && ln -s "$work/outside/frames" frames-link/f.film/frames
refused frames-link "frames-link/f.film/frames: error: is a link, and relief writes through none in its working folders" \
  "$relief" animate -q --resume frames-link/f.film
[ -z "$(ls -A outside/frames)" ] || fail "frames were written through a planted link"
[ -e frames-link/f.mp4 ] && fail "a planted frames/: the film was written"
keep tiles-link
rm -rf tiles-link/f.film/frame-00002.plan/tiles
mkdir -p outside/tiles && ln -s "$work/outside/tiles" tiles-link/f.film/frame-00002.plan/tiles
refused tiles-link "frame-00002.plan/tiles: is a link, and relief writes through none in its working folders" \
  "$relief" animate -q --resume tiles-link/f.film
[ -z "$(ls -A outside/tiles)" ] || fail "tiles were written through a planted link"
keep plan-link
mv plan-link/f.film/frame-00003.plan outside/frame-00003.plan && ln -s "$work/outside/frame-00003.plan" plan-link/f.film/frame-00003.plan
refused plan-link "frame-00003.plan: error: is a link, and relief writes through none in its working folders" \
  "$relief" animate -q --resume plan-link/f.film
[ -e outside/frame-00003.plan/tiles ] && fail "a frame's plan reached through a link was rendered"

# 3. film.json: the frames kept are asked for again; a film named elsewhere is refused.
keep frames-kept --frames frames-kept/frames
grep -q '"frames_dir"' frames-kept/f.film/film.json && fail "film.json names a frames folder"
refused frames-kept "frames-kept/f.film/film.json: error: the film's first run kept its frames \(--frames\), and its record names no folder outside its own: give --frames DIR again to say where they go" \
  "$relief" animate -q --resume frames-kept/f.film
"$relief" animate -q --resume frames-kept/f.film --frames frames-kept/again 2> again.txt || { fail "--resume --frames"; cat again.txt; }
[ "$(ls frames-kept/again | wc -l)" = 3 ] || fail "--resume --frames: $(ls frames-kept/again)"
cmp -s frames-kept/f.mp4 plain/a.mp4 || fail "the resumed film is not the film made in one run"
keep elsewhere
sed -i 's/"film": "f.mp4"/"film": "..\/..\/outside\/f.mp4"/' elsewhere/f.film/film.json
refused elsewhere "film.json: error: the film's record names a film that is not this folder's" \
  "$relief" animate -q --resume elsewhere/f.film
[ -e outside/f.mp4 ] && fail "a film.json naming a film elsewhere was written there"

[ "$status" = 0 ] && echo "films' names are no patterns, their working folders followed nowhere, their records name nothing outside"
exit $status
