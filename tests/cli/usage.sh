#!/usr/bin/env bash
# Usage errors say what was wrong in the option's own terms, exit 2, and render nothing: an unknown command is
# named with the list of commands, a whole-number option given a fraction or an exponent says it wants a whole
# number (CLI11 once said "not in range"), a range is given as the option states it (CLI11 once printed the largest
# double, 309 digits, as the upper bound). An option that cannot take effect is named in a warning: --exposure with
# an .exr or .hdr output; bench refuses --time and --exposure. Usage: usage.sh path/to/lumis   (exit 77 = skipped)
set -uo pipefail
LUMIS=${1:?usage: usage.sh path/to/lumis}
source "$(dirname "$0")/common.bash"
has() { grep -qF -- "$1" "$T/err" || { cat "$T/err"; fail "stderr lacks '$1'"; }; }
lacks() { ! grep -qF -- "$1" "$T/err" || { cat "$T/err"; fail "stderr has '$1'"; }; }

expect 2 "$LUMIS" frobnicate
has "lumis: unknown command 'frobnicate'; commands: render, warptest, diff, compare, bench"
expect 2 "$LUMIS" frobnicate "$SCENE" --spp 1
has "lumis: unknown command 'frobnicate'"
expect 2 "$LUMIS"
has "lumis: "
# An option before the command belongs to it: CLI11 once called its value ('2') an unknown command.
expect 2 "$LUMIS" --spp 2 render "$SCENE"
has "lumis: '--spp' comes before the command 'render'; options go after it: lumis render --spp ..."
expect 2 "$LUMIS" -q diff a.exr b.exr
has "lumis: '-q' comes before the command 'diff'; options go after it: lumis diff -q ..."
expect 2 "$LUMIS" --spp 2                   # no command at all: '2' was called an unknown command
has "lumis: '--spp' is an option of a command; give the command first: lumis COMMAND --spp 2 (commands: render,"

R=(render "$SCENE" --width 4 --height 4 --spp 1 -q -o "$T/r.png")
for bad in 1e3 1.5 ten -1 0 1073741825; do
  expect 2 "$LUMIS" "${R[@]}" --spp "$bad"
  has "lumis: --spp: expected a whole number in [1, 1073741824], found $bad"
  lacks "not in range"
done
# render --help gives the defaults that apply where the scene file is silent too (they are RenderSettings').
expect 0 "$LUMIS" render --help
grep -q "^  --spp 64, --integrator nee_mis, --max-depth 8, --rr-depth 3, --seed 0,$" "$T/out" ||
  fail "render --help lacks the defaults: $(cat "$T/out")"
expect 2 "$LUMIS" "${R[@]}" --spp 2        # R gives --spp 1 already
has "lumis: --spp: given 2 times; give it once"
lacks "At Most"
expect 2 "$LUMIS" "${R[@]}" --width 1e2
has "lumis: --width: expected a whole number in [1, 16384], found 1e2"
expect 2 "$LUMIS" "${R[@]}" --max-depth 0
has "lumis: --max-depth: expected a whole number in [1, 1024], found 0"
expect 2 "$LUMIS" "${R[@]}" --exposure 65
has "lumis: --exposure: expected a number in [-64, 64], found 65"
expect 2 "$LUMIS" "${R[@]}" --time -1
has "lumis: --time: expected a number of seconds in [0, 1e7], found -1"
# Beyond the double range: CLI11 reads +-inf, which the checks once let through (exit 0, a white or black image).
for opt in --exposure --time --mis-light-probability; do
  expect 2 "$LUMIS" "${R[@]}" $opt -1e400
  has "lumis: $opt: expected a finite number, found -1e400"
done
# Text where a number goes: CLI11 said "Could not convert: --time = abc".
expect 2 "$LUMIS" "${R[@]}" --time abc
has "lumis: --time: expected a number of seconds in [0, 1e7], found abc"   # with the option's range
lacks "Could not convert"
expect 2 "$LUMIS" diff a.exr b.exr --threshold abc   # no range to give: CLI11's conversion, reworded
has "lumis: --threshold: expected a number, found abc"
lacks "Could not convert"
expect 2 "$LUMIS" diff a.exr b.exr --alpha 1e400
has "lumis: --alpha: expected a finite number, found 1e400"
# An empty value (an unset shell variable) is refused, as it is for whole numbers and file names: it once read as
# "not given", so --time "" rendered at equal samples and --exposure "" at 0 (diff.sh: --threshold "").
for opt in --time --exposure --mis-light-probability; do
  expect 2 "$LUMIS" "${R[@]}" $opt ""
  has "lumis: $opt: expected a finite number, found an empty string"
