#!/usr/bin/env bash
# relief export: the terrain the still renders (its refined lattice, every node a vertex) as
# glTF (read back by Assimp, not the tinygltf that wrote it), STL (a closed, consistently oriented
# solid by ADMesh's check, its facet normals right), OBJ and PLY (read back here from the formats'
# specifications: Assimp wrote them); the same bytes under another name and on a second run; --scale in millimetres;
# --max-triangles met by the adaptive mesh, its bound said; a format relief does not write refused.
# Usage: export.sh RELIEF SOURCE_DIR WORK_DIR
. "$(dirname "$0")/lib.sh" "$@"
enter_fresh_work
for tool in admesh assimp; do command -v $tool >/dev/null || { echo "FAIL: $tool is not installed"; exit 1; }; done
cp "$src/scenes/data/rasters/volcano2.tif" dem.tif
sets=(--set render.width=320 --set 'samples.vertical_unit="m"')
"$relief" compile -q dem.tif -o dem.pov "${sets[@]}" --set base.thickness_m=false || fail "compile"
nodes=$(python3 -c "import json; r = json.load(open('dem.json'))['refined']; print(r['rows'] * r['cols'], r['triangles'])")
read -r vertices triangles <<< "$nodes"
echo "the still's surface: $vertices vertices, $triangles triangles"

# The floating surface ([base] thickness_m = false): every refined node once, the .pov's triangles.
for ext in glb gltf obj ply; do
  "$relief" export dem.tif -o "float.$ext" "${sets[@]}" --set base.thickness_m=false 2> "float-$ext.txt" ||
    { fail "export .$ext"; cat "float-$ext.txt"; }
  grep -q "wrote float.$ext (.*: $vertices vertices, $triangles triangles of the surface .* every node a vertex" "float-$ext.txt" ||
    { fail ".$ext: not the still's surface:"; cat "float-$ext.txt"; }
done
for ext in glb gltf; do
  assimp info "float.$ext" > "float-$ext.info" 2>&1 || { fail "Assimp cannot read float.$ext"; tail -3 "float-$ext.info"; }
  grep -q "^Vertices: *$vertices\$" "float-$ext.info" && grep -q "^Faces: *$triangles\$" "float-$ext.info" ||
    fail ".$ext read back: $(grep -E '^(Vertices|Faces)' "float-$ext.info" | tr -s ' \n' ' ')"
done
# OBJ and PLY by their specifications: counts, indices in range, and the same points as the glTF's
# bounds (OBJ y up as glTF; PLY z up: (x, y, z) = (x_gltf, -z_gltf, y_gltf)).
verdict=$(python3 - "$vertices" "$triangles" float-glb.info <<'PY'
import re, struct, sys
nv, nf = int(sys.argv[1]), int(sys.argv[2])
info = open(sys.argv[3]).read()
lo = [float(v) for v in re.search(r"Minimum point\s+\(([^)]*)\)", info).group(1).split()]
hi = [float(v) for v in re.search(r"Maximum point\s+\(([^)]*)\)", info).group(1).split()]
def obj():
    v, f = [], []
    for line in open("float.obj"):
        if line.startswith("v "): v.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "): f.append([int(x.split("/")[0]) - 1 for x in line.split()[1:]])
    return v, f
def ply():
    lines = open("float.ply").read().split("\n")
    assert lines[:2] == ["ply", "format ascii 1.0"], lines[:2]
    end = lines.index("end_header") + 1
    head = "\n".join(lines[:end])
    n = int(re.search(r"element vertex (\d+)", head).group(1)); m = int(re.search(r"element face (\d+)", head).group(1))
    v = [[float(x) for x in line.split()[:3]] for line in lines[end:end + n]]
    v = [[x, z, -y] for x, y, z in v]  # z up to glTF's y up
    f = [[int(x) for x in line.split()[1:]] for line in lines[end + n:end + n + m]]
    assert all(int(line.split()[0]) == 3 for line in lines[end + n:end + n + m]) and lines[end + n + m:] in ([], [""])
    return v, f
out = []
for name, (v, f) in (("obj", obj()), ("ply", ply())):
    ok = len(v) == nv and len(f) == nf and all(len(t) == 3 and 0 <= min(t) and max(t) < nv for t in f)
    vlo = [min(p[k] for p in v) for k in range(3)]; vhi = [max(p[k] for p in v) for k in range(3)]
    ok = ok and all(abs(a - b) < 1e-3 for a, b in zip(vlo + vhi, lo + hi))
    out.append(f"{name}: {len(v)} vertices, {len(f)} faces, {'ok' if ok else 'WRONG: %s %s' % (vlo, vhi)}")
print("; ".join(out))
PY
)
echo "read back: $verdict"
case "$verdict" in *WRONG*|"") fail "OBJ and PLY read back: $verdict" ;; esac

# A solid: the scene's block (STL always; --solid for the others) is closed and faces out.
"$relief" export dem.tif -o solid.stl "${sets[@]}" --set base.thickness_m=false 2> solid.txt || { fail "export .stl"; cat solid.txt; }
admesh solid.stl > solid.admesh 2>&1 || fail "admesh"
for line in "Number of parts *: *1 " "Total disconnected facets *: *0 *0" "Facets reversed *: *0" "Backwards edges *: *0" \
            "Normals fixed *: *0" "Degenerate facets *: *0"; do
  grep -qE "$line" solid.admesh || fail "the STL is not a closed solid facing out ($line): $(grep -E 'parts|disconnected facets|reversed|Backwards|Normals fixed' solid.admesh | tr -s ' \n' ' ')"
