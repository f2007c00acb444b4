#!/usr/bin/env bash
# End-to-end test of `lumis compare` on 8x8 to 32x32 renders of the built-in scene: the files it writes, the report
# contents, what the pipeline computes (each variant its own integrator, the metrics of lumis diff, the convergence
# series, the default reference spp, a reference that lumis render reproduces from its key, equal time, --spp over a
# scene's time budget), reference caching (also per glTF camera and per file the scene reads, and the reason a cached
# reference is not reused), usage errors, and (when /usr/bin/chromium exists) that index.html's script runs in
# headless Chromium; options no variant uses are warned about.
# Usage: compare.sh path/to/lumis   (exit 77 = skipped)
set -uo pipefail
LUMIS=${1:?usage: compare.sh path/to/lumis}
source "$(dirname "$0")/common.bash"
need python3 python3  # reads report.json and writes the test scenes
SMALL=(--width 32 --height 32 --max-depth 2 --reference-spp 64)
VARIANTS=(uniform bsdf light mis nee_mis)

# Equal samples, all five variants, crops and convergence.
D="$T/eq"
expect 0 "$LUMIS" compare "$SCENE" "${SMALL[@]}" --spp 8 --crop 8,8,8,8 --convergence -o "$D"
grep -q "compare: wrote .*, montage.png, convergence.png$" "$T/err" || fail "wrote line: $(grep wrote "$T/err")"
for f in reference.exr reference.json reference.png montage.png convergence.png report.json report.md index.html; do
  [ -s "$D/$f" ] || fail "missing $f"
done
for v in "${VARIANTS[@]}"; do
  for f in "$v.exr" "$v.png" "error-$v.png"; do [ -s "$D/$f" ] || fail "missing $f"; done
  grep -q "^| $v | 8 |" "$D/report.md" || fail "report.md has no row for $v: $(cat "$D/report.md")"
  grep -q "\"name\": \"$v\"" "$D/report.json" || fail "report.json lacks $v"
done
grep -q "| variant | spp | time (s) | samples/s | rays/s | MSE | relMSE | efficiency |" "$D/report.md" || fail "table header"
grep -q '"convergence"' "$D/report.json" || fail "no convergence series"
grep -q '"source": "rendered"' "$D/report.json" || fail "reference not rendered"
grep -Eiq '(src|href)="(https?:)?//' "$D/index.html" && fail "index.html refers to an external resource"
# The variants are the integrators they are named after: five different images, and on this scene uniform's error
# is far above nee_mis's (deterministic: fixed seeds, the same image for any thread count).
for a in "${VARIANTS[@]}"; do
  for b in "${VARIANTS[@]}"; do
    [[ "$a" < "$b" ]] || continue
    expect 1 "$LUMIS" diff "$D/$a.exr" "$D/$b.exr" --threshold 0
  done
done
# Each variant's MSE, relMSE and MAE in report.json are lumis diff's against the reference (relMSE divides by the
# reference's values, not the variant's), and its convergence series ends at its own spp.
for v in "${VARIANTS[@]}"; do
  expect 0 "$LUMIS" diff "$D/$v.exr" "$D/reference.exr" --json
  cp "$T/out" "$T/diff-$v.json"
done
python3 - "$D/report.json" "$T" <<'PY' || fail "report.json's metrics or convergence series: $(cat "$D/report.json")"
import json, sys
report = json.load(open(sys.argv[1]))
rel = {}
for v in report["variants"]:
    d = json.load(open(f"{sys.argv[2]}/diff-{v['name']}.json"))
    for k in ("mse", "relmse", "mae"):
        assert abs(v[k] - d[k]) <= 1e-12 * abs(d[k]), (v["name"], k, v[k], d[k])
    rel[v["name"]] = v["relmse"]
    # --convergence: 1, 2, 4, 8 spp; the last point is the comparison's own render (same seed, same image).
    c = v["convergence"]
    assert [p["spp"] for p in c] == [1, 2, 4, 8], (v["name"], c)
    assert c[-1]["mse"] == v["mse"] and c[-1]["relmse"] == v["relmse"], (v["name"], c[-1], v)
