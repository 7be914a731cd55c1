#!/usr/bin/env bash
# A render plan is trusted for nothing (docs/security.md): every step that reads one verifies it
# whole, and a plan forged by someone who can write its folder (its hash made right again) still
# cannot turn the sandbox off, write outside its folder, bind a folder it names, follow a link, or
# make the finish decode more pixels than the still has.
#  1. an edited .pov, an edited plan.json: every step refuses, naming the file; a forged plan that
#     changes nothing renders (so the forging below is relief's own hashing)
#  2. a forged .pov that writes a file, its plan saying "sandbox": false: POV-Ray stays in its
#     sandbox (only --no-sandbox on the command lets it out, with a warning)
#  3. forged outputs and templates outside the folder, a .pov that is a link, another relief's
#     plan, another POV-Ray's, a still of 1e9 pixels a side: refused before any work
#  4. a tile image swapped after rendering, a tile PNG whose header claims 60000 x 60000 pixels:
#     the finish refuses them by name, allocating nothing
#  5. a link planted as the plan's tiles/: nothing written through it
#  6. a read-only plan: exit 2, not 3
# Usage: plan_hostile.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
needs_povray
enter_fresh_work
scene="$src/tests/golden/small/scene.toml"   # 160 x 120: tiles of 40 rows
mkdir -p outside

# plan.py: plan.json read and written with its numbers as relief wrote them (Python's shortest
# float text is not always nlohmann's, and a number written otherwise would change the fields' hash
# and make the forge, not the attack, what relief refuses).
cat > plan.py <<'PY'
import hashlib, json, os, re
MARK = "@@relief-number@@"
def load(path):
    return json.load(open(path, encoding="utf-8"), parse_float=lambda text: MARK + text)
def text(j, **kw):
    return re.sub('"' + MARK + '([^"]*)"', r"\1", json.dumps(j, ensure_ascii=False, **kw))
def sha(p):
    return "sha256:" + hashlib.sha256(open(p, "rb").read()).hexdigest() if os.path.isfile(p) else ""
def forge(d, change=None):
    p = os.path.join(d, "plan.json")
    j = load(p)
    if change:
        change(j)
    j["pov"]["sha256"] = sha(os.path.join(d, j["pov"]["name"]))
    for key in ("reads", "extras"):
        for f in j[key]:
            f["sha256"] = sha(os.path.join(d, f["name"]))
    for f in j["templates"]:
        f["sha256"] = sha(os.path.join(d, "templates", f["name"]))
    del j["hash"]
    j["hash"] = "sha256:" + hashlib.sha256(text(j, separators=(",", ":")).encode("utf-8")).hexdigest()
    open(p, "w", encoding="utf-8").write(text(j, indent=1))
PY
# forge PLAN: the hashes made right again for what the folder now holds, as relief makes them.
forge() { PYTHONPATH=$work python3 -c 'import plan, sys; plan.forge(sys.argv[1])' "$1"; }
# edit PLAN PYTHON: plan.json's JSON as j, changed by PYTHON, then forged.
edit() {
  PYTHONPATH=$work python3 -c '
import plan, sys
def change(j):
    exec(sys.argv[2])
plan.forge(sys.argv[1], change)' "$1" "$2"
}
# refused NAME EXPECTED_CODE PATTERN command...: the command exits so, saying PATTERN.
refused() {
  local name=$1 want=$2 pattern=$3; shift 3
  "$@" > "$name.out" 2> "$name.txt"; local code=$?
  [ "$code" = "$want" ] || { fail "$name: exit $code, expected $want"; cat "$name.txt"; return; }
  grep -qE -- "$pattern" "$name.txt" || { fail "$name: not '$pattern':"; cat "$name.txt"; }
}
fresh() { "$relief" plan -q "$scene" --tiles 3 -o "$1/still.png"; }

