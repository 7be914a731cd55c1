#!/usr/bin/env bash
# Outputs are whole or absent: a render killed with SIGKILL leaves no file under a final name that
# is not complete, and the next run in that folder removes what it left (temporary files, POV-Ray's
# private folder); a write that fails for lack of room (a file-size limit standing in for a full
# disk) and an output folder that cannot be created are errors (exit 2) that leave nothing; two
# renders into one folder at once both finish whole; a render over render.timeout_s is stopped.
# Usage: crash_safety.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work/out" && cd "$work" || exit 1
scene="$src/scenes/mountain-sharp.toml"   # a mesh2 of 258,048 triangles: ~2.5 s to render
status=0
fail() { echo "FAIL: $*"; status=1; }
whole_png() { oiiotool --info "$1" >/dev/null 2>&1; }

# 1. SIGKILL in the middle of the render, then what a killed run left, then a run that cleans up.
"$relief" render -q "$scene" -o out/still.png &
pid=$!
sleep 1.2
kill -9 "$pid"; wait "$pid" 2>/dev/null
[ -e out/still.png ] && fail "a PNG under its final name after SIGKILL"
if [ -e out/still.pov ]; then tail -n 1 out/still.pov | grep -qx '// End of the scene.' || fail "an incomplete .pov under its final name"; fi
touch out/still.pov.tmp-999999 out/still.height.tmp-999999.png   # as a run killed while writing leaves them
mkdir -p /tmp/relief-povray-999999-XXXXXX
"$relief" render -q "$scene" -o out/still.png || fail "the render after a killed one"
whole_png out/still.png || fail "the PNG after a killed run is not whole"
ls out | grep -q '\.tmp-' && fail "temporary files left: $(ls out | grep '\.tmp-' | tr '\n' ' ')"
[ -d /tmp/relief-povray-999999-XXXXXX ] && fail "a killed run's POV-Ray folder was left in /tmp"

# 2. No room to write the .pov (a 1 MB file-size limit; SIGXFSZ ignored, so write() fails with EFBIG).
(trap '' XFSZ; ulimit -f 1024; exec "$relief" compile -q "$scene" -o out/big/too-big.pov) 2> full.txt
code=$?
[ "$code" = 2 ] || fail "no room: exit $code, expected 2"
grep -q "^relief: error: cannot write out/big/too-big.pov: File too large$" full.txt || { fail "no room:"; cat full.txt; }
[ -n "$(ls out/big 2>/dev/null)" ] && fail "no room: files left: $(ls out/big | tr '\n' ' ')"

# 3. An output folder that cannot be created (a file stands where the folder should be).
echo x > out/file
"$relief" compile -q "$scene" -o out/file/x.pov 2> folder.txt
code=$?
[ "$code" = 2 ] || fail "uncreatable folder: exit $code, expected 2"
grep -q "^relief: error: cannot create the folder out/file for x.pov: Not a directory$" folder.txt || { fail "folder:"; cat folder.txt; }

# 4. Two renders into one folder at once: both succeed, and the still is whole and the same as alone.
"$relief" render -q "$scene" -o out/twice.png & a=$!
"$relief" render -q "$scene" -o out/twice.png & b=$!
wait $a || fail "the first of two renders at once"
wait $b || fail "the second of two renders at once"
cmp -s out/twice.png out/still.png || fail "two renders at once did not leave the still a lone render gives"

# 5. A render over its time limit is stopped: exit 3, the time named, no PNG.
"$relief" render -q "$scene" --set render.timeout_s=0.5 -o out/slow.png 2> slow.txt
code=$?
[ "$code" = 3 ] || fail "timeout: exit $code, expected 3"
grep -q "POV-Ray did not finish within render.timeout_s = 0.5 s and was stopped" slow.txt || { fail "timeout:"; cat slow.txt; }
[ -e out/slow.png ] && fail "timeout: a PNG was written"

[ "$status" = 0 ] && echo "killed, full, unwritable, concurrent and timed-out runs all left whole outputs or none"
exit $status