assert rel["uniform"] > 2 * rel["nee_mis"], rel
assert sorted(report["reference"]) == ["hash", "png", "source", "spp"], report["reference"]  # a rendered one
PY

# The viewer's script runs: it marks the body ready and lists every variant plus the reference.
CHROMIUM=/usr/bin/chromium
if [ -x "$CHROMIUM" ]; then
  timeout 120 "$CHROMIUM" --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --disable-sync --no-first-run --user-data-dir="$T/chromium-profile" \
    --dump-dom "file://$D/index.html" >"$T/dom.html" 2>"$T/chromium.err" || fail "chromium: $(tail -5 "$T/chromium.err")"
  grep -q 'data-ready="1"' "$T/dom.html" || fail "index.html script did not run: $(head -c 2000 "$T/dom.html")"
  for v in "${VARIANTS[@]}" reference; do
    grep -q "<li data-variant=\"$v\"" "$T/dom.html" || fail "viewer lacks $v"
  done
  echo "compare.sh: index.html checked in headless Chromium"
else
  echo "compare.sh: $CHROMIUM not found, index.html not run in a browser"
fi
# Unchanged settings reuse the cached reference; a changed setting renders a new one. A convergence series ends at
# the variant's own spp also when that is not a power of two.
expect 0 "$LUMIS" compare "$SCENE" "${SMALL[@]}" --spp 5 --integrators mis --convergence -o "$D" -q
grep -q '"source": "cached"' "$D/report.json" || fail "reference not reused"
python3 - "$D/report.json" <<'PY' || fail "convergence series at 5 spp: $(cat "$D/report.json")"
import json, sys
v = json.load(open(sys.argv[1]))["variants"][0]
c = v["convergence"]
assert [p["spp"] for p in c] == [1, 2, 4, 5], c
assert c[-1]["mse"] == v["mse"], (c[-1], v)
PY
expect 0 "$LUMIS" compare "$SCENE" "${SMALL[@]}" --spp 4 --integrators mis --seed 3 -o "$D"
grep -q '"source": "rendered"' "$D/report.json" || fail "reference reused after the seed changed"
# The progress says why (the variants' seed, as --seed spells it, not the reference's own).
grep -qF "compare: not reusing the cached reference (settings changed: seed 0 -> 3)" "$T/err" ||
  fail "no reason for a new reference: $(cat "$T/err")"

# Equal time with a given reference file; an option that neither variant uses is named in a warning (also with -q).
expect 0 "$LUMIS" compare "$SCENE" --width 32 --height 32 --max-depth 2 --time 0.05 --integrators bsdf,light \
  --reference "$D/reference.exr" --reference-spp 32 --mis-light-probability 0.3 --light-selection power \
  -o "$T/time" -q --threads 1
grep -q '"mode": "equal-time"' "$T/time/report.json" || fail "equal-time mode"
grep -q "power light selection, balance MIS heuristic, 1 thread\.$" "$T/time/report.md" ||  # once "1 threads"
  fail "equal time's thread count: $(grep Settings "$T/time/report.md")"
grep -q '"time_budget": 0.05,' "$T/time/report.json" || fail "time budget not 0.05: $(grep time_budget "$T/time/report.json")"
grep -q "\"source\": \"$D/reference.exr\"" "$T/time/report.json" || fail "given reference not recorded"
REF_KEYS='import json, sys; r = json.load(open(sys.argv[1]))["reference"]
sys.exit(r != dict(r, channels=sys.argv[2]) or sorted(r) != ["channels", "png", "source"])'
python3 -c "$REF_KEYS" "$T/time/report.json" "R G B" ||
  fail "a given reference has a spp or hash, or no channels: $(grep -A4 '"reference"' "$T/time/report.json")"
grep -qF "warning: --mis-light-probability only affects the mis integrator; ignored for bsdf, light" "$T/err" ||
  fail "no warning for an option no variant uses: $(cat "$T/err")"
grep -q "light-selection" "$T/err" && fail "a warning for an option the light variant uses: $(cat "$T/err")"
grep -qF "warning: --reference-spp only affects a rendered reference; ignored with --reference" "$T/err" ||
  fail "no warning for --reference-spp beside --reference: $(cat "$T/err")"
