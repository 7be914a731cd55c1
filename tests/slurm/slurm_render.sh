#!/usr/bin/env bash
# Through the private Slurm cluster (cluster.sh: 3 nodes; SLURM_CONF names it): a still as 9 tiles
# (each tile's record naming its node, the sidecar counting them), a sweep, a test suite and a
# 12-frame film give the bytes they give on this machine alone, each on at least 2 nodes; a task that fails names
# its Slurm job, state and log; a task that cannot see its plan says so; a task list or plan
# changed after submission is refused; a plan in a folder named with % (sbatch's patterns) and
# --slurm-args quoted as a shell quotes work; without SLURM_CONF, or with a controller that does
# not answer, relief says what is missing within seconds; Ctrl-C cancels the job array.
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

# 1. A still: 9 tiles on Slurm's nodes, 1 here.
"$relief" render -q "$src/scenes/default.toml" "${size[@]}" -o local/still.png || fail "the local still"
"$relief" render -q "$src/scenes/default.toml" "${size[@]}" --tiles 9 --executor slurm -o slurm/still.png 2> still.txt ||
  { fail "the still on Slurm"; cat still.txt; }
for f in png pov; do cmp -s local/still.$f slurm/still.$f || fail "Slurm's still.$f is not the local one"; done
grep -q '"host":' slurm/still.json && [ "$(grep -c '"plan_hash":' slurm/still.json)" = 9 ] || fail "the sidecar lacks the 9 tiles' records"
nodes=$(python3 -c "
import json, sys
j = json.load(open('slurm/still.json'))
tiles = [t['node'] for t in j['tiles']]
ok = sorted(set(tiles)) == sorted(j['nodes']) and all(j['nodes'][n] == tiles.count(n) for n in j['nodes'])
print(len(j['nodes']), ' '.join(f'{n}:{c}' for n, c in sorted(j['nodes'].items())), 'ok' if ok and set(tiles) <= {'n1', 'n2', 'n3'} else 'WRONG')")
echo "the still's tiles ran on $nodes"
case "$nodes" in [2-9]\ *ok) ;; *) fail "the still's 9 tiles did not run on 2 nodes or more, named in their records: $nodes" ;; esac

# 2. A sweep: a task a still.
vary=(--vary subdivision.omega=1/64,1/16 --set render.width=64 --set render.height=48)
"$relief" sweep -q "$small" "${vary[@]}" -o local-sweep/sheet.png || fail "the local sweep"
"$relief" sweep -q "$small" "${vary[@]}" --executor slurm -o slurm-sweep/sheet.png 2> sweep.txt || { fail "the Slurm sweep"; cat sweep.txt; }
for f in sheet.png sheet-stills/001.png sheet-stills/002.png; do
  cmp -s "local-sweep/$f" "slurm-sweep/$f" || fail "the sweep's $f differs on Slurm"
