#!/usr/bin/env bash
# Compiles a golden scene twice and checks that both .pov files equal the
# committed ref.pov byte for byte. Usage: golden_pov.sh RELIEF CASE_DIR WORK_DIR
set -u
relief=$1 case_dir=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$case_dir" || exit 1
for run in 1 2; do
  # Two thread counts: the output must not depend on them.
  "$relief" compile -q scene.toml -o "$work/run$run.pov" --threads "$run" || exit 1
done
if [ "${RELIEF_UPDATE_GOLDEN:-0}" = 1 ]; then cp "$work/run1.pov" ref.pov; fi
cmp "$work/run1.pov" "$work/run2.pov" || { echo "FAIL: two compiles differ"; exit 1; }
cmp ref.pov "$work/run1.pov" || { echo "FAIL: .pov differs from ref.pov:"; diff ref.pov "$work/run1.pov" | head -20; exit 1; }
echo "identical to ref.pov ($(wc -c < ref.pov) bytes)"
