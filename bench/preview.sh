#!/usr/bin/env bash
# relief preview: the time from the command to the page's first frame of the terrain (headless
# Chromium started with it, WebGL in SwiftShader: this machine has no GPU), medians of 5, for the
# default scene and a 53 M-cell raster (volcano2hires.tif on a 2.5 m net); against relief compile
# of the same scene in the same run (the baseline: the still's first step).
# Usage: bench/preview.sh [build/relief] [shared/data] [build/web/node_modules]
source "$(dirname "$0")/common.sh"
relief=$(realpath "${1:-build/relief}")
data=$(realpath "${2:-$(dirname "$0")/../../shared/data}")
export NODE_PATH=$(realpath "${3:-build/web/node_modules}")
here=$(realpath "$(dirname "$0")")
scene=$(realpath "$here/../scenes/default.toml")
cd "$work"
first_frame() {  # the scene and --set arguments: prints the JSON line
  rm -f url.txt
  local start; start=$(date +%s%3N)
  "$relief" preview -q --no-open "$@" > url.txt 2>/dev/null &
  local pid=$!
  node "$here/preview_first_frame.cjs" url.txt "$start"
  kill -INT $pid; wait $pid || true
}
row() {  # label, then the scene and its --set arguments
  local label=$1; shift
  local f=() c=() line
  for _ in 1 2 3 4 5; do
    c+=("$(time_of "$relief" compile -q "$@" -o c.pov)")
    line=$(first_frame "$@")
    echo "  $line" >&2
    f+=("$(echo "$line" | sed -E 's/.*"firstFrameMs":([0-9]+).*/\1/')")
  done
  local ff; ff=$(echo "$(median "${f[@]}") / 1000" | bc -l)
  printf '| %s | %.2f s | %.2f s | %.2fx |\n' "$label" "$ff" "$(median "${c[@]}")" "$(echo "$ff / $(median "${c[@]}")" | bc -l)"
}
echo "| case | command to first frame | relief compile (the .pov) | ratio |"
echo "|---|---|---|---|"
row "default scene" "$scene"
row "volcano2hires.tif, 2.5 m net" "$data/rasters/volcano2hires.tif" --set net.spacing_m=2.5 --set 'samples.vertical_unit="m"'
