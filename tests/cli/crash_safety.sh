#!/usr/bin/env bash
# A run's outputs (still, .pov, sidecar) appear together or not at all, and nothing else is
# touched:
#  1. killed (SIGKILL) mid-render: nothing under a final name; the next run in that folder
#     removes the private folders killed runs left (there and in /tmp), and never a user's file;
#  2. killed after POV-Ray, before the overlays and the sidecar: the previous run's set is
#     left exactly as it was;
#  3. no room for the .pov, and 4. an output folder that cannot be made: exit 2, nothing left;
#  5. two renders of different scenes onto one name at once: the still, .pov and sidecar left
#     are all from one of them, byte for byte what that scene renders alone;
#  6. a render over render.timeout_s is stopped (exit 3), nothing written;
#  7. the output folder made read-only mid-render: exit 2, "nothing written", the previous set
#     unchanged;
#  8. relief sweep with a bad second value: exit 2 before any still is rendered, nothing written.
# Usage: crash_safety.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
mkdir -p out
scene="$src/scenes/mountain-sharp.toml"   # a mesh2 of 258,048 triangles: ~2.5 s to render
whole_png() { oiiotool --info "$1" >/dev/null 2>&1; }
povray_of() { pgrep -f "relief-povray-.*-$1-" >/dev/null; }  # POV-Ray (or its sandbox) of relief process $1
same_set() {  # PREFIX COPY: the still, .pov and sidecar at PREFIX are byte for byte those at COPY
  local f
  for f in png pov json; do cmp -s "$1.$f" "$2.$f" || { echo "  $1.$f differs from $2.$f"; return 1; }; done
}

# 1. SIGKILL in the middle of the render, then a run that cleans up what killed runs left.
"$relief" render -q "$scene" -o out/still.png &
pid=$!
sleep 1.2
kill -9 "$pid"; wait "$pid" 2>/dev/null
for f in png pov json; do [ -e "out/still.$f" ] && fail "a still.$f under its final name after SIGKILL"; done
ls -A out | grep -q '^\.relief-out-' || fail "the killed run left no private folder (the test did not kill it mid-run)"
# A user's own files that look like temporaries of old, and a folder with relief's prefix but
# no owner file: none of them is relief's to remove.
echo mine > out/still.pov.tmp-999999; echo mine > out/notes.tmp-12.csv; mkdir out/.relief-notes
"$relief" render -q "$scene" -o out/still.png || fail "the render after a killed one"
whole_png out/still.png || fail "the PNG after a killed run is not whole"
[ -n "$(ls -A out | grep '^\.relief-out-')" ] && fail "private folders left: $(ls -A out | grep '^\.relief-')"
for f in still.pov.tmp-999999 notes.tmp-12.csv .relief-notes; do [ -e "out/$f" ] || fail "a user's $f was removed"; done
ls -d /tmp/.relief-povray-*-"$pid"-* >/dev/null 2>&1 && fail "a killed run's POV-Ray folder was left in /tmp"
mkdir -p ref && for f in png pov json; do cp "out/still.$f" "ref/still.$f"; done

# 2. SIGKILL after POV-Ray finished, while relief draws the overlays on a large still: the
#    previous run's still, .pov and sidecar stay as they were.
big=(--set render.width=1600 --set render.height=1200)
"$relief" render -q "$scene" "${big[@]}" -o out/big.png || fail "a large still"
mkdir -p ref-big && for f in png pov json; do cp "out/big.$f" "ref-big/big.$f"; done
"$relief" render -q "$scene" "${big[@]}" --set subdivision.omega=0.31 -o out/big.png &
pid=$!
for _ in $(seq 300); do povray_of "$pid" && break; sleep 0.05; done
while povray_of "$pid"; do sleep 0.005; done  # POV-Ray is done; relief is on the overlays
kill -9 "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
same_set out/big ref-big/big || fail "killed between POV-Ray and the overlays: the previous set changed"

# 3. No room to write the .pov (a 1 MB file-size limit; SIGXFSZ ignored, so write() fails with EFBIG).
(trap '' XFSZ; ulimit -f 1024; exec "$relief" compile -q "$scene" -o out/big/too-big.pov) 2> full.txt
code=$?
[ "$code" = 2 ] || fail "no room: exit $code, expected 2"
grep -q "^out/big/too-big.pov: error: cannot be written: File too large; .*(ulimit -f)" full.txt || { fail "no room:"; cat full.txt; }
[ -n "$(ls -A out/big 2>/dev/null)" ] && fail "no room: files left: $(ls -A out/big | tr '\n' ' ')"

# 4. An output folder that cannot be created (a file stands where the folder should be).
echo x > out/file
"$relief" compile -q "$scene" -o out/file/x.pov 2> folder.txt
code=$?
[ "$code" = 2 ] || fail "uncreatable folder: exit $code, expected 2"
grep -q "^out/file: error: cannot be made as the folder of x.pov: Not a directory$" folder.txt || { fail "folder:"; cat folder.txt; }