# 1. Edited, forged unchanged.
p=$(fresh edited)
forge "$p"
"$relief" render-tile "$p" --tile 0 2> forged.txt || { fail "a plan forged unchanged is refused"; cat forged.txt; }
echo "// one more line" >> "$p/still.pov"
for step in "render-tile $p --tile 1" "finish $p" "render --resume $p"; do
  refused "edited-pov-${step%% *}" 2 "^$p/still.pov: error: differs from the file the plan was made with \(its SHA-256 is not the one plan.json holds\): make the plan again$" "$relief" $step
done
[ -e edited/still.png ] && fail "an edited .pov: a still was written"
p=$(fresh edited-json)
sed -i 's/"width": 160/"width": 161/' "$p/plan.json"
refused edited-json 2 "^$p/plan.json: error: the render plan was changed after relief wrote it \(its fields do not give the hash it holds\): make it again$" \
  "$relief" render-tile "$p" --tile 0
[ -e "$p/tiles/tile-0000.png" ] && fail "an edited plan.json: a tile was rendered"

# 2. A forged .pov that writes outside, in a plan that says "sandbox": false.
p=$(fresh pwn)
printf '#fopen F "%s/outside/pwned.txt" write\n#write (F, "pwned")\n#fclose F\n' "$work" >> "$p/still.pov"
edit "$p" 'j["render"]["sandbox"] = False'
refused pwn 3 "Cannot open|cannot open|Parse Error|Error" "$relief" render-tile "$p" --tile 0
[ -e outside/pwned.txt ] && fail "a forged plan wrote outside its folder: the sandbox was off"
"$relief" render-tile "$p" --tile 0 --no-sandbox 2> pwn-nosandbox.txt || true
grep -q "relief: warning: POV-Ray runs outside its sandbox (--no-sandbox)" pwn-nosandbox.txt || { fail "--no-sandbox: no warning"; cat pwn-nosandbox.txt; }
[ -e outside/pwned.txt ] || fail "--no-sandbox did not let the .pov write (so the refusal above proves nothing)"
rm -f outside/pwned.txt

# 3. Refused before any work.
damaged="error: the render plan is damaged \(its files or sizes are not a plan's\): make it again$"
p=$(fresh escape); edit "$p" 'j["outputs"]["still"] = "../escape.png"'
refused escape-still 2 "$damaged" "$relief" render-tile "$p" --tile 0
p=$(fresh escape-sidecar); edit "$p" 'j["outputs"]["sidecar"] = "/tmp/x.json"'
refused escape-sidecar 2 "$damaged" "$relief" finish "$p"
p=$(fresh templates); edit "$p" 'j["templates"].append({"name": "../../../etc", "role": "a template file", "sha256": ""})'
refused templates 2 "$damaged" "$relief" render-tile "$p" --tile 0
p=$(fresh huge); edit "$p" 'j["render"]["width"] = 1000000000; j["render"]["height"] = 1000000000'
refused huge 2 "$damaged" "$relief" render-tile "$p" --tile 0
p=$(fresh link)
cp "$p/still.pov" outside/still.pov && rm "$p/still.pov" && ln -s "$work/outside/still.pov" "$p/still.pov" && forge "$p"
refused link 2 "^$p/still.pov: error: the plan's file cannot be used: it is a link, and relief follows none out of its own folders$" \
  "$relief" render-tile "$p" --tile 0
p=$(fresh other-relief); edit "$p" 'j["relief_version"] = "0.0.1"'
refused other-relief 2 "^$p/plan.json: error: a render plan made by relief 0.0.1, and this is relief [^ ]+: make it again with this relief, or use the one that made it$" \
  "$relief" render-tile "$p" --tile 0
p=$(fresh other-povray); edit "$p" 'j["povray_version"] = "9.9"'
refused other-povray 2 "^$p/plan.json: error: the plan was made for POV-Ray 9.9, and .* has POV-Ray 3\.7.*: install that POV-Ray here, or render the plan where it is$" \
  "$relief" render-tile "$p" --tile 0
