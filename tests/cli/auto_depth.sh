#!/usr/bin/env bash
# depth = "auto" on the gentle-mountains scene (real topobathy data): the
# depth chosen, the summary line, the sidecar's distances per level, and the
# same .pov bytes on 1 and 2 threads. Usage: auto_depth.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
for t in 1 2; do
  mkdir -p "$work/$t"
  "$relief" compile "$src/scenes/mountain-gentle.toml" -o "$work/$t/auto.pov" --threads $t \
    --set subdivision.depth=auto --set subdivision.tolerance_m=10 2> "$work/stderr$t.txt" || fail "compile"
done
cat "$work/stderr1.txt"
grep -q "depth 4 chosen: .*1: 245 m, 2: 94.8 m, 3: 27 m, 4: 7.82 m; tolerance 10 m" "$work/stderr1.txt" \
  || fail "summary line"
cmp "$work/1/auto.pov" "$work/2/auto.pov" || fail "the .pov depends on the thread count"
grep -q '^// subdivision.depth: 4 (auto, tolerance_m = 10)$' "$work/1/auto.pov" || fail ".pov header"
json="$work/1/auto.json"
grep -q '"auto_depth": {' "$json" || fail "no auto_depth in the sidecar"
grep -q '"depth": 4,' "$json" || fail "sidecar depth"
[ "$(grep -c '"hausdorff_m": ' "$json")" = 4 ] || fail "sidecar: 4 levels expected"
grep -q '"curve": "row 16"' "$json" || fail "sidecar: the curve moved most"
echo "depth 4, 4 levels in the sidecar, identical .pov on 1 and 2 threads"
