#!/usr/bin/env bash
# The project's golden images through `relief test` (the same machinery users
# run), then determinism: the same scene rendered with 1 and 2 threads, with
# antialiasing off and on, must give byte-identical PNGs.
# Usage: golden_render.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
if ! command -v povray >/dev/null; then echo "SKIP: povray is not installed"; exit 77; fi
rm -rf "$work" && mkdir -p "$work" || exit 1
"$relief" test "$src/tests/golden/manifest.toml" --report "$work/report" || exit 1
cd "$src/tests/golden/small" || exit 1
for aa in false true; do
  for threads in 1 2; do
    "$relief" render -q scene.toml --set render.antialias=$aa --threads $threads \
      -o "$work/aa-$aa-threads-$threads.png" || exit 1
  done
  cmp "$work/aa-$aa-threads-1.png" "$work/aa-$aa-threads-2.png" ||
    { echo "FAIL: antialias=$aa: PNG bytes differ between 1 and 2 threads"; exit 1; }
done
"$relief" render -q scene.toml -o "$work/again.png" || exit 1
cmp "$work/aa-false-threads-2.png" "$work/again.png" || { echo "FAIL: PNG bytes differ between runs"; exit 1; }
echo "PNG bytes identical across runs and thread counts, antialiasing off and on"
