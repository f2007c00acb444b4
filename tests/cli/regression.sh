#!/usr/bin/env bash
# Regression suite (tests/regression/README.md): renders every case of tests/regression/cases.txt at its modest spp
# with a fixed seed and z-tests it against the stored high-spp reference tests/regression/refs/<case>.exr with
# `lumis diff --z-test` (per pixel and channel, Sidak-corrected).
#
# The variance in z: var(a - b) = var(a) + var_ref, where var(a), the variance of the render's pixel mean, is the
# LARGER of two estimates: the render's own (its variance channels, from n_a samples) and the reference's per-sample
# variance scaled to n_a samples, var_ref x n_ref / n_a (from 64-128x more samples). Each alone fails falsely where
# heavy tails make it unreliable: at n_a ~ 100 a pixel whose edge or texture border is hit by 1% of its samples often
# gets no such sample (own variance 0, |z| ~ 10), and a render that does catch a rare bright path (probability
# below 1/n_ref) has a deviation the reference's variance never saw; the larger estimate covers both. oiiotool builds
# the combined variance into a copy of the reference and strips the render's channels; `lumis diff` then adds nothing.
# (With the stratified and Sobol samplers both estimates over-estimate var(a): those cases are conservative.)
#
# False-failure rate: each case is tested at alpha_case = 1 - (1 - ALPHA)^(1/cases), so a correct renderer fails the
# whole suite with probability ALPHA (default 0.01) at a fresh seed, provided every case is in its central-limit
# regime (checked over many seeds; README.md records the smallest p-values). The fixed seed makes a pass reproducible.
#
# Usage: regression.sh path/to/lumis        (exit 0 pass, 1 a case failed, 77 skipped: references missing)
# Environment:
#   LUMIS_REGRESSION_SPP_SCALE  multiplies every case's spp (default 1; the sanitizer stage uses 0.25)
#   LUMIS_REGRESSION_SEED       render seed (default 1; the references use 7001)
#   LUMIS_REGRESSION_ALPHA      suite-wide false-failure rate (default 0.01)
#   LUMIS_REGRESSION_CASES      extended regex selecting case names (default: all); alpha is split over the selection
#   LUMIS_REGRESSION_JOBS       cases rendered at once (default 2: process start-up is single-threaded)
#   LUMIS_REGRESSION_KEEP       folder to keep the renders and diff reports in (default: a temporary folder)
set -uo pipefail
LUMIS=${1:?usage: regression.sh path/to/lumis}
SRC=${LUMIS_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
DIR="$SRC/tests/regression"
SCALE=${LUMIS_REGRESSION_SPP_SCALE:-1}
SEED=${LUMIS_REGRESSION_SEED:-1}
ALPHA=${LUMIS_REGRESSION_ALPHA:-0.01}
SELECT=${LUMIS_REGRESSION_CASES:-.}
JOBS=${LUMIS_REGRESSION_JOBS:-2}
[ -f "$DIR/cases.txt" ] || { echo "skip: $DIR/cases.txt missing"; exit 77; }
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool (Debian openimageio-tools, a build dependency) not found"; exit 1; }

if [ -n "${LUMIS_REGRESSION_KEEP:-}" ]; then
  T=$LUMIS_REGRESSION_KEEP; mkdir -p "$T"
else
  T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fi

mapfile -t CASES < <(grep -v '^#' "$DIR/cases.txt" | awk 'NF >= 3' | grep -E "^[^ ]*($SELECT)[^ ]* ")
N=${#CASES[@]}
[ "$N" -gt 0 ] || { echo "FAIL: no case matches '$SELECT'"; exit 1; }
for line in "${CASES[@]}"; do
  c=${line%% *}
  [ -f "$DIR/refs/$c.exr" ] || { echo "skip: reference $DIR/refs/$c.exr missing (scripts/regression.sh --regenerate)"; exit 77; }
done
CASE_ALPHA=$(awk -v a="$ALPHA" -v n="$N" 'BEGIN { printf "%.6g", 1 - exp(log(1 - a) / n) }')
echo "regression: $N cases, seed $SEED, spp scale $SCALE, alpha $ALPHA suite-wide = $CASE_ALPHA per case"

# run_case "NAME SPP REF_SPP GROUP": render, z-test, one summary line in $T/NAME.result.
run_case() {
  local c spp base ref_spp start
  read -r c base ref_spp _ <<<"$1"
  spp=$(awk -v s="$base" -v k="$SCALE" 'BEGIN { n = int(s * k + 0.5); print (n < 1 ? 1 : n) }')
  start=$(date +%s.%N)
  if ! "$LUMIS" render "$DIR/cases/$c.json" --spp "$spp" --seed "$SEED" -q -o "$T/$c.exr" >"$T/$c.render.log" 2>&1; then
    echo "ERROR $c spp $spp: render failed: $(tail -3 "$T/$c.render.log" | tr '\n' ' ')" >"$T/$c.result"
    return
  fi
  # The render without its variance channels; the reference with max(var_a, var_ref x n_ref / n_a) + var_ref.
  local k v='variance.R,variance.G,variance.B'
  k=$(awk -v a="$spp" -v r="$ref_spp" 'BEGIN { printf "%.9g", r / a }')
  if ! oiiotool "$T/$c.exr" --ch R,G,B -d float -o "$T/$c.rgb.exr" \
      "$DIR/refs/$c.exr" --ch "$v" --mulc "$k" "$T/$c.exr" --ch "$v" --max "$DIR/refs/$c.exr" --ch "$v" --add \
      "$DIR/refs/$c.exr" --ch R,G,B --swap --chappend -d float -o "$T/$c.ref.exr" >"$T/$c.oiio.log" 2>&1; then
    echo "ERROR $c: oiiotool failed: $(tr '\n' ' ' <"$T/$c.oiio.log")" >"$T/$c.result"
    return
  fi
  "$LUMIS" diff "$T/$c.rgb.exr" "$T/$c.ref.exr" --z-test --alpha "$CASE_ALPHA" --json >"$T/$c.json" 2>"$T/$c.diff.log"
  local rc=$? secs
  secs=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
  if [ "$rc" = 2 ] || ! grep -q '"min_p"' "$T/$c.json"; then
    echo "ERROR $c spp $spp: diff failed: $(tr '\n' ' ' <"$T/$c.diff.log")" >"$T/$c.result"
    return
  fi
  # The z-test block is the last part of the JSON; pull its fields without a JSON tool.
  local zt minp tested rejected wx wy wc
  zt=$(sed -n '/"z_test"/,$p' "$T/$c.json")
  minp=$(sed -n 's/.*"min_p": *\([^,]*\),*/\1/p' <<<"$zt")
  tested=$(sed -n 's/.*"tested": *\([0-9]*\).*/\1/p' <<<"$zt")
  rejected=$(sed -n 's/.*"rejected": *\([0-9]*\).*/\1/p' <<<"$zt")
  wc=$(sed -n 's/.*"channel": *\([0-9]*\).*/\1/p' <<<"$zt"); wx=$(sed -n 's/.*"x": *\([0-9]*\).*/\1/p' <<<"$zt")
  wy=$(sed -n 's/.*"y": *\([0-9]*\).*/\1/p' <<<"$zt")
  # Family-wise p of the smallest p-value: 1 - (1 - p)^tested (uniform on [0,1] for a correct renderer).
  local fwp
  fwp=$(awk -v p="$minp" -v n="$tested" 'BEGIN { if (p >= 1) print 1; else printf "%.3g", 1 - exp(n * log(1 - p)) }')
  local verdict=PASS
  [ "$rc" = 0 ] || verdict=FAIL
  printf '%s %s spp %s min_p %s familywise_p %s rejected %s worst x %s y %s ch %s seconds %s\n' \
    "$verdict" "$c" "$spp" "$minp" "$fwp" "$rejected" "$wx" "$wy" "$wc" "$secs" >"$T/$c.result"
}
export -f run_case
export LUMIS DIR T SCALE SEED CASE_ALPHA

start=$(date +%s)
printf '%s\n' "${CASES[@]}" | xargs -P "$JOBS" -I{} bash -c 'run_case "$1"' _ {}
status=0
for line in "${CASES[@]}"; do
  c=${line%% *}
  if [ -f "$T/$c.result" ]; then cat "$T/$c.result"; else echo "ERROR $c: no result"; fi
  grep -q '^PASS' "$T/$c.result" 2>/dev/null || status=1
done
echo "regression: $(( $(date +%s) - start )) s"
if [ "$status" != 0 ]; then
  echo "FAIL: a case disagrees with its reference beyond noise (or could not run); see the lines above."
  echo "      Reproduce one: lumis render tests/regression/cases/CASE.json --seed $SEED --spp SPP -o a.exr &&"
  echo "      LUMIS_REGRESSION_CASES=CASE LUMIS_REGRESSION_KEEP=DIR tests/cli/regression.sh LUMIS keeps the render
      (DIR/CASE.exr), the reference with the combined variance (DIR/CASE.ref.exr) and the report (DIR/CASE.json)."
  exit 1
fi
echo "regression: all $N cases passed"