done
expect 2 "$LUMIS" "${R[@]}" --width ""
has "lumis: --width: expected a whole number in [1, 16384], found an empty string"
expect 2 "$LUMIS" compare "$SCENE" -o "$T/cmp" --spp 1 --crop ""
has "lumis: --crop: expected x,y,w,h, found an empty string"
[ ! -e "$T/cmp" ] || fail "compare --crop '' made its folder"
expect 2 "$LUMIS" compare "$SCENE" -o ""
has "lumis: --output: expected a folder name, found an empty string"
expect 2 "$LUMIS" compare "$SCENE" -o "$T/cmp" --integrators ""   # once "unknown integrator ''"
has "lumis: --integrators: expected names separated by commas, found an empty string"
expect 2 "$LUMIS" bench --quick --assets ""      # CLI11 said "Directory does not exist: " and nothing
has "lumis: --assets: expected a folder, found an empty string"
[ ! -e "$T/r.png" ] || fail "a refused render wrote r.png"
# Kept as a 32-bit float, 0.99999999999 is 1, outside [0, 1): the message says so.
expect 2 "$LUMIS" "${R[@]}" --mis-light-probability 0.99999999999
has "lumis: --mis-light-probability: expected a probability in [0, 1), found 0.99999999999, which is 1 as the 32-bit"
expect 2 "$LUMIS" "${R[@]}" --mis-light-probability abc   # its own check: the range too (once "expected a number")
has "lumis: --mis-light-probability: expected a probability in [0, 1), found abc"
expect 2 "$LUMIS" bench --quick --repeat 0.5
has "lumis: --repeat: expected a whole number in [1, 100], found 0.5"
expect 2 "$LUMIS" warptest   # once only "name is required"
has "lumis: warptest: which warp? Valid names: uniform_theta_phi uniform_hemisphere cosine_hemisphere"
expect 2 "$LUMIS" warptest ""  # once "unknown warp ''"
has "lumis: name: expected a warp name, found an empty string"
expect 2 "$LUMIS" warptest uniform_sphere --samples 1e6
has "lumis: --samples: expected a whole number in [100000, 1000000000], found 1e6"
# An image name whose extension is no format lumis writes, or that has none (".png" alone is a hidden file's name,
# not a PNG; "out" once recursed until the stack ran out), refused before any work by render, diff and warptest.
Q=(render "$SCENE" --width 4 --height 4 --spp 1 -q -o)
expect 2 "$LUMIS" "${Q[@]}" "$T/.png"
NO_EXT="is a name without an extension (it starts with the dot); give a name before it, such as"
has "lumis: $T/.png: '.png' $NO_EXT out.png"
expect 2 "$LUMIS" "${Q[@]}" "$T/out"
has "lumis: $T/out: no extension to tell the image format by (use .exr, .png, .jpg/.jpeg or .hdr)"
expect 2 "$LUMIS" "${Q[@]}" "$T/out.TIF"
has "lumis: $T/out.TIF: unsupported image format '.tif' (use .exr, .png, .jpg/.jpeg or .hdr)"
expect 2 "$LUMIS" diff "$T/missing-a.exr" "$T/missing-b.exr" --heatmap "$T/heat"
has "lumis diff: $T/heat: no extension to tell the image format by"
lacks "missing-a.exr"  # refused before the images are read
expect 2 "$LUMIS" warptest cosine_hemisphere -o "$T/.EXR"
has "warptest: $T/.EXR: '.EXR' $NO_EXT out.EXR"
grep -q "chi-square" "$T/out" && fail "warptest sampled before refusing its picture's name"
[ -z "$(ls -A "$T" | grep -v -e "^out$" -e "^err$")" ] || fail "a refused name was written: $(ls -A "$T")"
[ ! -e "$T/r.png" ] || fail "a usage error rendered an image"
for bad in 0 -2 1.5; do
  expect 2 "$LUMIS" compare "$SCENE" --reference-spp "$bad" -o "$T/cmp"
  has "lumis: --reference-spp: expected a whole number in [1, 1073741824], found $bad"