# A grey reference (Y alone) is used as R = G = B, and the reports say so, as lumis diff does.
oiiotool "$D/reference.exr" --ch "Y=R" -o "$T/grey.exr" || fail "oiiotool: grey.exr"
expect 0 "$LUMIS" compare "$SCENE" --width 32 --height 32 --max-depth 2 --spp 1 --integrators bsdf \
  --reference "$T/grey.exr" -o "$T/grey" -q
python3 -c "$REF_KEYS" "$T/grey/report.json" "Y (as R, G, B)" ||
  fail "a grey reference's channels: $(grep -A4 '"reference"' "$T/grey/report.json")"
for f in report.md index.html; do
  grep -qF "reference: $T/grey.exr (grey: its Y is used as R, G and B)." "$T/grey/$f" || fail "$f: grey reference"
done
# A rendered reference is nee_mis with --mis-heuristic and --light-selection (they are in its key): no warning that
# they are ignored, though the one variant (bsdf) reads neither.
expect 0 "$LUMIS" compare "$SCENE" "${SMALL[@]}" --spp 2 --integrators bsdf --mis-heuristic power \
  --light-selection uniform -o "$T/bsdfref" -q
grep -q "warning" "$T/err" && fail "a warning for options the rendered reference uses: $(cat "$T/err")"

# Usage errors exit 2 and name the problem.
expect 2 "$LUMIS" compare "$SCENE" --integrators mis,photon -o "$T/bad"
grep -q "photon" "$T/err" || fail "unknown integrator message"
expect 2 "$LUMIS" compare "$SCENE" --width 32 --height 32 --crop 30,30,8,8 -o "$T/bad"
expect 2 "$LUMIS" compare "$SCENE" --width 16 --height 16 --reference "$D/reference.exr" -o "$T/bad"
grep -q "reference.exr" "$T/err" || fail "reference size message"

# --spp and --time together: no silent choice of one (equal samples or equal time), and no folder left behind.
expect 2 "$LUMIS" compare "$SCENE" --width 16 --height 16 --spp 1 --time 0.1 -o "$T/both"
grep -q "equal samples" "$T/err" || fail "--spp with --time message: $(cat "$T/err")"
[ ! -e "$T/both" ] || fail "--spp with --time created the output folder"
# Rejected inputs leave no empty output folder: a reference of the wrong size (2), a missing one (1).
[ ! -e "$T/bad" ] || fail "a rejected run left $T/bad behind"
expect 1 "$LUMIS" compare "$SCENE" --width 16 --height 16 --reference "$T/missing.exr" -o "$T/nofile"
grep -q "missing.exr" "$T/err" || fail "missing reference message: $(cat "$T/err")"
[ ! -e "$T/nofile" ] || fail "a missing reference left $T/nofile behind"
# -o naming a file (or a path through one) is a usage error with a plain message, not a C++ exception.
: >"$T/a.png"
expect 2 "$LUMIS" compare "$SCENE" --width 16 --height 16 --spp 1 -o "$T/a.png"
grep -q "a.png: exists and is not a folder" "$T/err" || fail "-o a file: $(cat "$T/err")"
grep -qi "filesystem error" "$T/err" && fail "raw exception: $(cat "$T/err")"
expect 2 "$LUMIS" compare "$SCENE" --width 16 --height 16 --spp 1 -o "$T/a.png/sub"
grep -q "a.png is not a folder" "$T/err" || fail "-o through a file: $(cat "$T/err")"
# A link there into a missing folder is refused up front too (a helper's finding: it failed after the renders).
mkdir -p "$T/link" && ln -s nodir/x.png "$T/link/bsdf.png"
expect 2 "$LUMIS" compare "$SCENE" --width 16 --height 16 --spp 1 --integrators bsdf -o "$T/link"
grep -qF "compare: -o $T/link: bsdf.png there links to $T/link/nodir/x.png, but the folder $T/link/nodir does not" \
  "$T/err" || fail "a link into a missing folder: $(cat "$T/err")"
