#!/usr/bin/env bash
# End-to-end test of `lumis diff`: exit codes (0 pass, 1 fail, 2 error), JSON output, the z-test and the heatmap,
# on tiny renders of the built-in scene, and exact values (sRGB decoding, the PSNR peak) on flat images made with
# oiiotool. Usage: diff.sh path/to/lumis   (exit 77 = skipped)
set -uo pipefail
LUMIS=${1:?usage: diff.sh path/to/lumis}
source "$(dirname "$0")/common.bash"

R=(render "$SCENE" --width 16 --height 16 --spp 8 -q)
expect 0 "$LUMIS" "${R[@]}" --max-depth 3 --seed 1 -o "$T/a.exr"
expect 0 "$LUMIS" "${R[@]}" --max-depth 3 --seed 2 -o "$T/b.exr"
expect 0 "$LUMIS" "${R[@]}" --max-depth 1 --seed 1 -o "$T/direct.exr"
expect 0 "$LUMIS" "${R[@]}" --max-depth 3 --seed 1 -o "$T/a.png"
expect 0 "$LUMIS" render "$SCENE" --width 8 --height 16 --spp 1 -q -o "$T/narrow.exr"

# Identical images: every metric is zero and any threshold passes.
expect 0 "$LUMIS" diff "$T/a.exr" "$T/a.exr" --threshold 0
grep -Eq "mse +0$" "$T/out" || fail "identical images: $(cat "$T/out")"
expect 0 "$LUMIS" diff "$T/a.exr" "$T/a.exr" --z-test

# Two seeds differ: a zero threshold fails, a generous one passes; --metric picks what it applies to.
expect 1 "$LUMIS" diff "$T/a.exr" "$T/b.exr" --threshold 0
expect 0 "$LUMIS" diff "$T/a.exr" "$T/b.exr" --threshold 1e9
expect 0 "$LUMIS" diff "$T/a.exr" "$T/b.exr" --metric psnr --threshold -1e9
expect 1 "$LUMIS" diff "$T/a.exr" "$T/b.exr" --metric over --tolerance 0 --threshold 0
# An empty value (T=; lumis diff A B --threshold "$T") is a usage error: it once read as "not given", so the
# comparison passed with no threshold at all; --tolerance and --alpha alike.
for opt in --threshold --tolerance --alpha; do
  expect 2 "$LUMIS" diff "$T/a.exr" "$T/b.exr" $opt ""
  grep -qF -- "lumis: $opt: expected a finite number, found an empty string" "$T/err" || fail "$opt '': $(cat "$T/err")"
done
expect 2 "$LUMIS" diff "$T/a.exr" "$T/b.exr" --metric "" --threshold 0
grep -qF -- "lumis: --metric: expected a metric name, found an empty string" "$T/err" ||
  fail "--metric '': $(cat "$T/err")"
# --metric without --threshold and --alpha without --z-test change nothing: each is named in a warning (the exit
# status is that of the comparison), and with the option it qualifies there is no warning.
expect 0 "$LUMIS" diff "$T/a.exr" "$T/b.exr" --metric psnr
grep -qF -- "lumis diff: warning: --metric chooses what --threshold tests; ignored without --threshold" "$T/err" ||
  fail "--metric alone: $(cat "$T/err")"
expect 0 "$LUMIS" diff "$T/a.exr" "$T/b.exr" --alpha 0.05
grep -qF -- "lumis diff: warning: --alpha is the z-test's significance level; ignored without --z-test" "$T/err" ||
  fail "--alpha alone: $(cat "$T/err")"
expect 0 "$LUMIS" diff "$T/a.exr" "$T/a.exr" --metric psnr --threshold -1e9 --z-test --alpha 0.05
! grep -q "warning" "$T/err" || fail "warning with --threshold and --z-test given: $(cat "$T/err")"

# JSON on stdout with every metric, and the heatmap file.
expect 0 "$LUMIS" diff "$T/a.exr" "$T/b.exr" --json --heatmap "$T/heat.png"
for key in '"mse"' '"rmse"' '"relmse"' '"mae"' '"psnr"' '"maxabs"' '"over"' '"passed": true'; do
  grep -q "$key" "$T/out" || fail "--json lacks $key: $(cat "$T/out")"
done
[ -s "$T/heat.png" ] || fail "no heatmap written"
# A heatmap named like an input (here by another path to it) would overwrite that image: refused, the image kept.
cp "$T/b.exr" "$T/b-copy.exr"
expect 2 "$LUMIS" diff "$T/a.exr" "$T/b-copy.exr" --heatmap "$T/../$(basename "$T")/b-copy.exr"
grep -q "is the input image $T/b-copy.exr; give another file name" "$T/err" || fail "heatmap over an input: $(cat "$T/err")"
cmp -s "$T/b.exr" "$T/b-copy.exr" || fail "the heatmap overwrote an input image"

