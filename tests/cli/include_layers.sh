#!/usr/bin/env bash
# The includes between src/ folders run one way: a folder includes only folders on lower layers
# (and its own). The layers, lowest first; no file sits at the top of src/ (the stages are composed
# in src/pipeline/). A new folder must be given its layer here.
# Usage: include_layers.sh SOURCE_DIR
set -u
src=$1/src
layers=(
  "core relief"          # relief/version.h is generated beside core's basics
  "scene curves"
  "geo subdiv"
  "compare plot fit"
  "measure"
  "emit"
  "model"                # the terrain as a 3-D model: emit's mesh to a file
  "annotate"
  "render"               # POV-Ray alone: it includes core only (below)
  "plan"
  "execute film"
  "pipeline"
  "figures regress"
  "serve"                # relief preview's server: the pipeline's preview on loopback
  "cli"
)
# Folders that may include fewer than every lower layer: FOLDER -> the folders it may include.
declare -A only=([render]="core relief")
declare -A layer
for i in "${!layers[@]}"; do for f in ${layers[$i]}; do layer[$f]=$i; done; done
status=0
for dir in "$src"/*/; do
  d=$(basename "$dir")
  [ -n "${layer[$d]:-}" ] || { echo "FAIL: src/$d has no layer in $0"; status=1; continue; }
done
check() {  # check FILE FOLDER
  local file=$1 from=$2 to inc
  while IFS= read -r inc; do
    case "$inc" in */*) to=${inc%%/*} ;; *) to=$from ;; esac
    [ -n "${layer[$to]:-}" ] || continue  # a system or third-party header
    if [ -n "${only[$from]:-}" ] && [ "$to" != "$from" ] && [[ " ${only[$from]} " != *" $to "* ]]; then
      echo "FAIL: src/${file#"$src"/} ($from) includes \"$inc\": $from includes only ${only[$from]}"
      status=1
    fi
    if [ "${layer[$to]}" -gt "${layer[$from]}" ]; then
      echo "FAIL: src/${file#"$src"/} ($from, layer ${layer[$from]}) includes \"$inc\" ($to, layer ${layer[$to]}): an upward include"
      status=1
    fi
  done < <(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$file")
}
for file in "$src"/*/*.cpp "$src"/*/*.h; do d=${file#"$src"/}; check "$file" "${d%%/*}"; done
for file in "$src"/*.cpp "$src"/*.h; do
  [ -e "$file" ] && { echo "FAIL: src/${file#"$src"/}: no file sits at the top of src/ (the stages are composed in src/pipeline/)"; status=1; }
done
[ "$status" = 0 ] && echo "includes: every one of src/'s folders includes only lower layers"
exit $status