done
grep -qE "Volume *: *[1-9]" solid.admesh || fail "the solid's volume is not positive: $(grep Volume solid.admesh)"
"$relief" export dem.tif -o solid.glb "${sets[@]}" --set base.thickness_m=false --solid 2> solid-glb.txt ||
  { fail "export --solid"; cat solid-glb.txt; }
assimp info solid.glb 2>&1 | grep -qE "^Meshes: *3$" || fail "--solid: not a surface, walls and a floor"

# The same bytes under another name and on a second run, every format.
mkdir again
for ext in glb gltf obj ply; do
  "$relief" export -q dem.tif -o "again/other.$ext" "${sets[@]}" --set base.thickness_m=false || fail "export again .$ext"
  cmp -s "float.$ext" "again/other.$ext" || fail ".$ext: not the same bytes under another name"
done
"$relief" export -q dem.tif -o again/other.stl "${sets[@]}" --set base.thickness_m=false || fail "export again .stl"
cmp -s solid.stl again/other.stl || fail ".stl: not the same bytes under another name"

# --scale: the wider side that many millimetres; --max-triangles: met, the bound said.
"$relief" export dem.tif -o print.glb "${sets[@]}" --scale 150 --max-triangles 20000 2> print.txt || { fail "export --scale"; cat print.txt; }
grep -q "an adaptive mesh within [0-9.e+-]* m of the refined surface" print.txt || { fail "no bound said:"; cat print.txt; }
assimp info print.glb > print.info 2>&1
python3 - print.info <<'PY' || fail "--scale 150 --max-triangles 20000: $(grep -E '^(Faces|Minimum|Maximum)' print.info | tr -s ' \n' ' ')"
import re, sys
info = open(sys.argv[1]).read()
lo = [float(v) for v in re.search(r"Minimum point\s+\(([^)]*)\)", info).group(1).split()]
hi = [float(v) for v in re.search(r"Maximum point\s+\(([^)]*)\)", info).group(1).split()]
faces = int(re.search(r"^Faces:\s*(\d+)", info, re.M).group(1))
across = max(hi[0] - lo[0], hi[2] - lo[2])
print(f"scaled: {across:.4f} mm across, {faces} triangles")
sys.exit(0 if abs(across - 150) < 1e-3 and 10000 < faces <= 20000 else 1)
PY

# A draped map's colours, as the still's drape has them, not the ramp's few: the same terrain
# coloured by elevation has at most the palette's 256 colours.
for scene in castilla-y-leon-map castilla-y-leon; do
  "$relief" export -q "$src/scenes/$scene.toml" -o "$scene.ply" --set subdivision.depth=0 || fail "export $scene"
done
colours=$(python3 - castilla-y-leon-map.ply castilla-y-leon.ply <<'PY'
import sys
for name in sys.argv[1:]:
    lines = open(name).read().split("\n"); end = lines.index("end_header") + 1
    n = int(next(l for l in lines if l.startswith("element vertex")).split()[2])
    red = [l.split()[-1] for l in lines[:end] if l.startswith("property ") and "list" not in l].index("red")
    print(len({tuple(l.split()[red:red + 3]) for l in lines[end:end + n]}), end=" ")
PY
)
read -r draped ramp <<< "$colours"
echo "colours: $draped draped, $ramp by elevation"
[ "$draped" -gt 1000 ] && [ "$ramp" -le 256 ] || fail "the drape's colours: $draped draped, $ramp by elevation"

# net.unsupported = "fade": the model's colours washed out as the still's are (the share of the
# surface between two strips of samples less saturated than shown: all but those grey already).
cp "$src/scenes/data/volcano_samples_1000_seed20251124.csv" s.csv
{ head -1 s.csv; awk -F, 'NR > 1 && (($2 > -36.8734 && $2 < -36.8726) || ($2 > -36.8794 && $2 < -36.8786))' s.csv; } > strip.csv
for mode in show fade; do
  printf '[samples]\npath = "strip.csv"\n[net]\ngridding = "fit"\nrows = 17\ncols = 17\nunsupported = "%s"\n' $mode > strip-$mode.toml
  "$relief" export -q strip-$mode.toml -o strip-$mode.ply --set base.thickness_m=false || fail "export strip-$mode"
done
faded=$(python3 - strip-show.ply strip-fade.ply <<'PY'
import sys
def colours(name):
    lines = open(name).read().split("\n"); end = lines.index("end_header") + 1
    n = int(next(l for l in lines if l.startswith("element vertex")).split()[2])
    red = [l.split()[-1] for l in lines[:end] if l.startswith("property ") and "list" not in l].index("red")
    return [tuple(int(x) for x in l.split()[red:red + 3]) for l in lines[end:end + n]]
show, fade = colours(sys.argv[1]), colours(sys.argv[2])
saturation = lambda p: (max(p) - min(p)) / max(max(p), 1)
differ = [(a, b) for a, b in zip(show, fade) if a != b]
greyer = sum(saturation(b) < saturation(a) for a, b in differ)
print(f"{len(differ)} of {len(show)} vertices faded, {greyer} less saturated")
PY
)
echo "fade: $faded"
read -r differ _ all _ _ greyer _ <<< "$faded"
[ "${differ:-0}" -gt $((all / 10)) ] && [ "$greyer" -ge $((differ * 99 / 100)) ] || fail "net.unsupported = \"fade\" in the model: $faded"

# A format relief does not write: one line naming the file and the formats, exit 2, nothing written.
"$relief" export dem.tif -o model.3ds "${sets[@]}" 2> bad.txt; code=$?
[ $code -eq 2 ] || fail "an unknown format exits $code"
grep -q '^model.3ds: error: relief export writes `.glb`, `.gltf`, `.stl`, `.obj` or `.ply`' bad.txt || { fail "unknown format:"; cat bad.txt; }
[ ! -e model.3ds ] || fail "model.3ds written"
exit $status
