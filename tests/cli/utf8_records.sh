#!/usr/bin/env bash
# Names and metadata that are not UTF-8, and titles that would be TOML if pasted, through every
# command that writes a record. A DEM named in Latin-1 ("caf\xe9.tif", a valid Linux name) whose
# title and credit are Latin-1 metadata:
#  records: relief render of it (PNG, PDF, SVG), compile and info --json write UTF-8 records, with
#    U+FFFD for the name's byte and the title and credit read as Latin-1, and one warning; relief
#    init refuses the name (exit 2, one line, nothing written) and takes the title of a copy with a
#    UTF-8 name. A DEM whose title holds ''', """, line breaks, [render], width = 9999,
#    output = ... and control characters: relief init's scene and the scene relief render DEM
#    keeps read back with that title byte for byte, and no key changed (the still's default size
#    and name).
#  stills: relief render onto names in Latin-1 (the DEM's own out/caf\xe9.png, -o caf\xe9.pdf and
#    .svg, a scene's -o caf\xe9.png): the still under those bytes, its records as above.
# Usage: utf8_records.sh RELIEF SOURCE_DIR WORK_DIR records|stills
. "$(dirname "$0")/lib.sh" "$@"
part=$4
needs_povray
enter_fresh_work
command -v gdal_translate >/dev/null || { fail "gdal_translate (gdal-bin) is not installed"; exit 1; }
dem=$src/tests/data/rasters/maungawhau-20m.tif
small=(--set render.width=480 --set render.height=300)  # 480 px: the overlays (title, credits) are drawn
latin1=$(printf 'caf\xe9')
fffd=$(printf '\xef\xbf\xbd')

# Whether FILE is JSON in UTF-8 (python3 refuses a byte that is not).
utf8_json() { python3 -c 'import json,sys; json.load(open(sys.argv[1], encoding="utf-8"))' "$1" 2>/dev/null; }
# The value at a path of keys (a.b.c) in a UTF-8 JSON file, printed as UTF-8.
json_at() {
  python3 -c 'import json,sys
v = json.load(open(sys.argv[1], encoding="utf-8"))
for k in sys.argv[2].split("."): v = v[k]
sys.stdout.write(v if isinstance(v, str) else json.dumps(v))' "$1" "$2"
}
# overlay.title of a TOML file.
toml_title() { python3 -c 'import tomllib,sys; print(tomllib.load(open(sys.argv[1],"rb"))["overlay"]["title"])' "$1"; }
# The number of lines of FILE saying a name or text is not UTF-8.
warnings_in() { grep -c 'is not UTF-8: the sidecar, info --json' "$1"; }

gdal_translate -q -mo TIFFTAG_DOCUMENTNAME="$(printf 'Monta\xf1a del Fr\xedo')" \
  -mo TIFFTAG_COPYRIGHT="$(printf '\xa9 Instituto Geogr\xe1fico')" "$dem" "$latin1.tif" ||
  fail "gdal_translate could not make the Latin-1 DEM"
title='Montaña del Frío' credit='© Instituto Geográfico'

