#!/usr/bin/env bash
# Runs `relief compile` on one bad-input case and checks, exactly: the
# diagnostics on stderr (expected_stderr.txt), the exit code (expected_code,
# default 2) and that no output file was written.
# Usage: run_bad_case.sh RELIEF CASE_DIR WORK_DIR   (RELIEF_UPDATE_GOLDEN=1 rewrites the expectation)
set -u
relief=$1 case_dir=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cp -r "$case_dir"/. "$work"/ && cd "$work" || exit 1
expected_code=$(cat expected_code 2>/dev/null || echo 2)
"$relief" compile -q scene.toml -o out/scene.pov --dump-net out/net.csv 2>stderr.txt >stdout.txt
code=$?
if [ "${RELIEF_UPDATE_GOLDEN:-0}" = 1 ]; then
  cp stderr.txt "$case_dir/expected_stderr.txt"
fi
status=0
if ! diff -u "$case_dir/expected_stderr.txt" stderr.txt; then
  echo "FAIL: diagnostics differ (above: - expected, + actual)"; status=1
fi
if [ "$code" != "$expected_code" ]; then
  echo "FAIL: exit code $code, expected $expected_code"; status=1
fi
if [ -d out ] && [ -n "$(ls -A out)" ]; then
  echo "FAIL: output written despite the error:"; ls -la out; status=1
fi
[ -s stdout.txt ] && { echo "FAIL: unexpected stdout:"; cat stdout.txt; status=1; }
exit $status
