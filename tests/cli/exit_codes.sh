#!/usr/bin/env bash
# README.md's table of exit codes is the one relief --help prints (src/cli/cli_common.cpp,
# kExitCodeRows), row for row and word for word.
# Usage: exit_codes.sh RELIEF README
set -u
relief=$1 readme=$2
# The help's rows, each joined to one line: "CODE MEANING".
help=$("$relief" --help) || { echo "FAIL: relief --help exited $?"; exit 1; }
from_help=$(printf '%s\n' "$help" | awk '
  /^Exit codes:$/ { on = 1; next }
  on && /^  [0-9]/ { if (row != "") print row; row = $1; $1 = ""; row = row $0; next }
  on && /^       / { sub(/^ +/, " "); row = row $0; next }
  on { if (row != "") print row; exit }')
# The README's rows under "### Exit codes": "| CODE | MEANING |".
from_readme=$(awk -F' [|] ' '
  /^### Exit codes/ { on = 1; next }
  on && /^\| [0-9]+ \| / { sub(/^\| /, "", $1); sub(/ \|$/, "", $2); print $1 " " $2; next }
  on && /^#/ { exit }' "$readme")
[ -n "$from_help" ] || { echo "FAIL: no exit codes in relief --help"; exit 1; }
if [ "$from_help" != "$from_readme" ]; then
  echo "FAIL: README.md's exit codes differ from relief --help's (- README, + help):"
  diff <(printf '%s\n' "$from_readme") <(printf '%s\n' "$from_help")
  exit 1
fi
echo "exit codes: $(printf '%s\n' "$from_help" | wc -l) rows, README and --help agree"
