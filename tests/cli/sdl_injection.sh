#!/usr/bin/env bash
# A scene whose samples path holds a line break and POV-Ray directives (the
# file exists under that name): the directives must stay inside the .pov
# header's comment, so POV-Ray writes no file, and the render succeeds.
# Usage: sdl_injection.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
name=$'x\n#fopen F "pwned.txt" write #write(F, "x") #fclose F\n.csv'
cp "$src/tests/golden/small/samples.csv" "$name"
printf '[samples]\npath = "%s"\n[subdivision]\ndepth = 1\n[render]\nwidth = 64\nheight = 48\n' \
  'x\n#fopen F \"pwned.txt\" write #write(F, \"x\") #fclose F\n.csv' > scene.toml
"$relief" render -q scene.toml -o out/still.png
code=$?
status=0
[ "$code" = 0 ] || { echo "FAIL: exit code $code"; status=1; }
[ -e pwned.txt ] || [ -e out/pwned.txt ] && { echo "FAIL: POV-Ray ran a directive from the path"; status=1; }
grep -q '^// samples.path: x\\x0a#fopen F "pwned.txt" write' out/still.pov ||
  { echo "FAIL: the path is not one escaped comment line:"; grep -n 'samples.path' out/still.pov; status=1; }
grep -n '^#fopen' out/still.pov && { echo "FAIL: a directive outside the comments"; status=1; }
[ "$status" = 0 ] && echo "the directives stayed in the comment; no file written"
exit $status