[ ! -e "$T/link/reference.exr" ] || fail "rendered before refusing the link"
# A folder or a pipe where one of its files goes: refused up front (once it failed after every render).
mkdir -p "$T/slot/bsdf.png" "$T/pipe"
mkfifo "$T/pipe/reference.json"
expect 2 "$LUMIS" compare "$SCENE" --width 8 --height 8 --spp 1 --integrators bsdf -o "$T/slot"
grep -qF "compare: -o $T/slot: bsdf.png there is a folder, where this run writes a file" "$T/err" ||
  fail "a folder where a file goes: $(cat "$T/err")"
[ "$(ls -A "$T/slot")" = bsdf.png ] || fail "compare wrote beside the folder in its way: $(ls -A "$T/slot")"
expect 2 "$LUMIS" compare "$SCENE" --width 8 --height 8 --spp 1 --integrators bsdf -o "$T/pipe"
grep -qF "reference.json there is not a regular file (a pipe, device or socket)" "$T/err" ||
  fail "a pipe where a file goes: $(cat "$T/err")"

# --help: --integrator is not advertised (and still refused helpfully), --time and --spp are worded for compare.
expect 0 "$LUMIS" compare --help
grep -Eq -- '--integrator( |$)' "$T/out" && fail "--help advertises --integrator: $(cat "$T/out")"
grep -q -- "--integrators" "$T/out" || fail "--help lacks --integrators"
grep -A1 -- '^ *--time ' "$T/out" | grep -q "Equal time" || fail "--time help: $(grep -A1 -- --time "$T/out")"
grep -A1 -- '^ *--spp ' "$T/out" | grep -q "default: the scene's" || fail "--spp help: $(grep -A1 -- --spp "$T/out")"
expect 2 "$LUMIS" compare "$SCENE" --integrator mis -o "$T/refused"
grep -q "use --integrators" "$T/err" || fail "--integrator refusal: $(cat "$T/err")"

# report.json's settings.
grep -q '"settings"' "$D/report.json" || fail "report.json has no settings"
grep -q '"max_depth": 2' "$D/report.json" || fail "settings lack max_depth"
grep -q '^Settings: max depth 2' "$D/report.md" || fail "report.md lacks the settings line"

# Without --reference-spp the reference takes 16x the variants' samples (at least 256), and lumis render reproduces
# it exactly from reference.json's key: nee_mis at that spp with the key's seed (not the variants' seed).
expect 0 "$LUMIS" compare "$SCENE" --width 32 --height 32 --max-depth 2 --spp 32 --integrators nee_mis -o "$T/ref" -q
key=$(python3 -c 'import json, sys; k = json.load(open(sys.argv[1]))["key"]; print(k["spp"], k["seed"])' \
  "$T/ref/reference.json") || fail "reference.json: $(cat "$T/ref/reference.json")"
read -r ref_spp ref_seed <<<"$key"
[ "$ref_spp" = 512 ] || fail "reference spp $ref_spp for --spp 32, expected 16 x 32"
grep -q '"spp": 512' "$T/ref/report.json" || fail "report.json's reference spp: $(cat "$T/ref/report.json")"
[ "$ref_seed" != 0 ] || fail "the reference shares the variants' seed 0"
expect 0 "$LUMIS" render "$SCENE" --width 32 --height 32 --max-depth 2 --integrator nee_mis --spp "$ref_spp" \
  --seed "$ref_seed" -q -o "$T/ref/again.exr"
expect 0 "$LUMIS" diff "$T/ref/again.exr" "$T/ref/reference.exr" --threshold 0

# Equal time renders each variant until the budget ends, not only the scene's spp (1 here: 64 samples in 0.25 s is
# a thousandth of the speed), and --spp overrides a time budget in the scene file (equal samples).
python3 -c '
import json, sys
s = json.load(open(sys.argv[1]))
s["render"]["spp"] = 1
json.dump(s, open(sys.argv[2], "w"))
s["render"]["time"] = 5
json.dump(s, open(sys.argv[3], "w"))
' "$SCENE" "$T/spp1.json" "$T/timed.json"
expect 0 "$LUMIS" compare "$T/spp1.json" --width 8 --height 8 --max-depth 1 --time 0.25 --integrators bsdf,nee_mis \
  --reference-spp 16 -o "$T/et" -q
