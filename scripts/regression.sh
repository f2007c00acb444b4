#!/usr/bin/env bash
# The regression suite (tests/regression/README.md) outside ctest.
#
#   scripts/regression.sh [--lumis PATH]                 run the suite once (as ctest's cli_regression does)
#   scripts/regression.sh --regenerate [--only REGEX]    re-render references (tests/regression/refs/<case>.exr) at
#                                                        each case's reference spp with seed 7001, then cross-check
#   scripts/regression.sh --cross-check                  z-test every reference against the first one of its group
#                                                        (cases of a group have the same expected image)
#   scripts/regression.sh --seeds "1 2 3" [--scale X]    run the suite once per seed and tabulate each case's
#                                                        smallest family-wise p-value (checks the CLT regime)
#
# --lumis defaults to build/lumis, else the newest build-*/lumis. --only and --scale also apply to the suite runs
# (LUMIS_REGRESSION_CASES and LUMIS_REGRESSION_SPP_SCALE, see tests/cli/regression.sh).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DIR="$ROOT/tests/regression"
REF_SEED=7001
LUMIS="" MODE=run SEEDS="" ONLY=.
while [ $# -gt 0 ]; do
  case $1 in
    --lumis) LUMIS=$2; shift 2 ;;
    --regenerate) MODE=regenerate; shift ;;
    --cross-check) MODE=cross; shift ;;
    --seeds) MODE=seeds; SEEDS=$2; shift 2 ;;
    --scale) export LUMIS_REGRESSION_SPP_SCALE=$2; shift 2 ;;
    --only) ONLY=$2; export LUMIS_REGRESSION_CASES=$2; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
if [ -z "$LUMIS" ]; then
  if [ -x "$ROOT/build/lumis" ]; then LUMIS="$ROOT/build/lumis"
  else LUMIS=$(ls -t "$ROOT"/build-*/lumis 2>/dev/null | head -1 || true); fi
fi
[ -n "$LUMIS" ] && [ -x "$LUMIS" ] || { echo "no lumis binary: build it, or pass --lumis PATH" >&2; exit 2; }
echo "lumis: $LUMIS"

cases() { grep -v '^#' "$DIR/cases.txt" | awk 'NF >= 4' | grep -E "^[^ ]*($ONLY)[^ ]* " || true; }

# Every reference of a group against the group's first, alpha 0.01 split (Sidak) over all pairs. Both images carry
# variance channels, so the test is symmetric; a failure means two variants disagree beyond noise.
cross_check() {
  local pairs alpha status=0
  pairs=$(grep -v '^#' "$DIR/cases.txt" | awk 'NF >= 4 { n[$4]++ } END { s = 0; for (g in n) s += n[g] - 1; print s }')
  alpha=$(awk -v n="$pairs" 'BEGIN { printf "%.6g", 1 - exp(log(0.99) / n) }')
  echo "cross-check: $pairs pairs, alpha $alpha each (1% in all)"
  declare -A first
  while read -r c _ _ g; do
    [ -f "$DIR/refs/$c.exr" ] || { echo "  missing refs/$c.exr"; status=1; continue; }
    if [ -z "${first[$g]:-}" ]; then first[$g]=$c; continue; fi
    local out
    if out=$("$LUMIS" diff "$DIR/refs/$c.exr" "$DIR/refs/${first[$g]}.exr" --z-test --alpha "$alpha" 2>&1); then
      echo "  pass $c vs ${first[$g]}: $(grep 'z-test:' <<<"$out" | sed 's/^z-test: //')"
    else
      echo "  FAIL $c vs ${first[$g]}:"; sed 's/^/    /' <<<"$out"; status=1
    fi
  done < <(grep -v '^#' "$DIR/cases.txt" | awk 'NF >= 4')
  return $status
}

case $MODE in
  run)
    exec bash "$ROOT/tests/cli/regression.sh" "$LUMIS" ;;
  regenerate)
    mkdir -p "$DIR/refs"
    # The binary may come from another checkout: README.md records the commit it was built from.
    echo "references: seed $REF_SEED, binary $LUMIS; this checkout is at $(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- . ':!tests/regression' || echo ' + local changes')"
    while read -r c _ ref_spp _; do
      start=$(date +%s)
      "$LUMIS" render "$DIR/cases/$c.json" --spp "$ref_spp" --seed "$REF_SEED" -q -o "$DIR/refs/$c.exr"
      echo "  $c: $ref_spp spp, $(( $(date +%s) - start )) s, $(stat -c %s "$DIR/refs/$c.exr") bytes"
    done < <(cases)
    echo "total: $(du -cb "$DIR"/refs/*.exr | tail -1 | cut -f1) bytes"
    cross_check ;;
  cross)
    cross_check ;;
  seeds)
    tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
    for s in $SEEDS; do
      LUMIS_REGRESSION_SEED=$s bash "$ROOT/tests/cli/regression.sh" "$LUMIS" >"$tmp/seed$s.txt" || true
      echo "seed $s: $(grep -c '^PASS ' "$tmp/seed$s.txt") passed, $(grep -Ec '^(FAIL|ERROR) ' "$tmp/seed$s.txt") failed, $(grep '^regression: [0-9]* s' "$tmp/seed$s.txt" | cut -d' ' -f2-)"
      grep -E '^(FAIL|ERROR) ' "$tmp/seed$s.txt" | sed 's/^/  /' || true
    done
    echo "per case over seeds [$SEEDS]: smallest per-test p, smallest family-wise p (1 - (1 - p)^tests), failures"
    cat "$tmp"/seed*.txt | awk '$1 == "PASS" || $1 == "FAIL" {
        c = $2; n[c]++; if (!(c in mp) || $6 < mp[c]) mp[c] = $6; if (!(c in fw) || $8 < fw[c]) fw[c] = $8
        if ($1 == "FAIL") f[c]++ }
      END { for (c in n) printf "  %-28s runs %2d  min p %-10.3g min familywise p %-8.3g failures %d\n", c, n[c], mp[c], fw[c], f[c] }' |
      sort ;;
esac
