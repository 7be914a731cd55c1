#!/usr/bin/env bash
# A still in tiles, here and on Slurm; a test suite here and on Slurm. Whole processes,
# alternating, medians of 3:
#  1. relief render scenes/default.toml at 3840 x 2160: --tiles 2 --jobs 2 against --tiles 1
#     (the speed-up, and the share of POV-Ray's time spent parsing, from the sidecar);
#  2. the same still, --tiles 2 through a private single-node Slurm cluster against --tiles 2
#     --jobs 2 here (the cost of submitting and waiting);
#  3. relief test tests/golden/manifest.toml --jobs 2 --executor slurm against --jobs 2 here.
# Starts and stops its own cluster (tests/slurm/cluster.sh); needs povray, slurm-wlm, munge, bc.
# Usage: bench/tiles.sh [build/relief]
source "$(dirname "$0")/common.sh"
relief=$(realpath "${1:-build/relief}")
src=$(cd "$(dirname "$0")/.." && pwd)
size=(--set render.width=3840 --set render.height=2160)
scene="$src/scenes/default.toml"
cd "$work"
ratio() { echo "scale=3; $1 / $2" | bc -l; }
sidecar() { sed -n "s/.*\"$2\": \\([0-9.e+-]*\\).*/\\1/p" "$1" | head -1; }

# pair A B: runs the commands A and B alternately, three times each; their medians in $ma and $mb.
pair() {
  local a=() b=() run
  for run in 1 2 3; do a+=("$($1)"); b+=("$($2)"); done
  ma=$(median "${a[@]}") mb=$(median "${b[@]}")
}

whole() { time_of "$relief" render -q "$scene" "${size[@]}" --tiles 1 -o one/still.png; }
tiled() { time_of "$relief" render -q "$scene" "${size[@]}" --tiles 2 --jobs 2 -o two/still.png; }
pair whole tiled; m1=$ma m2=$mb
cmp -s one/still.png two/still.png || echo "warning: the tiled still differs"
echo "3840 x 2160 default scene: --tiles 1 $m1 s, --tiles 2 --jobs 2 $m2 s, ratio $(ratio "$m2" "$m1")"
for f in one two; do
  p=$(sidecar $f/still.json povray_parse) t=$(sidecar $f/still.json povray_trace)
  echo "  $f: POV-Ray parse $p s, trace $t s (summed over tiles), parse share $(ratio "$p" "$(echo "$p + $t" | bc -l)")"
done

bash "$src/tests/slurm/cluster.sh" start "$work/cluster" >/dev/null || { echo "no Slurm cluster: skipped"; exit 0; }
trap 'bash "$src/tests/slurm/cluster.sh" stop "$work/cluster" >/dev/null; rm -rf "$work"' EXIT
export SLURM_CONF="$work/cluster/slurm.conf"
here() { time_of "$relief" render -q "$scene" "${size[@]}" --tiles 2 --jobs 2 -o loc/still.png; }
slurm() { time_of "$relief" render -q "$scene" "${size[@]}" --tiles 2 --executor slurm -o slu/still.png; }
pair here slurm; ml=$ma ms=$mb
cmp -s loc/still.png slu/still.png || echo "warning: Slurm's still differs"
echo "--tiles 2: here $ml s, Slurm $ms s: overhead $(echo "$ms - $ml" | bc -l) s, ratio $(ratio "$ms" "$ml")"

test_here() { time_of "$relief" test "$src/tests/golden/manifest.toml" --jobs 2 --report tl; }
test_slurm() { time_of "$relief" test "$src/tests/golden/manifest.toml" --jobs 2 --executor slurm --report ts; }
pair test_here test_slurm; ml=$ma ms=$mb
echo "relief test (17 cases) --jobs 2: here $ml s, Slurm $ms s, ratio $(ratio "$ms" "$ml")"
