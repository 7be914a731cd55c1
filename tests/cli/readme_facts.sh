#!/usr/bin/env bash
# The numbers the README states about the test suite, held to the tree: the count of bad-input
# cases it names is the count of folders in tests/cli/bad/.
# Usage: readme_facts.sh SOURCE_DIR
set -u
src=$1
cases=$(find "$src/tests/cli/bad" -mindepth 1 -maxdepth 1 -type d | wc -l)
said=$(grep -oE '[0-9]+ bad scene files' "$src/README.md" | grep -oE '^[0-9]+')
[ -n "$said" ] || { echo "FAIL: README.md no longer says how many bad scene files tests/cli/bad/ holds"; exit 1; }
[ "$said" = "$cases" ] || { echo "FAIL: README.md says $said bad scene files; tests/cli/bad/ holds $cases: fix the README"; exit 1; }
echo "README: $said bad scene files, as tests/cli/bad/ holds"
