#!/usr/bin/env bash
# POV-Ray's scene language can read and write files (#fopen), and Debian's POV-Ray 3.7 does not
# enforce its own I/O restrictions: relief runs it in a bubblewrap sandbox. A template (as a
# scene from elsewhere could carry) that writes a file outside the render's private folder, or
# reads one, must fail with relief's exit code 3 and leave nothing behind; the same with
# --no-sandbox succeeds, which shows that the sandbox, not something else, stopped it.
# Usage: sandbox.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
# A long folder name: POV-Ray wraps its error at 80 columns, mid-word, and relief must join it.
outside="$work/outside/a-folder-whose-name-is-long-enough-that-povray-wraps-its-error-mid-word"
rm -rf "$work" && mkdir -p "$outside" "$work/write" "$work/read" && cd "$work" || exit 1
echo '"s3cret",' > "$work/secret.txt"
cp "$src/templates/scene.pov.in" write/ && cp "$src/templates/scene.pov.in" read/
printf '#fopen Out "%s/pwned.txt" write\n#write(Out, "written by the scene\\n")\n#fclose Out\n' "$outside" >> write/scene.pov.in
printf '#fopen In "%s/secret.txt" read\n#read(In, Secret)\n#fclose In\n#debug concat("read: ", Secret, "\\n")\n' "$work" >> read/scene.pov.in
scene="$src/tests/golden/small/scene.toml"
status=0
run() {  # expected-exit template-folder [relief options]
  local want=$1 tmpl=$2; shift 2
  "$relief" render -q "$scene" --templates "$tmpl" --set render.width=48 --set render.height=32 \
    -o "$work/out/$tmpl.png" "$@" 2> "$work/stderr.txt"
  local got=$?
  [ "$got" = "$want" ] || { echo "FAIL: $tmpl $*: exit $got, expected $want"; cat "$work/stderr.txt"; status=1; }
}
run 3 write
[ -e "$outside/pwned.txt" ] && { echo "FAIL: the sandboxed POV-Ray wrote outside its folder"; status=1; }
grep -q "Parse Error: Cannot open user file $outside/pwned.txt (write)" stderr.txt ||
  { echo "FAIL: POV-Ray's own error is not reported:"; cat stderr.txt; status=1; }
[ -e out/write.png ] && { echo "FAIL: a PNG was left behind"; status=1; }
run 3 read
grep -q "Parse Error: Cannot open user file $work/secret.txt (read)" stderr.txt ||
  { echo "FAIL: the read was not refused:"; cat stderr.txt; status=1; }
# The same templates without the sandbox: what the sandbox stopped happens.
run 0 write --no-sandbox
[ -e "$outside/pwned.txt" ] || { echo "FAIL: without the sandbox the write did not happen either"; status=1; }
run 0 read --no-sandbox  # the same #fopen ... read, which the sandbox refused, succeeds
# Without bwrap on PATH: a refusal that says how to install it, not a render outside the sandbox.
mkdir -p bin && ln -sf "$(command -v povray)" bin/povray
PATH="$work/bin" "$relief" render -q "$scene" -o "$work/out/nobwrap.png" 2> stderr.txt
got=$?
[ "$got" = 3 ] || { echo "FAIL: without bwrap: exit $got, expected 3"; status=1; }
grep -q "bwrap is not installed: apt-get install bubblewrap, or render without the sandbox (--no-sandbox)" stderr.txt ||
  { echo "FAIL: without bwrap:"; cat stderr.txt; status=1; }
[ -e out/nobwrap.png ] && { echo "FAIL: rendered without bwrap"; status=1; }
# A height field's scene reads its PNGs beside the .pov: the sandbox holds those files, not the
# folder they are in, so a template cannot read another file of the output folder.
mkdir -p beside && cp "$src/templates/scene.pov.in" beside/ && mkdir -p "$work/out"
echo '"out-s3cret",' > "$work/out/secret.txt"
printf '#fopen In "%s/out/secret.txt" read\n#read(In, Secret)\n#fclose In\n' "$work" >> beside/scene.pov.in
run 3 beside --set geometry.kind=height_field
grep -q "Parse Error: Cannot open user file $work/out/secret.txt (read)" stderr.txt ||
  { echo "FAIL: a file beside the outputs was readable:"; cat stderr.txt; status=1; }
# User paths never reach POV-Ray's option parser: a templates folder named like a switch and an
# output folder with spaces render as any other (no +UA alpha channel from the folder's name).
mkdir -p "tpl +UA" && cp "$src/templates/scene.pov.in" "tpl +UA/"
for sandbox in "" --no-sandbox; do
  rm -rf "$work/out dir"
  "$relief" render -q "$scene" --templates "tpl +UA" --set render.width=48 --set render.height=32 \
    -o "$work/out dir/a still.png" $sandbox 2> stderr.txt
  got=$?
  [ "$got" = 0 ] || { echo "FAIL: paths with spaces $sandbox: exit $got"; cat stderr.txt; status=1; }
  # The PNG's colour type (byte 25): 2 is RGB, 6 would be RGBA (+UA).
  [ "$(od -An -tu1 -j25 -N1 "$work/out dir/a still.png" 2>/dev/null | tr -d ' ')" = 2 ] ||
    { echo "FAIL: $sandbox the still is not RGB: a folder's name became POV-Ray's +UA"; status=1; }
  [ -f "$work/out dir/a still.pov" ] && [ -f "$work/out dir/a still.json" ] || { echo "FAIL: $sandbox set incomplete"; status=1; }
done
# POV-Ray never outlives relief, sandboxed or not: killed (SIGKILL) mid-render, no POV-Ray is left.
for sandbox in "" --no-sandbox; do
  "$relief" render -q "$src/scenes/mountain-sharp.toml" -o "$work/out/killed.png" $sandbox 2>/dev/null &
  pid=$!
  for _ in $(seq 100); do pgrep -f "relief-povray-.*-$pid-" >/dev/null && break; sleep 0.1; done
  pgrep -f "relief-povray-.*-$pid-" >/dev/null || { echo "FAIL: $sandbox POV-Ray never started"; status=1; }
  sleep 0.5
  kill -9 "$pid"; wait "$pid" 2>/dev/null
  for _ in $(seq 20); do pgrep -f "relief-povray-.*-$pid-" >/dev/null || break; sleep 0.1; done
  if pgrep -f "relief-povray-.*-$pid-" >/dev/null; then
    echo "FAIL: $sandbox POV-Ray still runs 2 s after relief was killed"; pkill -9 -f "relief-povray-.*-$pid-"; status=1
  fi
done
[ "$status" = 0 ] && echo "in the sandbox: the write outside and the read outside failed (exit 3); without it both ran"
exit $status