grep -qF "warning: bsdf rendered" "$T/err" &&
  grep -qF "more than the reference's 16: its error is partly the reference's noise; raise --reference-spp" "$T/err" ||
  fail "no warning for variants with more samples than the reference: $(cat "$T/err")"
# A variant that takes the most samples a timed render asks for before its time is up did not get equal time: said.
# One pixel whose camera ray misses everything: 2^20 samples in about 2 s, against a budget of 60.
cat > "$T/miss.json" <<'EOF2'
{"version": 1, "camera": {"type": "perspective", "from": [0, 0, 0], "to": [0, 0, -1], "fov": 1},
 "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
 "shapes": [{"type": "quad", "origin": [-1, -1, 5], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0], "material": "grey"}]}
EOF2
expect 0 "$LUMIS" compare "$T/miss.json" --width 1 --height 1 --time 60 --integrators bsdf --reference-spp 1 \
  -o "$T/cap" -q
grep -qF "warning: bsdf reached 1048576 spp, the most a timed render takes, in " "$T/err" &&
  grep -qF "s of the 60 s budget: not equal time" "$T/err" || fail "no warning at the timed spp cap: $(cat "$T/err")"
# lumis render says the same (here, rather than in outputs.sh, which also runs under AddressSanitizer).
expect 0 "$LUMIS" render "$T/miss.json" --width 1 --height 1 --time 60 -q -o "$T/cap.exr"
grep -qF "warning: stopped at 1048576 spp, the most a timed render takes, after " "$T/err" ||
  fail "render: no warning at the timed spp cap: $(cat "$T/err")"
expect 0 "$LUMIS" compare "$T/timed.json" --width 8 --height 8 --max-depth 1 --spp 2 --integrators bsdf \
  --reference-spp 4 -o "$T/timed" -q
python3 -c '
import json, sys
et, timed = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert et["mode"] == "equal-time", et["mode"]
for v in et["variants"]:
    assert v["spp"] > 1 and v["seconds"] >= 0.2, ("--time 0.25", v["name"], v["spp"], v["seconds"])
assert timed["mode"] == "equal-spp", ("--spp 2 over the scene time", timed["mode"])
assert [v["spp"] for v in timed["variants"]] == [2], ("--spp 2 over the scene time", timed["variants"])
' "$T/et/report.json" "$T/timed/report.json" || fail "equal time, or --spp over the scene's time budget"
# ... and so does render's --spp: the reference of a scene with a time budget that would end a render after its first
# pass is still reproduced by lumis render from reference.json's key (render --spp once kept the scene's budget).
python3 -c '
import json, sys
s = json.load(open(sys.argv[1]))
s["render"]["time"] = 1e-6
json.dump(s, open(sys.argv[2], "w"))
' "$SCENE" "$T/instant.json"
expect 0 "$LUMIS" compare "$T/instant.json" --width 8 --height 8 --max-depth 1 --spp 2 --integrators bsdf \
  --reference-spp 8 -o "$T/instant" -q
ref_seed=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["key"]["seed"])' "$T/instant/reference.json")
expect 0 "$LUMIS" render "$T/instant.json" --width 8 --height 8 --max-depth 1 --integrator nee_mis --spp 8 \
  --seed "$ref_seed" -q -o "$T/instant/again.exr"
expect 0 "$LUMIS" diff "$T/instant/again.exr" "$T/instant/reference.exr" --threshold 0

# The cached reference belongs to one camera of a glTF file: another --camera renders a new one, and reference.json's
# key names it (for `lumis render --camera`).
python3 - "$T/cams.gltf" <<'PY'
import base64, json, struct, sys
data = struct.pack("<9f", -1, -1, -2, 1, -1, -2, 0, 1, -2)
gltf = {
    "asset": {"version": "2.0"},
    "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": [{"buffer": 0, "byteLength": len(data)}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [-1, -1, -2], "max": [1, 1, -2]}],
    "materials": [{"emissiveFactor": [1, 1, 1]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}},
                {"name": "Lens", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}}],
    "nodes": [{"mesh": 0}, {"camera": 0}, {"name": "Side", "camera": 1, "translation": [0.5, 0, 0]}],
    "scenes": [{"nodes": [0, 1, 2]}],
    "scene": 0,
}
json.dump(gltf, open(sys.argv[1], "w"))
PY
CAM=(--width 8 --height 8 --spp 1 --reference-spp 4 --integrators nee_mis -o "$T/cams" -q)
expect 0 "$LUMIS" compare "$T/cams.gltf" "${CAM[@]}" --camera 0
expect 0 "$LUMIS" compare "$T/cams.gltf" --width 8 --height 8 --spp 1 --reference-spp 4 --integrators nee_mis \
  -o "$T/cams" --camera 1
