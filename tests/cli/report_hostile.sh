#!/usr/bin/env bash
# relief test against hostile manifests:
#  - a reference "image" and a scene's samples that are someone's secret text: the run reports
#    both cases, and not a byte of either file reaches the terminal or the report (HTML, JSON,
#    JUnit);
#  - --update with references outside the manifest's folder: refused (exit 2) before anything
#    is rendered, the PNG there untouched;
#  - a manifest path with a space and a quote: the report's bless command is shell-quoted.
# Usage: report_hostile.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
small="$src/tests/golden/small/scene.toml"
secret='root:$6$REPORTSECRET$Kc9yQvS1:19000:0:99999:7:::'

# Secrets as a reference image and as samples.
mkdir -p m/refs m/data
echo "$secret" > m/refs/ref.png
echo "$secret" > m/data/shadow
printf '[samples]\npath = "data/shadow"\n' > m/secret-samples.toml
cat > m/manifest.toml <<EOF
[defaults]
width = 48
height = 32
[[case]]
name = "secret-reference"
scene = "$small"
references = "refs/"
[[case]]
name = "secret-samples"
scene = "secret-samples.toml"
references = "refs/"
EOF
"$relief" test m/manifest.toml --report report > out.txt 2>&1
code=$?
[ "$code" = 1 ] || fail "secrets: exit $code, expected 1"
grep -q "FAIL *secret-reference" out.txt || fail "the case with a secret reference is not reported as failing"
grep -q "ERROR *secret-samples" out.txt || fail "the case with secret samples is not reported as an error"
if grep -rl "REPORTSECRET" out.txt report; then fail "a secret file's bytes reached the output or the report (above)"; fi
for f in index.html summary.json junit.xml; do [ -s "report/$f" ] || fail "report/$f missing"; done

# --update with references outside the manifest's folder.
mkdir -p outside && cp "$src/tests/data/images/a.png" outside/ref.png && cp outside/ref.png outside-copy.png
mkdir -p m2 && printf '[[case]]\nname = "out"\nscene = "%s"\nreferences = "../outside/"\n' "$small" > m2/manifest.toml
"$relief" test m2/manifest.toml --update --report report2 > update.txt 2>&1
code=$?
[ "$code" = 2 ] || fail "update outside: exit $code, expected 2"
grep -q "manifest.toml:4:14: error: --update: the references of case \"out\", .*outside/*, are not in the manifest's folder" update.txt ||
  { fail "update outside:"; cat update.txt; }
cmp -s outside/ref.png outside-copy.png || fail "update outside: the PNG outside was changed"
[ -e report2 ] && fail "update outside: a report was written"

# A manifest whose path a shell would split or expand: the bless command is quoted.
dir="it's \$(here) now"
mkdir -p "$dir/refs" && cp "$src/tests/data/images/a.png" "$dir/refs/ref.png"
printf '[[case]]\nname = "q"\nscene = "%s"\nreferences = "refs/"\n' "$small" > "$dir/manifest.toml"
"$relief" test "$dir/manifest.toml" --report report3 > quoted.txt 2>&1
grep -q "\"bless\": \"relief test 'it'\\\\\\\\''s \$(here) now/manifest.toml' --update\"" report3/summary.json ||
  { fail "the bless command is not shell-quoted:"; grep bless report3/summary.json; }
grep -q "to accept the new images: relief test 'it'\\\\''s \$(here) now/manifest.toml' --update" quoted.txt ||
  { fail "the printed bless command is not shell-quoted:"; cat quoted.txt; }

[ "$status" = 0 ] && echo "secret files stayed out of the report, --update stayed in its folder, bless is quoted"
exit $status