# relief render SCENE [-o STILL]: exit 0, the still at STILL, its sidecar UTF-8 with outputs.<ext> =
# SHOWN, inputs.samples = SAMPLES, the credit and the title, and one warning of a name.
check_render() {
  local scene=$1 still=$2 shown=$3 samples=$4 sidecar=${2%.*}.json ext=${2##*.}
  shift 4
  "$relief" render -q "$scene" "${small[@]}" "$@" 2>render.err
  local rc=$?
  [ "$rc" = 0 ] && [ -s "$still" ] || { fail "relief render $scene $* exited $rc, or wrote no $still"; cat render.err; return; }
  utf8_json "$sidecar" || { fail "$sidecar is not JSON in UTF-8"; return; }
  [ "$(json_at "$sidecar" "outputs.$ext")" = "$shown" ] || fail "$sidecar: outputs.$ext is $(json_at "$sidecar" "outputs.$ext")"
  [ "$(json_at "$sidecar" inputs.samples)" = "$samples" ] ||
    fail "$sidecar: inputs.samples is $(json_at "$sidecar" inputs.samples)"
  [ "$(json_at "$sidecar" inputs.attribution)" = "$credit" ] ||
    fail "$sidecar: the credit is $(json_at "$sidecar" inputs.attribution), not the Latin-1 metadata's"
  [ "$(warnings_in render.err)" = 1 ] || { fail "relief render $scene $*: not one warning of a name"; cat render.err; }
}
# A PDF's title and an SVG's text: the Latin-1 metadata's title and credit, in UTF-8.
check_documents() {
  [ "$(pdfinfo "$1" 2>/dev/null | sed -n 's/^Title: *//p')" = "$title" ] || fail "$1's title: $(pdfinfo "$1" 2>&1 | grep Title)"
  python3 -c 'import sys, xml.etree.ElementTree as E
texts = [t.text for t in E.parse(sys.argv[1]).iter() if t.tag.endswith("text")]
sys.exit(0 if sys.argv[2] in texts and sys.argv[3] in texts else 1)' "$2" "$title" "$credit" 2>/dev/null ||
    fail "$2 is not UTF-8 XML with the title and the credit as text"
}

if [ "$part" = stills ]; then
  check_render "$latin1.tif" "out/$latin1.png" "out/caf$fffd.png" "caf$fffd.tif"
  check_render "$latin1.tif" "out/$latin1.pdf" "out/caf$fffd.pdf" "caf$fffd.tif" -o "out/$latin1.pdf"
  check_render "$latin1.tif" "out/$latin1.svg" "out/caf$fffd.svg" "caf$fffd.tif" -o "out/$latin1.svg"
  check_documents "out/$latin1.pdf" "out/$latin1.svg"
  cp "$latin1.tif" montana.tif
  printf '[samples]\npath = "montana.tif"\n' > montana.toml
  check_render montana.toml "s/$latin1.png" "s/caf$fffd.png" montana.tif -o "s/$latin1.png"
  [ "$status" = 0 ] && echo "stills onto Latin-1 names (PNG, PDF, SVG, from a DEM and a scene): UTF-8 records"
  exit $status
fi

# relief render DEM: the name's byte as U+FFFD in the records, the title and credit read as Latin-1.
for ext in png pdf svg; do
  check_render "$latin1.tif" "out/dem.$ext" "out/dem.$ext" "caf$fffd.tif" -o "out/dem.$ext"
  json_at out/dem.json inputs.scene_made_for_the_data > made.toml
  [ "$(toml_title made.toml)" = "$title" ] || fail "the scene made for the data has another title: $(cat made.toml)"
done
check_documents out/dem.pdf out/dem.svg

# relief compile DEM: the .pov under the name as given, the sidecar UTF-8, the header one UTF-8 line a key.
"$relief" compile -q "$latin1.tif" -o "c/$latin1.pov" 2>compile.err || { fail "relief compile exited $?"; cat compile.err; }
utf8_json "c/$latin1.json" || fail "the compile's sidecar is not JSON in UTF-8"
python3 -c 'import sys; open(sys.argv[1], encoding="utf-8").read()' "c/$latin1.pov" 2>/dev/null ||
  fail "the .pov is not UTF-8"
grep -q "^// samples.path: caf$fffd.tif\$" "c/$latin1.pov" || fail "the .pov header: $(grep -a '^// samples.path' "c/$latin1.pov")"
[ "$(warnings_in compile.err)" = 1 ] || { fail "relief compile: not one warning of the name"; cat compile.err; }

# relief info --json: UTF-8 JSON on stdout.
"$relief" info --json "$latin1.tif" > info.json 2>info.err || fail "relief info --json exited $?"
utf8_json info.json || fail "relief info --json printed no JSON in UTF-8"
[ "$(json_at info.json data.path)" = "caf$fffd.tif" ] && [ "$(json_at info.json data.attribution)" = "$credit" ] ||
  fail "relief info --json: $(head -c 400 info.json)"
[ "$(warnings_in info.err)" = 1 ] || { fail "relief info --json: not one warning of the name"; cat info.err; }

# relief init: the name cannot be TOML: one line saying to rename it, exit 2, nothing written.
"$relief" init "$latin1.tif" -o i/scene.toml 2>init.err
rc=$?
[ "$rc" = 2 ] && [ "$(head -1 init.err)" = 'caf\xe9.tif: error: the scene would say samples.path = "../caf\xe9.tif", which is not UTF-8, and TOML holds only UTF-8: rename the file (or its folder) to a UTF-8 name and run relief init again (relief render reads the file as it is named)' ] &&
  [ "$(wc -l < init.err)" = 2 ] || { fail "relief init of a Latin-1 name: exit $rc"; cat init.err; }
[ ! -e i ] || fail "relief init of a Latin-1 name left $(find i)"
# A copy under a UTF-8 name: the Latin-1 title read as Latin-1, in the scene.
cp "$latin1.tif" montana.tif
"$relief" init -q montana.tif -o i/montana.toml 2>/dev/null || fail "relief init montana.tif exited $?"
[ "$(toml_title i/montana.toml)" = "$title" ] || fail "relief init's title: $(grep '^title' i/montana.toml)"

# A title that pasted into TOML would close its string and set keys: data, whatever it holds.
# Without control characters (toml++ wrote such a title as '''...''', which its ''' closed), and with.
injected=$(printf "Mt \"Eden\" \"\"\" 'x'''\n[render]\nwidth = 9999\noutput = '''pwned.png")
controls=$(printf "ctl \x01\x1b[31m red\x7f tab\there \\\\ back\r\nend '''")
for name in injected controls; do
  want=${!name}
  gdal_translate -q -mo TIFFTAG_DOCUMENTNAME="$want" "$dem" "$name.tif" || fail "gdal_translate: $name.tif"
  "$relief" init -q "$name.tif" -o "$name.toml" 2>/dev/null || fail "relief init $name.tif exited $?"
  python3 -c 'import tomllib,sys
s = tomllib.load(open(sys.argv[1], "rb"))
sys.exit(0 if s["overlay"]["title"] == sys.argv[2] and s["render"] == {"width": 800, "height": 600} else 1)' \
    "$name.toml" "$want" || { fail "relief init's scene of $name.tif reads back otherwise:"; cat "$name.toml"; }
done
# relief render DEM at the scene's own size: the still where its name says, 800 x 600, the title kept.
"$relief" render -q injected.tif 2>injected.err || { fail "relief render injected.tif exited $?"; cat injected.err; }
[ -s out/injected.png ] && [ ! -e pwned.png ] && [ ! -e out/pwned.png ] || fail "the still is not out/injected.png"
[ "$(json_at out/injected.json parameters.render)" = "800 x 600, antialias on" ] ||
  fail "the still is $(json_at out/injected.json parameters.render)"
json_at out/injected.json inputs.scene_made_for_the_data > injected-made.toml
python3 -c 'import tomllib,sys
s = tomllib.load(open(sys.argv[1], "rb"))
sys.exit(0 if s["overlay"]["title"] == sys.argv[2] and "render" not in s else 1)' injected-made.toml "$injected" ||
  { fail "the scene relief made for injected.tif reads back otherwise:"; cat injected-made.toml; }

[ "$status" = 0 ] && echo "records UTF-8 (render PNG, PDF, SVG, compile, info --json, init); titles stay titles"
exit $status