grep -q '"source": "rendered"' "$T/cams/report.json" || fail "reference reused for another camera"
grep -qF "compare: not reusing the cached reference (the camera changed)" "$T/err" ||
  fail "no reason for another camera's reference: $(cat "$T/err")"
expect 0 "$LUMIS" compare "$T/cams.gltf" "${CAM[@]}" --camera 1
grep -q '"source": "cached"' "$T/cams/report.json" || fail "reference not reused for the same camera"
grep -q '"camera": "1"' "$T/cams/reference.json" ||
  fail "reference.json's key lacks the camera: $(cat "$T/cams/reference.json")"
# The same camera by its node's name or its camera's name: the cache is the camera's, not its spelling's.
for name in Side Lens; do
  expect 0 "$LUMIS" compare "$T/cams.gltf" "${CAM[@]}" --camera "$name"
  grep -q '"source": "cached"' "$T/cams/report.json" || fail "reference not reused for camera 1 named $name"
done

# The cached reference also belongs to the files the scene reads: a JSON scene's included glTF file, a glTF file's
# buffer and its texture. Changing any one renders a new reference; the same bytes reuse it, wherever they are.
mkdir "$T/inputs"
python3 - "$T/inputs" <<'PY' || fail "could not write the scenes with inputs"
import json, struct, sys
d = sys.argv[1]
data = struct.pack("<9f", -1, -1, -2, 1, -1, -2, 0, 1, -2) + struct.pack("<6f", 0, 0, 1, 0, 0, 1)
open(d + "/tri.bin", "wb").write(data)
gltf = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 1]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.2, "znear": 0.01}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}], "images": [{"uri": "tex.png"}],
        "buffers": [{"byteLength": len(data), "uri": "tri.bin"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [-1, -1, -2], "max": [1, 1, -2]},
                      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]}
json.dump(gltf, open(d + "/tri.gltf", "w"))
json.dump({"shapes": [{"type": "gltf", "file": "tri.gltf"}], "camera": {"from": [0, 0, 1], "to": [0, 0, -2]},
           "lights": [{"type": "environment", "radiance": [1, 1, 1]}]}, open(d + "/inc.json", "w"))
PY
oiiotool --pattern constant:color=0.2,0.4,0.6 4x4 3 -d uint8 -o "$T/inputs/tex.png" ||
  fail "oiiotool could not write the texture"
IN=(--width 8 --height 8 --spp 1 --reference-spp 4 --integrators nee_mis)
source_is() {  # source_is SCENE OUT rendered|cached WHY: compare SCENE into OUT; the reference must be WHY's source
  expect 0 "$LUMIS" compare "$1" "${IN[@]}" -q -o "$2"
  grep -q "\"source\": \"$3\"" "$2/report.json" || fail "$4: $(grep -A3 '"reference"' "$2/report.json")"
}
rendered_for() {  # rendered_for SCENE OUT REASON: a new reference, and the progress gives REASON for it
  expect 0 "$LUMIS" compare "$1" "${IN[@]}" -o "$2"
  grep -q '"source": "rendered"' "$2/report.json" || fail "$1: reference reused ($3)"
  grep -qF "compare: not reusing the cached reference ($3)" "$T/err" || fail "$1: not '$3': $(cat "$T/err")"
}
for scene in inc.json tri.gltf; do
  source_is "$T/inputs/$scene" "$T/in-$scene" rendered "$scene: first run"
  source_is "$T/inputs/$scene" "$T/in-$scene" cached "$scene: reference not reused"
done
oiiotool --pattern constant:color=0.6,0.4,0.2 4x4 3 -d uint8 -o "$T/inputs/tex.png" ||
  fail "oiiotool could not rewrite the texture"
