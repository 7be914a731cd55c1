#!/usr/bin/env bash
# Runs one fuzz target for SECONDS (or, with RUNS=N in the environment, N executions) on a corpus
# seeded from the project's own files of its kind; a finding (crash, leak, undefined behaviour,
# timeout) fails it and leaves the input as crash-* / leak-* / timeout-* in the corpus folder.
# RELIEF_FUZZ_SECONDS in the environment, when set, stands for SECONDS (the build's configured value).
# Usage: fuzz/run.sh TARGET_BINARY scene|samples|curve|manifest|cpt|vrt|plan CORPUS_DIR SECONDS
set -u
bin=$(realpath "$1") kind=$2 corpus=$3 seconds=${RELIEF_FUZZ_SECONDS:-$4}
src=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$corpus"
seed() { for f in "$@"; do [ -f "$f" ] && [ "$(stat -c %s "$f")" -le 65536 ] && cp "$f" "$corpus/seed-$(echo "$f" | md5sum | cut -c1-12)"; done; }
case "$kind" in
  scene) seed "$src"/scenes/*.toml "$src"/tests/golden/*/scene.toml "$src"/tests/cli/bad/*/scene.toml ;;
  samples) seed "$src"/tests/golden/*/samples.csv "$src"/tests/cli/bad/*/*.csv "$src"/scenes/data/volcano_samples_*.csv ;;
  curve) seed "$src"/tests/cli/curves/*.json "$src"/scenes/figures/*.json ;;
  manifest) seed "$src"/tests/golden/manifest.toml "$src"/tests/cli/report/manifest.toml ;;
  cpt) seed "$src"/scenes/palettes/*.cpt "$src"/tests/cli/bad/*/*.cpt ;;
  vrt) seed "$src"/tests/cli/bad/*/*.vrt "$src"/tests/data/rasters/*.vrt ;;
  plan) seed "$src"/tests/data/plans/*.json ;;
  *) echo "unknown kind $kind"; exit 2 ;;
esac
limit=(-max_total_time="$seconds")
[ -n "${RUNS:-}" ] && limit=(-runs="$RUNS")
cd "$corpus" || exit 1
maxlen=65536
[ "$kind" = samples ] && maxlen=4096  # CSV lines: longer inputs only repeat them, at a tenth of the speed
exec "$bin" "${limit[@]}" -timeout=10 -rss_limit_mb=2048 -max_len="$maxlen" -print_final_stats=1 "$corpus"