refused other-povray-resume 2 "the plan was made for POV-Ray 9.9" "$relief" render --resume "$p"
# An output renamed by a forger is still written beside the plan, under the plan's own folder's parent.
p=$(fresh beside); edit "$p" 'j["outputs"]["still"] = "renamed.png"'
for k in 0 1 2; do "$relief" render-tile "$p" --tile $k || fail "beside: tile $k"; done
"$relief" finish "$p/" 2> beside.txt || { fail "beside: finish"; cat beside.txt; }
[ -f beside/renamed.png ] || fail "a plan's renamed still was not written beside the plan"

# 4. Tiles: one swapped after rendering, one whose header claims 60000 x 60000 pixels.
p=$(fresh swapped)
for k in 0 1 2; do "$relief" render-tile "$p" --tile $k || fail "swapped: tile $k"; done
cp "$p/tiles/tile-0002.png" "$p/tiles/tile-0001.png"
refused swapped 2 "^$p/plan.json: error: tile 2 of 3: its image is not the one rendered \(its SHA-256 is not the record's\): render the tile again$" \
  "$relief" finish "$p"
[ -e swapped/still.png ] && fail "a swapped tile: a still was written"
python3 - "$p/tiles/tile-0000.png" <<'PY'
import struct, sys, zlib
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
row = b"\0" + b"\0" * 3 * 60000
idat = zlib.compressobj(9)
body = b"".join(idat.compress(row) for _ in range(200)) + idat.flush()
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 60000, 60000, 8, 2, 0, 0, 0)) + chunk(b"IDAT", body) + chunk(b"IEND", b"")
open(sys.argv[1], "wb").write(png)
PY
python3 - "$p/tiles" <<'PY'
import hashlib, json, os, sys
d = sys.argv[1]
r = json.load(open(os.path.join(d, "tile-0000.json")))
r["image_sha256"] = "sha256:" + hashlib.sha256(open(os.path.join(d, "tile-0000.png"), "rb").read()).hexdigest()
json.dump(r, open(os.path.join(d, "tile-0000.json"), "w"), indent=1)
PY
"$relief" render-tile "$p" --tile 1 || fail "swapped: tile 1 again"
# Under a 2 GB address-space limit that decoding it would break (not under AddressSanitizer, whose
# shadow memory alone is more than that).
limit=(bash -c 'ulimit -v 2000000; exec "$0" "$@"')
"${limit[@]}" "$relief" --version > /dev/null 2>&1 || limit=()
"${limit[@]}" "$relief" finish "$p" > bomb.out 2> bomb.txt; code=$?
[ "$code" = 2 ] || { fail "a tile of 60000 x 60000 pixels: exit $code, expected 2"; cat bomb.txt; }
grep -q "tile 1 of 3: cannot read .*tile-0000.png: it is 60000 x 60000 pixels, not 160 x 40" bomb.txt || { fail "bomb:"; cat bomb.txt; }

# 5. A link planted as tiles/.
p=$(fresh planted)
mkdir -p outside/tiles && ln -s "$work/outside/tiles" "$p/tiles"
refused planted 2 "^relief: error: .*$p/tiles: is a link, and relief writes through none in its working folders \(someone put it there\): remove it" \
  "$relief" render-tile "$p" --tile 0
[ -z "$(ls -A outside/tiles)" ] || fail "a tile was written through a planted link: $(ls outside/tiles)"

# 6. A read-only plan (a read-only bind mount: root ignores file modes).
p=$(fresh readonly)
if unshare -m true 2>/dev/null; then
  unshare -m sh -c 'mount --bind -o ro "$1" "$1" && exec "$2" render-tile "$1" --tile 0' sh "$p" "$relief" > ro.out 2> ro.txt; code=$?
  [ "$code" = 2 ] || { fail "a read-only plan: exit $code, expected 2"; cat ro.txt; }
  grep -q "Read-only file system" ro.txt || { fail "a read-only plan:"; cat ro.txt; }
else
  echo "SKIP 6 (a read-only plan): no mount namespace here"
fi

[ "$status" = 0 ] && echo "plans verified at every step; forged plans kept in the sandbox, in their folder, and small"
exit $status