python3 - "$T/inputs" <<'PY' || fail "could not rewrite tri.bin"
import struct, sys
d = sys.argv[1]
data = bytearray(open(d + "/tri.bin", "rb").read())
data[0:4] = struct.pack("<f", -0.5)  # the first vertex moves; byteLength is unchanged
open(d + "/tri.bin.new", "wb").write(data)
PY
# Each new reference names what changed, in the progress on stderr.
for scene in inc.json tri.gltf; do rendered_for "$T/inputs/$scene" "$T/in-$scene" "changed: $T/inputs/tex.png"; done
mv "$T/inputs/tri.bin.new" "$T/inputs/tri.bin"
for scene in inc.json tri.gltf; do rendered_for "$T/inputs/$scene" "$T/in-$scene" "changed: $T/inputs/tri.bin"; done
printf ' ' >> "$T/inputs/tri.gltf"  # the included glTF file's own bytes
rendered_for "$T/inputs/inc.json" "$T/in-inc.json" "changed: $T/inputs/tri.gltf"
rendered_for "$T/inputs/tri.gltf" "$T/in-tri.gltf" "the scene file changed"
# reference.json lists each file the scene reads once, with its hash: here a glTF file included twice.
python3 - "$T/inputs" <<'PY' || fail "could not write twice.json"
import json, sys
d = sys.argv[1]
json.dump({"shapes": [{"type": "gltf", "file": "tri.gltf"}, {"type": "gltf", "file": "tri.gltf"}],
           "camera": {"from": [0, 0, 1], "to": [0, 0, -2]}}, open(d + "/twice.json", "w"))
PY
source_is "$T/inputs/twice.json" "$T/twice" rendered "twice.json: first run"
R="$T/twice/reference.json"
python3 - "$T/inputs" "$R" <<'PY' || fail "reference.json's inputs: $(cat "$R")"
import json, sys
d, j = sys.argv[1], json.load(open(sys.argv[2]))
assert [i["file"] for i in j["inputs"]] == [d + "/tri.gltf", d + "/tri.bin", d + "/tex.png"], j["inputs"]
assert all(len(i["fnv1a"]) == 16 for i in j["inputs"]) and len(j["scene_fnv1a"]) == 16, j
PY
# The same bytes in another folder (the project moved) reuse the reference; with a file changed there, the reason
# lists the files by their new and old paths, three of them and a count.
cp -r "$T/inputs" "$T/moved"
source_is "$T/moved/inc.json" "$T/in-inc.json" cached "inc.json: reference not reused after the project moved"
printf ' ' >> "$T/moved/tri.gltf"
rendered_for "$T/moved/inc.json" "$T/in-inc.json" "changed: $T/moved/tri.gltf (new), $T/moved/tri.bin (new), \
$T/moved/tex.png (new) and 3 more"
# A reference.json written before lumis recorded the scene's files: the settings are all it can tell apart.
python3 - "$T/in-inc.json/reference.json" <<'PY' || fail "could not age reference.json"
import json, sys
j = json.load(open(sys.argv[1]))
del j["scene_fnv1a"], j["inputs"]
j["hash"] = "0123456789abcdef"
json.dump(j, open(sys.argv[1], "w"))
PY
rendered_for "$T/moved/inc.json" "$T/in-inc.json" "cached by an older lumis, which did not record the scene's files"

# A run that fails part way leaves no report of the earlier run beside images it replaced: the report goes first.
SMALL8=(--width 8 --height 8 --spp 1 --reference-spp 4 --integrators bsdf,nee_mis -q)
expect 0 "$LUMIS" compare "$T/cams.gltf" "${SMALL8[@]}" -o "$T/rerun"
# The variants' pictures cannot all be written now: a file-size limit of 1 KiB lets the reference's small PNG through
# and stops a variant's (a folder in its place, or a link into a missing folder, is refused up front).
(trap '' XFSZ; ulimit -f 1 && exec "$LUMIS" compare "$T/cams.gltf" "${SMALL8[@]}" -o "$T/rerun") 2>"$T/err"
code=$?
[ "$code" = 1 ] || fail "a rerun under a file-size limit exited $code, expected 1: $(cat "$T/err")"
grep -qE "/rerun/(error-)?(bsdf|nee_mis)\.(exr|png): cannot write" "$T/err" ||
  fail "the rerun did not fail at a variant's picture: $(cat "$T/err")"
