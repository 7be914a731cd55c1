#!/usr/bin/env bash
# POV-Ray's front end gives up when its worker thread is slow to start ("Timed out waiting for
# worker thread startup", seen on a loaded machine): relief runs it again, up to three runs in
# all, and the still is made. A povray that does so once (then the real one) gives a still from
# the second run; one that always does gives exit 3 after three runs, POV-Ray's words and no PNG.
# Usage: povray_start_retry.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
real=$(command -v povray) || { echo "SKIP: povray is not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work/once" "$work/always" && cd "$work" || exit 1
status=0
# fake DIR FAILURES: a povray in DIR that fails FAILURES times as POV-Ray does, then is POV-Ray.
fake() {
  cat > "$1/povray" <<SH
#!/bin/sh
[ "\$1" = --version ] && exec "$real" "\$@"  # relief asks the version first: not a render
echo run >> "$work/$1/runs"
if [ "\$(wc -l < "$work/$1/runs")" -le $2 ]; then
  echo "povray: Timed out waiting for worker thread startup" >&2
  exit 1
fi
exec "$real" "\$@"
SH
  chmod +x "$1/povray"
}
fake once 1
fake always 99
scene="$src/tests/golden/small/scene.toml"
# --no-sandbox: the fake counts its runs in a file, which the sandbox would not let it write.
for kind in once always; do
  PATH="$work/$kind:$PATH" "$relief" render -q "$scene" --set render.width=48 --set render.height=32 \
    -o "$work/out-$kind/still.png" --no-sandbox 2> "$kind.txt"
  echo $? > "$kind.exit"
done
[ "$(cat once.exit)" = 0 ] || { echo "FAIL: one slow start: exit $(cat once.exit)"; cat once.txt; status=1; }
[ "$(wc -l < once/runs)" = 2 ] || { echo "FAIL: one slow start: $(wc -l < once/runs) runs, expected 2"; status=1; }
[ -s out-once/still.png ] || { echo "FAIL: one slow start: no still"; status=1; }
[ "$(cat always.exit)" = 3 ] || { echo "FAIL: always slow: exit $(cat always.exit), expected 3"; cat always.txt; status=1; }
[ "$(wc -l < always/runs)" = 3 ] || { echo "FAIL: always slow: $(wc -l < always/runs) runs, expected 3"; status=1; }
grep -q "Timed out waiting for worker thread startup" always.txt || { echo "FAIL: POV-Ray's words are not in:"; cat always.txt; status=1; }
[ -e out-always/still.png ] && { echo "FAIL: always slow: a PNG was left"; status=1; }
[ "$status" = 0 ] && echo "a slow worker start: tried again (2 runs, a still); always slow: 3 runs, exit 3"
exit $status
