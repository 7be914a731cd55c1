#!/usr/bin/env bash
# Through the private Slurm cluster (cluster.sh; SLURM_CONF names it): a still as 7 tiles, a
# sweep, a test suite and a film give the bytes they give on this machine alone; a task that fails names
# its Slurm job, state and log; a task that cannot see its plan says so; without SLURM_CONF relief
# says what is missing; Ctrl-C cancels the job array.
# Usage: slurm_render.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }
[ -n "${SLURM_CONF:-}" ] && sinfo -h >/dev/null 2>&1 || { echo "SKIP: no Slurm cluster (SLURM_CONF=${SLURM_CONF:-})"; exit 77; }
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
status=0
fail() { echo "FAIL: $*"; status=1; }
small="$src/tests/golden/small/scene.toml"
size=(--set render.width=480 --set render.height=320)

# 1. A still: 7 tiles on Slurm, 1 here.
"$relief" render -q "$src/scenes/default.toml" "${size[@]}" -o local/still.png || fail "the local still"
"$relief" render -q "$src/scenes/default.toml" "${size[@]}" --tiles 7 --executor slurm -o slurm/still.png 2> still.txt ||
  { fail "the still on Slurm"; cat still.txt; }
for f in png pov; do cmp -s local/still.$f slurm/still.$f || fail "Slurm's still.$f is not the local one"; done
grep -q '"host":' slurm/still.json && [ "$(grep -c '"plan_hash":' slurm/still.json)" = 7 ] || fail "the sidecar lacks the 7 tiles' records"

# 2. A sweep: a task a still.
vary=(--vary subdivision.omega=1/64,1/16 --set render.width=64 --set render.height=48)
"$relief" sweep -q "$small" "${vary[@]}" -o local-sweep/sheet.png || fail "the local sweep"
"$relief" sweep -q "$small" "${vary[@]}" --executor slurm -o slurm-sweep/sheet.png 2> sweep.txt || { fail "the Slurm sweep"; cat sweep.txt; }
for f in sheet.png sheet-stills/001.png sheet-stills/002.png; do
  cmp -s "local-sweep/$f" "slurm-sweep/$f" || fail "the sweep's $f differs on Slurm"
done

# 3. A test suite: a task a case; the same verdicts and the same new images.
mkdir -p suite
cat > suite/manifest.toml <<EOF
[[case]]
name = "small"
scene = "$src/tests/golden/small/scene.toml"
references = "$src/tests/golden/small/ref/"
[[case]]
name = "gentle"
scene = "$src/scenes/mountain-gentle.toml"
references = "$src/tests/golden/gentle/ref/"
[[case]]
name = "eden"
scene = "$src/scenes/mt-eden-lidar.toml"
references = "$src/tests/golden/mt-eden-lidar/ref/"
EOF
"$relief" test suite/manifest.toml --jobs 2 --report local-report > local-test.txt 2>&1 || fail "the local suite"
"$relief" test suite/manifest.toml --jobs 2 --executor slurm --report slurm-report > slurm-test.txt 2>&1 ||
  { fail "the suite on Slurm"; cat slurm-test.txt; }
for c in small gentle eden; do
  cmp -s "local-report/images/$c.new.png" "slurm-report/images/$c.new.png" || fail "case $c renders otherwise on Slurm"
done
[ "$(grep -o '"status": "[A-Z]*"' local-report/summary.json)" = "$(grep -o '"status": "[A-Z]*"' slurm-report/summary.json)" ] ||
  fail "the verdicts differ on Slurm"

# 3b. A film: a task a frame on Slurm, the same MP4 as here.
if command -v ffmpeg >/dev/null; then
  film=(--set animation.frames=3 --set 'animation.path="orbit"' --set render.width=160 --set render.height=120)
  "$relief" animate -q "$small" "${film[@]}" -o local-film/film.mp4 || fail "the local film"
  "$relief" animate -q "$small" "${film[@]}" --executor slurm -o slurm-film/film.mp4 2> film.txt ||
    { fail "the film on Slurm"; cat film.txt; }
  cmp -s local-film/film.mp4 slurm-film/film.mp4 || fail "the film differs on Slurm"
fi

# 4. A task that fails: named by job, state and log; nothing written; the plan kept.
mkdir -p bad && sed 's/^#version 3.7;/#version 3.7;\nsphere { <0,0,0>, 1 pigment { colour Nonexistent } }/' \
  "$src/templates/scene.pov.in" > bad/scene.pov.in
"$relief" render -q "$small" --templates bad --tiles 3 --executor slurm -o failed/x.png 2> failed.txt
code=$?
[ "$code" = 3 ] || fail "a failing task: exit $code, expected 3"
# Every task fails; the first seen to end is named and the rest of the array is cancelled.
grep -Eq "^task ([0-2]) \(Slurm job [0-9]+_\1, tile [1-3] of 3\) FAILED: tile [1-3] of 3: File 'scene.pov' line [0-9]+: Parse Error: No matching } in 'pigment'.*; its log: $work/failed/x.plan/slurm/logs/task-\1.log$" failed.txt ||
  { fail "a failing task:"; cat failed.txt; }
[ -e failed/x.png ] && fail "a failing task: a still was written"
log=$(sed -n 's/.*; its log: \(.*\)$/\1/p' failed.txt | head -1)
[ -s "$log" ] || fail "a failing task: no log at '$log'"

# 5. A task whose plan this machine does not see.
printf '0\t%s\n' "$work/nowhere/x.plan" > tasks.txt
"$relief" render-tile --tasks tasks.txt --index 0 2> nowhere.txt; code=$?
[ "$code" = 3 ] || fail "a plan not seen: exit $code, expected 3"
grep -q "^relief: error: $work/nowhere/x.plan/plan.json: no render plan here: the plan's folder must be on a filesystem this machine sees" nowhere.txt ||
  { fail "a plan not seen:"; cat nowhere.txt; }

# 6. No SLURM_CONF: what is missing, said plainly.
env -u SLURM_CONF "$relief" render -q "$small" --executor slurm -o noconf/x.png 2> noconf.txt; code=$?
[ "$code" = 2 ] || fail "no SLURM_CONF: exit $code, expected 2"
grep -q "relief: error: no Slurm cluster answers (sinfo: .*); SLURM_CONF is not set: point it at the cluster's slurm.conf" noconf.txt ||
  { fail "no SLURM_CONF:"; cat noconf.txt; }

# 7. Ctrl-C cancels the array.
"$relief" render -q "$src/scenes/mountain-sharp.toml" --tiles 4 --executor slurm -o cancelled/x.png 2> cancelled.txt &
pid=$!
for _ in $(seq 200); do [ -n "$(squeue -h -n relief -t RUNNING 2>/dev/null)" ] && break; sleep 0.1; done
[ -n "$(squeue -h -n relief -t RUNNING 2>/dev/null)" ] || fail "cancel: no task ever ran"
kill -INT "$pid"; wait "$pid"; code=$?
[ "$code" = 130 ] || fail "cancel: exit $code, expected 130"
for _ in $(seq 50); do [ -z "$(squeue -h -n relief -t PENDING,RUNNING 2>/dev/null)" ] && break; sleep 0.1; done
[ -z "$(squeue -h -n relief -t PENDING,RUNNING 2>/dev/null)" ] || fail "cancel: the array still runs: $(squeue -h -n relief)"
[ -e cancelled/x.png ] && fail "cancel: a still was written"

[ "$status" = 0 ] && echo "on Slurm: the same bytes as here; failures, missing plans and Ctrl-C as they should"
exit $status