for f in report.json report.md index.html; do [ ! -e "$T/rerun/$f" ] || fail "a failed rerun left the old $f"; done
[ -s "$T/rerun/reference.exr" ] || fail "a failed rerun removed the cached reference"

# A run that fails (here: a file-size limit of 0 stops its first write, the reference's) removes the folders it
# created and left empty, parents included: -o new/deeper/out once left new/deeper behind.
(trap '' XFSZ; ulimit -f 0 && exec "$LUMIS" compare "$T/cams.gltf" "${SMALL8[@]}" -o "$T/new/deeper/out") 2>"$T/err"
code=$?
[ "$code" = 1 ] || fail "compare under a file-size limit of 0 exited $code, expected 1: $(cat "$T/err")"
[ ! -e "$T/new" ] || fail "a failed compare left the folders it created: $(find "$T/new" | tr '\n' ' ')"

# A given reference that this run would overwrite (bsdf's image in the output folder) is refused before any work.
cp "$T/rerun/bsdf.exr" "$T/bsdf-before.exr"
expect 2 "$LUMIS" compare "$T/cams.gltf" "${SMALL8[@]}" -o "$T/rerun" --reference "$T/rerun/bsdf.exr"
grep -qF "is the bsdf.exr this run writes in $T/rerun" "$T/err" || fail "reference in -o: $(cat "$T/err")"
cmp -s "$T/bsdf-before.exr" "$T/rerun/bsdf.exr" || fail "the given reference was overwritten"

# Nor may a file the run writes in DIR be the scene file or a file the scene reads (also through a link): the scene
# file named report.json in DIR, a texture linked as nee_mis.png, a glTF buffer linked as reference.exr. Each is
# refused before DIR is touched, and left as it was.
cp -r "$T/inputs" "$T/self" && mv "$T/self/inc.json" "$T/self/report.json"
mkdir "$T/link-tex" "$T/link-bin"
ln -s "$T/inputs/tex.png" "$T/link-tex/nee_mis.png"
ln -s "$T/inputs/tri.bin" "$T/link-bin/reference.exr"
cp "$T/inputs/tex.png" "$T/tex-before.png" && cp "$T/inputs/tri.bin" "$T/bin-before.bin" &&
  cp "$T/self/report.json" "$T/scene-before.json" || fail "could not copy the inputs"
expect 2 "$LUMIS" compare "$T/self/report.json" "${IN[@]}" -o "$T/self"
grep -qF "this run writes report.json there, which is the scene file ($T/self/report.json)" "$T/err" ||
  fail "scene file in -o: $(cat "$T/err")"
expect 2 "$LUMIS" compare "$T/inputs/inc.json" "${IN[@]}" -o "$T/link-tex"
grep -qF "writes nee_mis.png there, which is a file the scene reads ($T/inputs/tex.png)" "$T/err" ||
  fail "texture in -o: $(cat "$T/err")"
expect 2 "$LUMIS" compare "$T/inputs/tri.gltf" "${IN[@]}" -o "$T/link-bin"
grep -qF "writes reference.exr there, which is a file the scene reads ($T/inputs/tri.bin)" "$T/err" ||
  fail "buffer in -o: $(cat "$T/err")"
cmp -s "$T/self/report.json" "$T/scene-before.json" && cmp -s "$T/inputs/tex.png" "$T/tex-before.png" &&
  cmp -s "$T/inputs/tri.bin" "$T/bin-before.bin" || fail "compare changed a file the scene reads"

# An output folder that cannot be written in fails before the reference is rendered (not as root, who can write).
mkdir "$T/readonly" && chmod a-w "$T/readonly"
if ! touch "$T/readonly/probe" 2>/dev/null; then
  expect 1 "$LUMIS" compare "$T/cams.gltf" "${SMALL8[@]}" -o "$T/readonly" --reference-spp 1000000
  grep -qF "$T/readonly: cannot write in this folder" "$T/err" || fail "read-only -o: $(cat "$T/err")"
fi
chmod u+w "$T/readonly"

echo "compare.sh: all checks passed"