# Direct lighting only against full paths is biased: the z-test rejects it, with a useful summary.
expect 1 "$LUMIS" diff "$T/direct.exr" "$T/a.exr" --z-test
grep -q "z-test:.*, min p [0-9.e-]* at ([0-9]*, [0-9]*) [RGB],.*FAIL" "$T/out" || fail "z-test summary: $(cat "$T/out")"
expect 1 "$LUMIS" diff "$T/direct.exr" "$T/a.exr" --z-test --json
grep -q '"min_p"' "$T/out" && grep -q '"scored": [1-9]' "$T/out" || fail "z-test JSON: $(cat "$T/out")"
# At 1 spp every pixel's variance is 0: no p-values, so the rejections are counted apart and the first is placed.
"$LUMIS" render "$SCENE" --width 8 --height 8 --spp 1 -q -o "$T/one1.exr" || fail "1-spp render"
"$LUMIS" render "$SCENE" --width 8 --height 8 --spp 1 --seed 3 -q -o "$T/one2.exr" || fail "1-spp render, seed 3"
expect 1 "$LUMIS" diff "$T/one1.exr" "$T/one2.exr" --z-test
grep -q "^z-test: [1-9][0-9]* of 192 pixel-channels rejected ([0-9.]*%), none has a p-value, Sidak" "$T/out" &&
  grep -q "^  192 pixel-channels with zero variance compared to 1e-5 relative: [1-9][0-9]* rejected$" "$T/out" &&
  grep -q "^  first rejected without a p-value at ([0-7], [0-7]) [RGB]$" "$T/out" ||
  fail "z-test without p-values: $(cat "$T/out")"
expect 1 "$LUMIS" diff "$T/one1.exr" "$T/one2.exr" --z-test --json
grep -q '"scored": 0,' "$T/out" || fail "z-test JSON without p-values: $(cat "$T/out")"

# Errors (exit 2), each naming the files involved.
expect 2 "$LUMIS" diff "$T/a.exr" "$T/narrow.exr"
grep -q "a.exr" "$T/err" && grep -q "narrow.exr" "$T/err" || fail "size message: $(cat "$T/err")"
expect 2 "$LUMIS" diff "$T/a.exr" "$T/a.png" --z-test          # a PNG has no variance channels
grep -q "a.png" "$T/err" || fail "variance message: $(cat "$T/err")"
expect 2 "$LUMIS" diff "$T/a.exr" "$T/missing.exr"
grep -q "missing.exr" "$T/err" || fail "missing-file message: $(cat "$T/err")"
expect 2 "$LUMIS" diff "$T/a.exr" "$T/b.exr" --metric ssim
expect 2 "$LUMIS" diff "$T/a.exr"
expect 2 "$LUMIS" diff "$T/a.exr" "$T/b.exr" --psnr-peak zero

# A PNG (decoded from sRGB) and an EXR are comparable; PSNR can use the reference's largest value as its peak.
expect 0 "$LUMIS" diff "$T/a.png" "$T/a.exr" --psnr-peak max
grep -q "psnr .*(peak [0-9]" "$T/out" || fail "psnr line: $(cat "$T/out")"

# Exact values on flat images made with oiiotool. An 8-bit PNG holds sRGB codes: code 128 is linear 0.2158605, so it
# equals an EXR of that value. --psnr-peak max is the reference's largest value (2 here): a difference of 0.5 in
# one channel of three gives MSE 1/12 and PSNR 10 log10(4 / (1/12)) = 16.8124 dB.
need oiiotool openimageio-tools
oiiotool --pattern constant:color=0.5,0.5,0.5 4x4 3 -d uint8 -o "$T/code128.png" || fail "oiiotool: code128.png"
oiiotool --pattern constant:color=0.2158605,0.2158605,0.2158605 4x4 3 -d float -o "$T/linear.exr" ||
  fail "oiiotool: linear.exr"
expect 0 "$LUMIS" diff "$T/code128.png" "$T/linear.exr" --metric maxabs --threshold 1e-6
oiiotool --pattern constant:color=0.25,0.5,2 4x4 3 -d float -o "$T/peak2.exr" || fail "oiiotool: peak2.exr"
oiiotool --pattern constant:color=0.25,0.5,1.5 4x4 3 -d float -o "$T/off.exr" || fail "oiiotool: off.exr"
expect 0 "$LUMIS" diff "$T/off.exr" "$T/peak2.exr" --psnr-peak max --json
grep -q '"psnr_peak": 2.0,' "$T/out" || fail "--psnr-peak max: $(cat "$T/out")"
grep -q '"psnr": 16.8124' "$T/out" || fail "PSNR with peak 2: $(cat "$T/out")"
# A grey image (Y, with or without A) compares as R = G = B, and the report says so; Y beside other colour channels
# (an XYZ image) is not grey: an error naming the channels, not R, G, B silently taken as Y three times.
oiiotool "$T/linear.exr" --ch "Y=R" -o "$T/grey.exr" || fail "oiiotool: grey.exr"
oiiotool "$T/linear.exr" --ch "Y=R,A=G" -o "$T/grey-alpha.exr" || fail "oiiotool: grey-alpha.exr"
oiiotool "$T/linear.exr" --ch "X=R,Y=G,Z=B" -o "$T/xyz.exr" || fail "oiiotool: xyz.exr"
expect 0 "$LUMIS" diff "$T/grey.exr" "$T/grey-alpha.exr" --threshold 0
grep -q "^4x4, Y (as R, G, B) compared$" "$T/out" || fail "grey report: $(cat "$T/out")"
expect 0 "$LUMIS" diff "$T/grey.exr" "$T/linear.exr" --threshold 0
grep -q "^4x4, Y of A (as R, G, B) and R G B of B compared$" "$T/out" || fail "grey against RGB: $(cat "$T/out")"
expect 0 "$LUMIS" diff "$T/linear.exr" "$T/linear.exr"
grep -q "^4x4, R G B compared$" "$T/out" || fail "RGB report: $(cat "$T/out")"
expect 2 "$LUMIS" diff "$T/xyz.exr" "$T/linear.exr"
grep -qF "$T/xyz.exr: no R, G, B channel (has X, Y, Z)" "$T/err" || fail "XYZ message: $(cat "$T/out" "$T/err")"
echo "diff.sh: all checks passed"
