#!/usr/bin/env bash
# A full disk and an output folder that cannot be made: clear errors naming the disk full, exit 2,
# nothing half-written. The disk is a 1 MB tmpfs mounted in a private mount namespace (needs root or
# user namespaces; skipped where neither is allowed).
# Usage: disk_full.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$(realpath "$1") src=$2 work=$3
rm -rf "$work" && mkdir -p "$work/disk" || exit 1
unshare -m true 2>/dev/null || unshare -rm true 2>/dev/null || { echo "SKIP: no mount namespace"; exit 77; }
flag=-m; unshare -m true 2>/dev/null || flag=-rm
cat > "$work/inside.sh" <<'INSIDE'
set -u
relief=$1 src=$2 disk=$3
mount -t tmpfs -o size=1m tmpfs "$disk" || exit 77
status=0
check() {  # name, expected exit code, files that may stay (a regex; "" none), command...
  local name=$1 want=$2 may=$3; shift 3
  rm -rf "${disk:?}"/*
  "$@" > "$disk/../$name.out" 2> "$disk/../$name.err"
  local code=$?
  [ "$code" = "$want" ] || { echo "FAIL: $name: exit $code, expected $want"; cat "$disk/../$name.err"; status=1; }
  grep -q "the disk is full (No space left on device); make room on that disk or write elsewhere" "$disk/../$name.err" ||
    { echo "FAIL: $name: the error does not say the disk is full:"; cat "$disk/../$name.err"; status=1; }
  [ "$(wc -l < "$disk/../$name.err")" -le 2 ] || { echo "FAIL: $name: more than an error line and the count"; status=1; }
  leftovers=$(find "$disk" -type f | { if [ -n "$may" ]; then grep -Ev "$may"; else cat; fi })
  [ -z "$leftovers" ] || { echo "FAIL: $name: files left on the full disk:"; ls -la $leftovers; status=1; }
  echo "$name: exit $code: $(head -1 "$disk/../$name.err")"
}
# A 57 MB mesh2 .pov.
check mesh2 2 "" "$relief" compile -q "$src/scenes/mt-eden-lidar.toml" --set geometry.kind=mesh2 -o "$disk/out/eden.pov"
# The height field's PNGs (2.7 MB of drape).
check height-field 2 "" "$relief" compile -q "$src/scenes/default.toml" --set geometry.kind=height_field -o "$disk/out/default.pov"
# A still: the .pov fits (and stays, whole, as after any failed render), the PNG does not.
check still 2 '/still\.(pov|json)$' "$relief" render -q "$src/scenes/mt-eden-lidar.toml" --set render.width=1600 --set render.height=1200 \
  --set geometry.kind=adaptive --set geometry.tolerance_px=20 -o "$disk/out/still.png"
# A PDF that does not fit where its tile did (a 2 MB disk): the disk named full, where cairo's own
# writer said only "error while writing to output stream"; the render's plan kept for --resume.
mount -o remount,size=2m "$disk" || exit 77
rm -rf "${disk:?}"/*
"$relief" render -q "$src/scenes/mt-eden-lidar.toml" --set render.width=1600 --set render.height=1200 \
  --set geometry.kind=adaptive --set geometry.tolerance_px=20 -o "$disk/out/still.pdf" 2> "$disk/../pdf.err"
code=$?
echo "pdf: exit $code: $(head -1 "$disk/../pdf.err")"
[ "$code" = 2 ] || { echo "FAIL: pdf: exit $code, expected 2"; status=1; }
[ "$(head -1 "$disk/../pdf.err")" = "$disk/out/still.pdf: error: cannot be written: the disk is full (No space left on device); make room on that disk or write elsewhere" ] ||
  { echo "FAIL: pdf: the error does not say the disk is full:"; cat "$disk/../pdf.err"; status=1; }
[ -z "$(find "$disk" -type f | grep -v '/still\.plan/')" ] || { echo "FAIL: pdf: files left beside the plan"; status=1; }
exit $status
INSIDE
unshare $flag bash "$work/inside.sh" "$relief" "$src" "$work/disk"
status=$?
[ "$status" = 77 ] && { echo "SKIP: cannot mount a tmpfs"; exit 77; }
# An output folder that cannot be made: a file stands where a folder must go.
touch "$work/a-file"
"$relief" compile -q "$src/tests/golden/small/scene.toml" -o "$work/a-file/out/x.pov" 2> "$work/nofolder.err"
code=$?
echo "no folder: exit $code: $(head -1 "$work/nofolder.err")"
[ "$code" = 2 ] || { echo "FAIL: exit $code for an output folder that cannot be made"; status=1; }
grep -q "a-file/out" "$work/nofolder.err" || { echo "FAIL: the error does not name the folder"; status=1; }
[ "$status" = 0 ] && echo "a full disk and a missing folder: exit 2, one clear line, nothing left behind"
exit $status