# 5. Two different scenes rendered onto one name at once, three times: whichever lands last,
#    its still, .pov and sidecar are one set, the same bytes as that scene alone.
"$relief" render -q "$scene" --set subdivision.omega=0.2 -o alone/a.png || fail "alone a"
"$relief" render -q "$scene" --set subdivision.omega=0.4 -o alone/b.png || fail "alone b"
for round in 1 2 3; do
  "$relief" render -q "$scene" --set subdivision.omega=0.2 -o out/race.png & a=$!
  "$relief" render -q "$scene" --set subdivision.omega=0.4 -o out/race.png & b=$!
  wait $a || fail "round $round: the first of two renders at once"
  wait $b || fail "round $round: the second of two renders at once"
  # The sidecar (whose timings differ run to run) says which scene it is; the still and the
  # .pov must be that scene's, byte for byte.
  winner=$(grep -q '"override subdivision.omega": "0.2"' out/race.json && echo a || echo b)
  for f in png pov; do
    cmp -s "out/race.$f" "alone/$winner.$f" || fail "round $round: race.$f is not from the run its sidecar names ($winner)"
  done
done

# 6. A render over its time limit is stopped: exit 3, the time named, no PNG.
"$relief" render -q "$scene" --set render.timeout_s=0.5 -o out/slow.png 2> slow.txt
code=$?
[ "$code" = 3 ] || fail "timeout: exit $code, expected 3"
grep -q "POV-Ray did not finish within render.timeout_s = 0.5 s and was stopped" slow.txt || { fail "timeout:"; cat slow.txt; }
for f in png pov json; do [ -e "out/slow.$f" ] && fail "timeout: slow.$f was written"; done

# 7. The output folder made read-only while POV-Ray renders: exit 2, the previous set untouched.
#    (As root, permissions bind nobody: the renders run as the user nobody.)
as_user=(); [ "$(id -u)" = 0 ] && as_user=(setpriv --reuid=nobody --regid=nogroup --clear-groups)
# nobody must reach relief and the scenes: a clone under /root (0700) is out of its reach.
if [ "${#as_user[@]}" -gt 0 ] && ! "${as_user[@]}" sh -c 'test -x "$1" && test -r "$2" && test -r "$3"' _ \
     "$relief" "$scene" "$src/tests/golden/small/scene.toml"; then
  echo "SKIP 7 (read-only mid-render): the user nobody cannot reach $relief and the scenes"
else
  mkdir -p ro keep && { [ "$(id -u)" = 0 ] && chown nobody ro; true; }
  "${as_user[@]}" "$relief" render -q --no-sandbox "$scene" -o ro/still.png || fail "read-only: the first render"
  cp ro/still.png ro/still.pov ro/still.json keep/
  "${as_user[@]}" "$relief" render -q --no-sandbox "$scene" --set subdivision.omega=0.31 -o ro/still.png 2> ro-err.txt &
  pid=$!
  for _ in $(seq 300); do povray_of "$pid" && break; sleep 0.05; done
  chmod a-w ro
  wait "$pid"; code=$?
  chmod u+w ro
  [ "$code" = 2 ] || { fail "read-only mid-render: exit $code, expected 2"; cat ro-err.txt; }
  grep -q "^ro/still.png: error: cannot be moved into place: Permission denied; write it in a folder you may write in$" ro-err.txt && grep -q "nothing written" ro-err.txt ||
    { fail "read-only: not 'cannot be moved into place ... nothing written':"; cat ro-err.txt; }
  same_set ro/still keep/still || fail "read-only mid-render: the previous set changed"
  # Writable again, the next run removes the private folder the refused one could not.
  "${as_user[@]}" "$relief" render -q --no-sandbox "$src/tests/golden/small/scene.toml" -o ro/small.png || fail "read-only: after"
  [ -z "$(ls -A ro | grep '^\.relief-')" ] || fail "read-only: private folders left: $(ls -A ro | tr '\n' ' ')"
fi

# 8. A sweep whose second value is bad renders nothing.
"$relief" sweep "$src/tests/golden/small/scene.toml" --vary subdivision.omega=1/64,abc -o sweep/sheet.png 2> sweep.txt
code=$?
[ "$code" = 2 ] || fail "sweep: exit $code, expected 2"
grep -q "nothing written" sweep.txt || { fail "sweep:"; cat sweep.txt; }
[ -e sweep ] && [ -n "$(ls -A sweep)" ] && fail "sweep: written: $(ls -A sweep sweep/* | tr '\n' ' ')"

[ "$status" = 0 ] && echo "killed, full, unwritable, concurrent, read-only and timed-out runs left whole sets or none"
exit $status
