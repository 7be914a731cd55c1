#!/usr/bin/env bash
# relief diff against idiff on the same pair of 4096 x 4096 RGB images, in the
# same run: megapixels per second (median of 5 runs each, alternating).
# Needs openimageio-tools (idiff, oiiotool). Usage: bench/diff_vs_idiff.sh [build/relief]
set -euo pipefail
relief=${1:-build/relief}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
oiiotool --pattern noise:type=uniform:min=0:max=1:seed=1 4096x4096 3 -d uint8 -o "$work/a.png"
oiiotool "$work/a.png" --fill:color=1,0,0 512x256+1000+2000 -d uint8 -o "$work/b.png"
time_of() { local t0 t1; t0=$(date +%s.%N); "$@" >/dev/null 2>&1 || true; t1=$(date +%s.%N); echo "$t1 - $t0" | bc -l; }
r=(); i=()
for run in 1 2 3 4 5; do
  r+=("$(time_of "$relief" diff "$work/a.png" "$work/b.png" --fail 0.004)")
  i+=("$(time_of idiff -fail 0.004 "$work/a.png" "$work/b.png")")
done
median() { printf '%s\n' "$@" | sort -g | sed -n 3p; }
rm=$(median "${r[@]}"); im=$(median "${i[@]}")
mp=$(echo "4096*4096/1000000" | bc -l)
printf 'relief diff: %.3f s (%.1f MP/s)\nidiff:       %.3f s (%.1f MP/s)\nratio (idiff time / relief time): %.2f\n' \
  "$rm" "$(echo "$mp/$rm" | bc -l)" "$im" "$(echo "$mp/$im" | bc -l)" "$(echo "$im/$rm" | bc -l)"
