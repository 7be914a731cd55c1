#!/usr/bin/env bash
# Renders a golden scene and compares the still with ref/*.png (OpenImageIO),
# then renders again with one thread and checks the PNG bytes are identical.
# Usage: golden_render.sh RELIEF IMAGE_CHECK CASE_DIR WORK_DIR
set -u
relief=$1 check=$2 case_dir=$3 work=$4
if ! command -v povray >/dev/null; then echo "SKIP: povray is not installed"; exit 77; fi
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$case_dir" || exit 1
"$relief" render -q scene.toml -o "$work/new.png" || exit 1
"$check" "$work/new.png" ref || exit 1
"$relief" render -q scene.toml -o "$work/again.png" --threads 1 || exit 1
cmp "$work/new.png" "$work/again.png" || { echo "FAIL: PNG bytes differ between runs"; exit 1; }
echo "PNG identical across runs and thread counts"