done
# The nodes a set of records name (the sidecars' "nodes", the suite's cases', the film's frames'): at least 2.
on_nodes() {  # what, then a Python expression of the nodes' names from j (each file's JSON) over the files
  local what=$1 expr=$2; shift 2
  local seen
  seen=$(python3 -c "
import json, sys
names = set()
for f in sys.argv[1:]:
    j = json.load(open(f))
    names |= set($expr)
print(' '.join(sorted(names)))" "$@")
  echo "$what ran on: $seen"
  [ "$(wc -w <<< "$seen")" -ge 2 ] || fail "$what did not run on 2 nodes or more: ${seen:-none named}"
}
on_nodes "the sweep's stills" "j['nodes']" slurm-sweep/sheet-stills/*.json

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
on_nodes "the suite's cases" "n for c in j['cases'] for n in c['nodes']" slurm-report/summary.json

# 3b. A film: a task a frame on Slurm's nodes, the same MP4 as here.
if command -v ffmpeg >/dev/null; then
  film=(--set animation.frames=12 --set 'animation.path="orbit"' --set render.width=160 --set render.height=120)
  "$relief" animate -q "$small" "${film[@]}" -o local-film/film.mp4 || fail "the local film"
  "$relief" animate -q "$small" "${film[@]}" --executor slurm -o slurm-film/film.mp4 2> film.txt ||
    { fail "the film on Slurm"; cat film.txt; }
  cmp -s local-film/film.mp4 slurm-film/film.mp4 || fail "the film differs on Slurm"
  on_nodes "the film's 12 frames" "n for f in j['frames'] for n in f.get('nodes', [])" slurm-film/film.json
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

# 5. A task whose plan this machine does not see; a task list or a plan changed after submission.
printf '0\tsha256:0\t%s\n' "$work/nowhere/x.plan" > tasks.txt
sum="sha256:$(sha256sum tasks.txt | cut -d' ' -f1)"
"$relief" render-tile --tasks tasks.txt --tasks-sha256 "$sum" --index 0 2> nowhere.txt; code=$?
[ "$code" = 3 ] || fail "a plan not seen: exit $code, expected 3"
grep -q "^relief: error: $work/nowhere/x.plan/plan.json: no render plan here: the plan's folder must be on a filesystem this machine sees" nowhere.txt ||
  { fail "a plan not seen:"; cat nowhere.txt; }
plan=$("$relief" plan -q "$small" --tiles 2 -o listed/x.png)
hash=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["hash"])' "$plan/plan.json")
printf '0\t%s\t%s\n' "$hash" "$plan" > listed.txt
sum="sha256:$(sha256sum listed.txt | cut -d' ' -f1)"
"$relief" render-tile --tasks listed.txt --tasks-sha256 "$sum" --index 0 || fail "a listed task"
printf '1\t%s\t%s\n' "$hash" "$plan" > listed.txt
"$relief" render-tile --tasks listed.txt --tasks-sha256 "$sum" --index 0 2> changed-list.txt; code=$?
[ "$code" = 3 ] && grep -q "listed.txt: the task list is not the one submitted (its SHA-256 changed since): submit the job again" changed-list.txt ||
  { fail "a task list changed after submission: exit $code"; cat changed-list.txt; }
printf '0\tsha256:%064d\t%s\n' 0 "$plan" > other-plan.txt
sum="sha256:$(sha256sum other-plan.txt | cut -d' ' -f1)"
"$relief" render-tile --tasks other-plan.txt --tasks-sha256 "$sum" --index 0 2> other-plan-err.txt; code=$?
[ "$code" = 3 ] && grep -q "plan.json: the render plan is not the one submitted (another plan was made in its folder since)" other-plan-err.txt ||
  { fail "a plan changed after submission: exit $code"; cat other-plan-err.txt; }

# 5b. A plan in a folder whose name holds sbatch's patterns (%x, %a), --slurm-args quoted as a shell quotes.
"$relief" render -q "$small" --tiles 2 --executor slurm --keep-plan --slurm-args "--comment='a still, named with spaces'" \
  -o 'pct%x%a/x.png' 2> pct.txt || { fail "a plan in a folder named with %"; cat pct.txt; }
ls 'pct%x%a/x.plan/slurm/logs/task-0.log' 'pct%x%a/x.plan/slurm/logs/task-1.log' >/dev/null || fail "the tasks' logs are not in the plan's folder"
"$relief" render -q "$small" -o pct-local/x.png || fail "the local still of small"
cmp -s 'pct%x%a/x.png' pct-local/x.png || fail "the still in a folder named with % differs from the local one"
"$relief" render -q "$small" --executor slurm --slurm-args "--comment='unclosed" -o unclosed/x.png 2> unclosed.txt; code=$?
[ "$code" = 2 ] && grep -q "relief: error: --slurm-args: .* cannot be split into words as a shell would .*: close its quotes" unclosed.txt ||
  { fail "--slurm-args with an unclosed quote: exit $code"; cat unclosed.txt; }

# 6. No SLURM_CONF: what is missing, said plainly.
env -u SLURM_CONF "$relief" render -q "$small" --executor slurm -o noconf/x.png 2> noconf.txt; code=$?
[ "$code" = 2 ] || fail "no SLURM_CONF: exit $code, expected 2"
grep -q "relief: error: no Slurm cluster answers (sinfo: .*); SLURM_CONF is not set: point it at the cluster's slurm.conf" noconf.txt ||
  { fail "no SLURM_CONF:"; cat noconf.txt; }

# 6b. A controller that does not answer: said within seconds, not after Slurm's 60 s.
sed 's/^SlurmctldPort=.*/SlurmctldPort=1/' "$SLURM_CONF" > dead.conf
grep -q '^SlurmctldPort=1$' dead.conf || echo 'SlurmctldPort=1' >> dead.conf
t0=$(date +%s)
SLURM_CONF=$work/dead.conf "$relief" render -q "$small" --executor slurm -o dead/x.png 2> dead.txt; code=$?
took=$(( $(date +%s) - t0 ))
[ "$code" = 2 ] && grep -q "relief: error: no Slurm cluster answers" dead.txt || { fail "a dead controller: exit $code"; cat dead.txt; }
[ "$took" -le 20 ] || fail "a dead controller took $took s to be told"

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
