#!/usr/bin/env bash
# End-to-end test of `lumis warptest`: exit codes (0 pass, 2 usage error), the picture's path checked before any
# sampling, the defaults shown by --help, and GGX down to tiny alphas. Usage: warptest.sh path/to/lumis
set -uo pipefail
LUMIS=${1:?usage: warptest.sh path/to/lumis}
source "$(dirname "$0")/common.bash"

# --help shows the defaults the README sends readers to it for.
expect 0 "$LUMIS" warptest --help
grep -Eq -- '--samples .*=1000000( |$)' "$T/out" || fail "--samples default: $(grep -- --samples "$T/out")"
grep -Eq -- '--output .*=warptest\.png( |$)' "$T/out" || fail "-o default: $(grep -- --output "$T/out")"

# A pass, with the picture.
expect 0 "$LUMIS" warptest cosine_hemisphere --samples 100000 -o "$T/w.png"
grep -q PASSED "$T/out" || fail "no PASSED: $(cat "$T/out")"
[ -s "$T/w.png" ] || fail "no picture"

# An unusable picture path is a usage error found before sampling: no statistic is printed.
for out in "$T/none/w.png" "$T/w.tif" "$T"; do
  expect 2 "$LUMIS" warptest cosine_hemisphere -o "$out"
  grep -q "chi-square" "$T/out" && fail "sampled before refusing -o $out: $(cat "$T/out")"
  grep -qF "$out" "$T/err" || fail "message for -o $out does not name it: $(cat "$T/err")"
done

# The smallest --samples allowed can decide for every warp at its default parameter; below it is a usage error.
for name in $("$LUMIS" warptest --help | sed -n 's/.*Warp to test: //p' | tr -d ','); do
  expect 0 "$LUMIS" warptest "$name" --samples 100000 -o ''
done
expect 2 "$LUMIS" warptest uniform_sphere --samples 1000 -o ''

# Alpha anywhere in (0, 1] for the GGX warps, including lobes far narrower than the cells.
for name in ggx_heitz ggx_cap; do
  for alpha in 1e-4 1e-6 1; do
    expect 0 "$LUMIS" warptest "$name" --param "$alpha" --samples 200000 -o ''
  done
done

# A parameter inside the domain where the test cannot decide says so (2), not FAILED (1).
expect 0 "$LUMIS" warptest spherical_cap --param 0.9999 --samples 200000 -o ''
expect 2 "$LUMIS" warptest spherical_cap --param 0.99999 -o ''
grep -q "cannot decide" "$T/err" || fail "undecidable cap: $(cat "$T/err")"

echo "warptest.sh: all checks passed"