done
[ ! -e "$T/cmp" ] || fail "a usage error made compare's folder"
expect 0 "$LUMIS" render "$SCENE" --width 4 --height 4 --spp 1000 --max-depth 1 -q -o "$T/ok.png"
# A leading zero is decimal, as the range check reads it: CLI11's own conversion took "010" as octal 8 (after the
# check passed it as 10) and refused "08" with "Could not convert".
need iinfo openimageio-tools
expect 0 "$LUMIS" render "$SCENE" --width 4 --height 4 --spp 010 --seed 010 --max-depth 08 -q -o "$T/z.exr"
iinfo -v "$T/z.exr" | grep -q 'lumis:spp: "10"' || fail "--spp 010 did not take 10 samples: $(iinfo -v "$T/z.exr")"
iinfo -v "$T/z.exr" | grep -q 'lumis:seed: "10"' || fail "--seed 010 is not seed 10: $(iinfo -v "$T/z.exr")"

# --exposure applies to PNG and JPEG only: with .exr or .hdr a warning says it is ignored (the image is written).
for ext in exr hdr HDR; do
  expect 0 "$LUMIS" render "$SCENE" --width 4 --height 4 --spp 1 -q --exposure 3 -o "$T/e.$ext"
  has "lumis: warning: --exposure only affects .png, .jpg and .jpeg output; ignored for $T/e.$ext"
  [ -s "$T/e.$ext" ] || fail "no image written to e.$ext"
done
expect 0 "$LUMIS" render "$SCENE" --width 4 --height 4 --spp 1 -q --exposure 3 -o "$T/e.png"
lacks "warning"
expect 0 "$LUMIS" render "$SCENE" --width 4 --height 4 --spp 1 -q -o "$T/e2.exr"
lacks "warning"
expect 0 "$LUMIS" render "$SCENE" --width 4 --height 4 --spp 1 -q --exposure 0 -o "$T/e2.exr"  # changes nothing
lacks "warning"

# A light too small for rays to hit (a radius of 1e-5 where the scene spans 4.6) is named in a warning by render
# with the variants that must hit lights (uniform, bsdf, mis), and by compare once when its variants include one;
# not with light and nee_mis, which sample the light itself.
cat > "$T/tiny.json" <<'EOF'
{"camera": {"from": [0, 3, 3], "to": [0, 0, 0]}, "materials": {"m": {"type": "diffuse"}},
 "shapes": [{"type": "quad", "origin": [-2, 0, 2], "edge_u": [4, 0, 0], "edge_v": [0, 0, -4], "material": "m"}],
 "lights": [{"type": "sphere", "center": [0, 2, -1.5], "radius": 1e-5, "radiance": [1e10, 1e10, 1e10]}]}
EOF
TINY="$T/tiny.json:/lights/0/radius: warning: the sphere light's radius, 1e-05, is less than 1e-05 times the span"
for it in uniform bsdf mis light nee_mis; do
  expect 0 "$LUMIS" render "$T/tiny.json" --width 4 --height 4 --spp 1 -q --integrator $it -o "$T/tiny.exr"
  case $it in light | nee_mis) lacks "warning" ;; *) has "$TINY" ;; esac
done
expect 0 "$LUMIS" compare "$T/tiny.json" --width 4 --height 4 --spp 1 --reference-spp 4 -q -o "$T/tiny-compare"
[ "$(grep -cF "$TINY" "$T/err")" = 1 ] || { cat "$T/err"; fail "compare did not name the tiny light once"; }
expect 0 "$LUMIS" compare "$T/tiny.json" --width 4 --height 4 --spp 1 --reference-spp 4 -q --integrators light,nee_mis \
  -o "$T/tiny-compare2"
lacks "warning"

# bench renders a fixed number of samples, writes no image and measures through each scene's default camera, so
# --time, --exposure and --camera cannot take effect there: they are refused by name before anything is measured
# (--time and --exposure were once accepted and ignored; --camera got CLI11's "argument was not expected"), and
# bench's help does not list them.
for opt in --time --exposure --camera; do
  expect 2 "$LUMIS" bench --quick --json "$T/b.json" "$opt" 1
  has "lumis: bench: $opt does not apply: "
  [ ! -s "$T/out" ] || fail "bench $opt measured before refusing: $(cat "$T/out")"
  [ ! -e "$T/b.json" ] || fail "bench $opt wrote its JSON"
  "$LUMIS" bench --help >"$T/help" || fail "bench --help exited $?"
  ! grep -q -- "$opt " "$T/help" || fail "bench --help lists $opt"
done
echo "usage.sh: all checks passed"
