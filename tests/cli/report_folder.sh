#!/usr/bin/env bash
# relief test's report folder appears whole or not at all:
#  - a run writes it, and leaves no private folder beside it;
#  - an interrupted run (Ctrl-C) exits 130 and leaves the report before it byte for byte;
#  - a folder of the user's as --report is refused (exit 2) and left as it was;
#  - a suite of more cases than the soft limit of open files allows two each still runs
#    (relief raises the soft limit to the hard one).
# Usage: report_folder.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
small="$src/tests/golden/small/scene.toml"
manifest() {  # manifest FILE CASES WIDTH HEIGHT
  { printf '[defaults]\nwidth = %s\nheight = %s\n' "$3" "$4"
    for i in $(seq 1 "$2"); do printf '[[case]]\nname = "c%02d"\nscene = "%s"\nreferences = "refs/c%02d/"\n' "$i" "$small" "$i"; done
  } > "$1"
}
private_left() { ls -A "$1" | grep -q '^\.relief-'; }

# A whole report, nothing beside it.
mkdir -p suite && manifest suite/manifest.toml 2 48 32
"$relief" test suite/manifest.toml --update --report reports/first > first.txt 2>&1
code=$?
[ "$code" = 0 ] || { fail "first run: exit $code, expected 0"; cat first.txt; }
for f in index.html summary.json junit.xml images/c01.new.png images/c02.new.png; do
  [ -s "reports/first/$f" ] || fail "first run: reports/first/$f missing"
done
private_left reports && fail "first run: a private folder is left in reports/: $(ls -A reports)"
cp -a reports/first first-copy

# Interrupted: the report before it, as it was.
manifest suite/big.toml 3 960 640
"$relief" test suite/big.toml --jobs 1 --report reports/first > interrupted.txt 2>&1 &
pid=$!
for _ in $(seq 1 100); do pgrep -P "$pid" >/dev/null && break; sleep 0.1; done  # POV-Ray started
sleep 0.5
kill -INT "$pid"
wait "$pid"
code=$?
[ "$code" = 130 ] || { fail "interrupted: exit $code, expected 130"; cat interrupted.txt; }
grep -q "^relief test: interrupted; no report written$" interrupted.txt || { fail "interrupted:"; cat interrupted.txt; }
diff -r first-copy reports/first >/dev/null || fail "interrupted: the report before it was changed"
private_left reports && fail "interrupted: a private folder is left in reports/: $(ls -A reports)"

# A folder of the user's is not replaced.
mkdir -p mine && echo "notes" > mine/notes.txt
"$relief" test suite/manifest.toml --report mine > mine.txt 2>&1
code=$?
[ "$code" = 2 ] || fail "a user's folder: exit $code, expected 2"
grep -q "^relief: error: --report mine: holds files that are not a relief test report" mine.txt ||
  { fail "a user's folder:"; cat mine.txt; }
[ "$(cat mine/notes.txt)" = notes ] && [ "$(ls -A mine)" = notes.txt ] || fail "a user's folder was changed"

# A trailing slash is the same folder.
"$relief" test suite/manifest.toml --report reports/first/ > slash.txt 2>&1
code=$?
[ "$code" = 0 ] || { fail "--report reports/first/: exit $code, expected 0"; cat slash.txt; }
[ -s reports/first/index.html ] && [ ! -e reports/first/report ] || fail "--report reports/first/: not the same folder"
private_left reports && fail "--report reports/first/: a private folder is left in reports/"

# A folder holding the suite's references (it would be replaced, blessed images and all).
mkdir -p blessing && manifest blessing/manifest.toml 1 48 32
"$relief" test blessing/manifest.toml --update --report blessing/refs > refs.txt 2>&1
code=$?
[ "$code" = 2 ] || fail "--report over the references: exit $code, expected 2"
grep -q "^relief: error: --report blessing/refs: holds the references of case \"c01\"" refs.txt ||
  { fail "--report over the references:"; cat refs.txt; }
[ -e blessing/refs ] && fail "--report over the references: something was written"

# More cases than a soft limit of 40 open files allows at two each.
mkdir -p many && manifest many/manifest.toml 24 16 16
(ulimit -Sn 40 && "$relief" test many/manifest.toml --update --report reports/many) > many.txt 2>&1
code=$?
[ "$code" = 0 ] || { fail "24 cases under ulimit -Sn 40: exit $code, expected 0"; tail -5 many.txt; }
[ "$(ls reports/many/images/*.new.png 2>/dev/null | wc -l)" = 24 ] || fail "24 cases: not 24 new images"
exit $status
