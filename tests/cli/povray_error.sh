#!/usr/bin/env bash
# A scene that POV-Ray rejects (a template with an SDL error): `relief render`
# must print POV-Ray's own error text, exit with 3, and leave no PNG behind.
# Usage: povray_error.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
if ! command -v povray >/dev/null; then echo "SKIP: povray is not installed"; exit 77; fi
rm -rf "$work" && mkdir -p "$work/templates" || exit 1
sed 's/^#version 3.7;/#version 3.7;\nsphere { <0,0,0>, 1 pigment { colour Nonexistent } }/' \
  "$src/templates/scene.pov.in" > "$work/templates/scene.pov.in"
cd "$src/tests/golden/small" || exit 1
"$relief" render -q scene.toml --templates "$work/templates" -o "$work/out.png" 2> "$work/stderr.txt"
code=$?
cat "$work/stderr.txt"
status=0
[ "$code" = 3 ] || { echo "FAIL: exit code $code, expected 3"; status=1; }
grep -qE "line [0-9]+: Parse Error: No matching } in 'pigment', undeclared identifier 'Nonexistent' found instead" "$work/stderr.txt" ||
  { echo "FAIL: POV-Ray's error text is not shown"; status=1; }
ls "$work"/out.png* >/dev/null 2>&1 && { echo "FAIL: a PNG was left behind"; status=1; }
exit $status
