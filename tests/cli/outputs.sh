#!/usr/bin/env bash
# Where an output cannot be written, lumis says so before doing any work (render, diff's heatmap, bench's JSON and scene
# list), naming the path given and not a temporary one; options that cannot take effect are refused (AOVs in a PNG) or
# named in a warning (--mis-light-probability without the mis integrator); command-line errors start with "lumis: " and
# give the accepted range; --uniform-measure takes the scene file's spelling too; --width or --height alone keeps the
# aspect ratio; --camera is refused for a JSON scene; diff compares grey images; an empty file name is a usage error; -o
# may not name the scene file or a file it reads, nor bench --json the scene file or a file it reads; a write cut short
# (a file-size limit standing in for a full disk) fails render, diff and compare without a short file, and output lost
# on stdout is an error too.
# Usage: outputs.sh path/to/lumis   (exit 77 = skipped)
set -uo pipefail
LUMIS=${1:?usage: outputs.sh path/to/lumis}
source "$(dirname "$0")/common.bash"
has() { grep -qF -- "$1" "$T/err" || { cat "$T/err"; fail "stderr lacks '$1'"; }; }
lacks() { ! grep -qF -- "$1" "$T/err" || { cat "$T/err"; fail "stderr has '$1'"; }; }

# A render that would take hours if it started: each case must fail at once, without a temporary file.
LONG=(render "$SCENE" --width 64 --height 64 --spp 100000000 -q)
quick() {  # quick CODE CMD...: as expect, within 20 s (rendering first would take far longer)
  local want=$1; shift
  timeout 20 "$@" >"$T/out" 2>"$T/err"
  local got=$?
  [ "$got" != 124 ] || fail "still working after 20 s instead of failing at once: $*"
  [ "$got" = "$want" ] || { cat "$T/out" "$T/err"; fail "exit $got, expected $want: $*"; }
}
quick 2 "$LUMIS" "${LONG[@]}" -o "$T/no-such-folder/out.png"
has "lumis: $T/no-such-folder/out.png: the folder $T/no-such-folder does not exist"
grep -qF ".tmp-" "$T/err" && fail "the message names a temporary file: $(cat "$T/err")"
# A name longer than the file system allows is refused up front (it failed after the render); the longest it allows
# is written, though NAME.tmp-PID is longer still (once "File name too long", after the render, for 248 bytes).
MAXNAME=$(getconf NAME_MAX "$T")
LONGNAME=$(printf 'n%.0s' $(seq $((MAXNAME - 4))))  # with .png: the longest name
quick 2 "$LUMIS" "${LONG[@]}" -o "$T/${LONGNAME}x.png"
has "lumis: $T/${LONGNAME}x.png: the file name is $((MAXNAME + 1)) bytes long, more than the $MAXNAME its folder's file"
expect 0 "$LUMIS" render "$SCENE" --width 4 --height 4 --spp 1 -q -o "$T/$LONGNAME.png"
[ -s "$T/$LONGNAME.png" ] || fail "the longest name was not written"
[ -z "$(ls "$T" | grep -F .tmp-)" ] || fail "a temporary file was left: $(ls "$T" | grep -F .tmp-)"
rm "$T/$LONGNAME.png"
# A path the system takes, but whose temporary name (24 bytes longer) it would not: refused up front (it failed after
# the render with "File name too long").
DEEP=$T/$(printf 'd%.0s' $(seq 200))
for _ in $(seq 19); do DEEP=$DEEP/$(printf 'd%.0s' $(seq 200)); done
mkdir -p "$DEEP"
DEEPFILE=$DEEP/$(printf 'f%.0s' $(seq $((4090 - ${#DEEP} - 5)))).png
quick 2 "$LUMIS" "${LONG[@]}" -o "$DEEPFILE"
has "bytes long; lumis writes at most 4071 (the system takes 4095, and the file is first written under a temporary"
# An empty file or camera name (an unset shell variable) is a usage error, not "not given": it rendered the default
# scene, or wrote <scene name>.png in the current folder over whatever was there.
mkdir "$T/cwd"
for args in "render|" "render|$SCENE|-o|" "render|$SCENE|--camera|" "compare|" "compare|$SCENE|-o|" \
    "compare|$SCENE|--reference|" "diff||$T/b.exr" "diff|$T/a.exr|$T/b.exr|--heatmap|" "bench|" "bench|--json|"; do
  IFS='|' read -r -a argv <<< "$args|"
  (cd "$T/cwd" && quick 2 "$LUMIS" "${argv[@]}" --spp 1) || exit 1
  has "found an empty string"
done
[ -z "$(ls -A "$T/cwd")" ] || fail "an empty name wrote $(ls -A "$T/cwd")"
mkdir "$T/dir"
quick 2 "$LUMIS" "${LONG[@]}" -o "$T/dir"
has "$T/dir: is a folder; give a file name, e.g. $T/dir/out.png"
touch "$T/file"
quick 2 "$LUMIS" "${LONG[@]}" -o "$T/file/out.png"
has "$T/file is not a folder"
# A pipe (or device) as the output is refused, not replaced by a file (as root, `--json /dev/null` replaced
# /dev/null), and so is the bench's room into a missing folder.
mkfifo "$T/fifo.png"
quick 2 "$LUMIS" "${LONG[@]}" -o "$T/fifo.png"
has "$T/fifo.png: is not a regular file (a pipe, device or socket)"
[ -p "$T/fifo.png" ] || fail "the pipe $T/fifo.png was replaced"
rm -f "$T/fifo.png"
quick 2 "$LUMIS" bench --write-large-scene "$T/no-such-folder/room.glb"
has "the folder $T/no-such-folder does not exist"
[ -z "$(ls -A "$T/dir")" ] || fail "files left in $T/dir: $(ls -A "$T/dir")"
# -o through a symbolic link is checked where the link leads (the render is written there): a link into a missing
# folder once passed this check and failed only after the whole render; a loop of links fails too.
ln -s ../no-such-folder/x.png "$T/dir/latest.png"
quick 2 "$LUMIS" "${LONG[@]}" -o "$T/dir/latest.png"
has "$T/dir/latest.png: links to $T/dir/../no-such-folder/x.png, but the folder $T/dir/../no-such-folder does not exist"
ln -s loop-b "$T/loop-a" && ln -s loop-a "$T/loop-b"
quick 2 "$LUMIS" "${LONG[@]}" -o "$T/loop-a"
has "$T/loop-a: is a loop of symbolic links"
rm "$T/dir/latest.png"

# AOV channels exist only in EXR files: asked for with a PNG, a usage error before rendering.
quick 2 "$LUMIS" "${LONG[@]}" --aov-normal -o "$T/aov.png"
has "aov.png: --aov-normal adds EXR channels; write an .exr to keep them"   # the flag given, not all three
quick 2 "$LUMIS" "${LONG[@]}" --aov-depth --aov-albedo -o "$T/aov.png"
has "aov.png: --aov-albedo and --aov-depth add EXR channels"
[ ! -e "$T/aov.png" ] || fail "aov.png written"

# Options the chosen integrator does not use: rendered, with a warning that says so (also with -q).
R=(render "$SCENE" --width 8 --height 8 --spp 1 -q)
expect 0 "$LUMIS" "${R[@]}" --mis-light-probability 0.3 -o "$T/w.png"
has "warning: --mis-light-probability only affects the mis integrator; ignored for nee_mis"
expect 0 "$LUMIS" "${R[@]}" --integrator bsdf --uniform-measure solid-angle --light-selection power -o "$T/w.png"
has "--uniform-measure only affects the uniform integrator; ignored for bsdf"
has "--light-selection only affects light, mis and nee_mis; ignored for bsdf"
expect 0 "$LUMIS" "${R[@]}" --integrator mis --mis-light-probability 0.3 -o "$T/w.png"
[ ! -s "$T/err" ] || fail "a warning for options that apply: $(cat "$T/err")"

# --width or --height alone keeps the scene's aspect ratio (cornell-sphere is 512 x 512).
need iinfo openimageio-tools
expect 0 "$LUMIS" render "$SCENE" --width 24 --spp 1 -q -o "$T/aspect.png"
iinfo "$T/aspect.png" | grep -Eq " 24 x +24," || fail "--width 24 alone: $(iinfo "$T/aspect.png")"
expect 0 "$LUMIS" render "$SCENE" --height 20 --spp 1 -q -o "$T/aspect.png"
iinfo "$T/aspect.png" | grep -Eq " 20 x +20," || fail "--height 20 alone: $(iinfo "$T/aspect.png")"
expect 0 "$LUMIS" render "$SCENE" --width 24 --height 8 --spp 1 -q -o "$T/aspect.png"
iinfo "$T/aspect.png" | grep -Eq " 24 x +8," || fail "--width 24 --height 8: $(iinfo "$T/aspect.png")"

# --camera chooses among a glTF file's cameras; an unknown one lists them, and a JSON scene has none to choose.
expect 2 "$LUMIS" "${R[@]}" --camera 1 -o "$T/c.png"
has "--camera chooses among a glTF file's cameras"

# The scene file's spelling of a measure works on the command line too.
expect 0 "$LUMIS" "${R[@]}" --integrator uniform --uniform-measure solid_angle -o "$T/w.png"

# Command-line errors: prefixed like every other message, with the range that is accepted.
expect 2 "$LUMIS" "${R[@]}" --seed 4294967296 -o "$T/s.png"
has "lumis: --seed: expected a whole number in [0, 4294967295], found 4294967296"
expect 2 "$LUMIS" "${R[@]}" --spp 0 -o "$T/s.png"
has "lumis: --spp"
expect 0 "$LUMIS" "${R[@]}" --seed 4294967295 -o "$T/s.png"

# diff: the heatmap's folder is checked before the images are read; ranges are stated as accepted.
expect 0 "$LUMIS" "${R[@]}" -o "$T/a.png"
expect 2 "$LUMIS" diff "$T/a.png" "$T/a.png" --heatmap "$T/no-such-folder/heat.png"
has "the folder $T/no-such-folder does not exist"
expect 2 "$LUMIS" diff "$T/a.png" "$T/a.png" --alpha 0
has "expected a significance level in [1e-12, 0.5], found 0"
expect 2 "$LUMIS" diff "$T/a.png" "$T/a.png" --tolerance -1
has "--tolerance: expected a number >= 0, found -1"
# A grey image (one channel, Y) compares as R = G = B.
need oiiotool openimageio-tools
oiiotool "$T/a.png" --ch "Y=R" -o "$T/grey.png" || fail "oiiotool could not write a grey PNG"
expect 0 "$LUMIS" diff "$T/grey.png" "$T/grey.png" --threshold 0
expect 1 "$LUMIS" diff "$T/grey.png" "$T/a.png" --metric maxabs --threshold 0

# A write cut short (a full disk; here a file-size limit, `ulimit -f`, which fails writes the same way) is an error
# naming the file, exit 1, and leaves neither a short file under the final name nor a temporary one: a PNG render
# once exited 0 with a truncated file, and a JPEG left its temporary file after libjpeg ended the process.
limited() {  # limited CODE CMD...: as expect, with files limited to 8 KiB
  local want=$1; shift
  ( ulimit -f 8; "$@" ) >"$T/out" 2>"$T/err"
  local got=$?
  [ "$got" = "$want" ] || { cat "$T/out" "$T/err"; fail "exit $got, expected $want with a file-size limit: $*"; }
}
mkdir "$T/full"
for ext in png jpg exr; do
  limited 1 "$LUMIS" render "$SCENE" --width 96 --spp 2 -q -o "$T/full/r.$ext"
  has "lumis: $T/full/r.$ext: cannot write: File too large (after 8192 of "
done
expect 0 "$LUMIS" render "$SCENE" --width 96 --spp 1 --seed 1 -q -o "$T/n1.exr"
expect 0 "$LUMIS" render "$SCENE" --width 96 --spp 1 --seed 2 -q -o "$T/n2.exr"
limited 2 "$LUMIS" diff "$T/n1.exr" "$T/n2.exr" --heatmap "$T/full/heat.png"  # diff's errors exit 2
has "lumis diff: $T/full/heat.png: cannot write: File too large"
limited 1 "$LUMIS" compare "$SCENE" --width 64 --spp 1 --reference-spp 2 --integrators bsdf,nee_mis -o "$T/full/cmp"
has "cannot write: File too large"
leftover=$(find "$T/full" -type f \( -size 8192c -o -name '*tmp-*' \))
[ -z "$leftover" ] || fail "a write cut short left files behind: $leftover"
# The same for what goes to stdout (diff --json > metrics.json on a full disk): an error, not a silent success.
if [ -w /dev/full ]; then
  "$LUMIS" diff "$T/n1.exr" "$T/n1.exr" --json >/dev/full 2>"$T/err"
  got=$?
  [ "$got" = 2 ] || { cat "$T/err"; fail "diff --json to a full disk: exit $got, expected 2"; }
  has "lumis: cannot write the standard output: No space left on device"
  # --help too: its text is the output asked for (exit 1; diff's 2, since its 1 means the images differ).
  for cmd in "" render compare bench warptest diff; do
    "$LUMIS" $cmd --help >/dev/full 2>"$T/err"
    got=$?
    want=1
    [ "$cmd" = diff ] && want=2
    [ "$got" = "$want" ] || { cat "$T/err"; fail "lumis $cmd --help to a full disk: exit $got, expected $want"; }
    has "lumis: cannot write the standard output: No space left on device"
  done
fi

# bench: a scene that is not there fails the run before anything is measured, without printing empty tables.
quick 1 "$LUMIS" bench "$SCENE" "$T/no-such-scene.json"
has "$T/no-such-scene.json: file not found"
[ ! -s "$T/out" ] || fail "bench printed a report: $(cat "$T/out")"
quick 2 "$LUMIS" bench "$SCENE" --json "$T/no-such-folder/b.json"
has "the folder $T/no-such-folder does not exist"
# -o naming a file the scene reads (its environment map, a texture of the scene or of a glTF file it loads, or of a
# glTF file rendered directly, a glTF buffer named like an image) or the scene file itself (also through a link) is
# refused before rendering, and the file is left as it was: a render once replaced the scene's environment map.
mkdir "$T/own"
need python3 python3
python3 - "$T/own" <<'PY' || fail "could not write the scenes that read images"
import base64, json, struct, sys
d = sys.argv[1]
mat = {"m": {"type": "diffuse"}}
sphere = {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}
json.dump({"materials": mat, "shapes": [sphere], "lights": [{"type": "environment", "file": "env.exr"}]},
          open(d + "/env.json", "w"))
json.dump({"materials": {"m": {"type": "diffuse", "texture": "tex.png"}}, "shapes": [sphere],
           "lights": [{"type": "environment", "radiance": [1, 1, 1]}]}, open(d + "/tex.json", "w"))
pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<6f", 0, 0, 1, 0, 0, 1)
gltf = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}], "images": [{"uri": "gtex.png"}],
        "buffers": [{"byteLength": len(pos), "uri": "data:application/octet-stream;base64," +
                     base64.b64encode(pos).decode()}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]}
json.dump(gltf, open(d + "/tri.gltf", "w"))
json.dump({"materials": mat, "shapes": [{"type": "gltf", "file": "tri.gltf"}],
           "lights": [{"type": "environment", "radiance": [1, 1, 1]}]}, open(d + "/inc.json", "w"))
open(d + "/buf.png", "wb").write(pos)  # an external buffer named like an image
gltf["buffers"][0]["uri"] = "buf.png"
json.dump(gltf, open(d + "/ext.gltf", "w"))
gltf["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(pos).decode()
gltf["scenes"][0]["nodes"] = [0, 1]  # a camera whose aspectRatio no 512-wide image holds
gltf["nodes"].append({"camera": 0, "translation": [0.3, 0.3, 3]})
gltf["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01, "aspectRatio": 0.001}}]
json.dump(gltf, open(d + "/tall.gltf", "w"))
PY
oiiotool --pattern constant:color=0.5,0.5,0.5 8x4 3 -d half -o "$T/own/env.exr" &&
  oiiotool --pattern constant:color=0.2,0.4,0.6 4x4 3 -d uint8 -o "$T/own/tex.png" &&
  cp "$T/own/tex.png" "$T/own/gtex.png" || fail "oiiotool could not write the scenes' images"
ln -s env.exr "$T/own/env-link.exr"
ln -s tex.json "$T/own/tex-link.png"
for pair in "env.json env.exr" "env.json env-link.exr" "tex.json tex.png" "inc.json gtex.png" "tri.gltf gtex.png" \
            "ext.gltf buf.png" "tex.json tex-link.png"; do
  read -r scene image <<< "$pair"
  what="a file the scene reads"
  [ "$image" != tex-link.png ] || what="the scene file"
  cp -L "$T/own/$image" "$T/own/before"  # the contents, also through a link
  quick 2 "$LUMIS" render "$T/own/$scene" -o "$T/own/$image" --width 8 --spp 1 -q
  has "lumis: $T/own/$image: is $what ($T/own/"
  cmp -s "$T/own/$image" "$T/own/before" || fail "rendering $scene changed $image"
  rm -f "$T/own/before"
done
expect 0 "$LUMIS" render "$T/own/tri.gltf" -o "$T/own/other.png" --width 8 --spp 1 -q
# --width alone keeps the camera's aspectRatio 0.001 (2 x 2000), not the 512 x 16384 that the default was clamped
# to; the image then has the camera's shape, so the clamp's warning is not given.
expect 0 "$LUMIS" render "$T/own/tall.gltf" -o "$T/own/tall.png" --width 2 --spp 1 -q
lacks "aspectRatio"
oiiotool --info "$T/own/tall.png" | grep -q " 2 x 2000," || fail "tall.png: $(oiiotool --info "$T/own/tall.png")"
# bench --json naming the scene file is refused before anything is measured; naming a file the scene reads (known
# once it has loaded) stops the run there, before that scene is measured.
cp "$T/own/inc.json" "$T/own/inc-before.json" && cp "$T/own/gtex.png" "$T/own/gtex-before.png" ||
  fail "could not copy the scene files"
quick 2 "$LUMIS" bench "$T/own/inc.json" --quick --json "$T/own/inc.json"
has "lumis: bench: --json $T/own/inc.json is the scene file $T/own/inc.json; write the results elsewhere"
[ ! -s "$T/out" ] || fail "bench measured a scene before refusing --json: $(cat "$T/out")"
quick 2 "$LUMIS" bench "$T/own/inc.json" --quick --json "$T/own/gtex.png"
has "lumis: bench: --json $T/own/gtex.png is a file scene inc reads ($T/own/gtex.png); write the results elsewhere"
[ ! -s "$T/out" ] || fail "bench measured a scene before refusing --json naming a file it reads: $(cat "$T/out")"
cmp -s "$T/own/inc.json" "$T/own/inc-before.json" && cmp -s "$T/own/gtex.png" "$T/own/gtex-before.png" ||
  fail "bench --json wrote over a file the scene reads"
echo "output and option checks passed"
