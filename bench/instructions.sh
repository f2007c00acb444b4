#!/usr/bin/env bash
# Instructions per sample, by function: a deterministic measure of lumis's own cost, for a machine whose timings
# drift (docs/performance.md). Runs one single-thread 64x64 render under callgrind at SPP and at 2 SPP samples per
# pixel and prints the difference divided by the extra samples, so process start, loading, the BVH build and the
# image output cancel out. Keep SPP a power of two: the stratified sampler's permutations then never walk a cycle
# (both runs cost the same per sample).
# Needs valgrind. Under valgrind Embree runs its AVX2 kernels (valgrind has no AVX-512), so Embree's count is not
# the native one; lumis's own code is the same either way.
# Usage: bench/instructions.sh path/to/lumis SCENE [SPP (default 16)] [TOP (default 30)] [-- render options...]
set -euo pipefail
LUMIS=${1:?usage: bench/instructions.sh path/to/lumis SCENE [SPP] [TOP] [-- render options]}
SCENE=${2:?usage: bench/instructions.sh path/to/lumis SCENE [SPP] [TOP] [-- render options]}
SPP=${3:-16}
TOP=${4:-30}
shift $(( $# < 4 ? $# : 4 ))
[[ ${1:-} == -- ]] && shift
command -v valgrind >/dev/null || { echo "valgrind is needed (apt install valgrind)" >&2; exit 1; }
OUT=$(mktemp -d /tmp/lumis-instructions.XXXXXX)
W=64 H=64
run() {  # spp file render-options...
  local spp=$1 file=$2
  shift 2
  valgrind --tool=callgrind --callgrind-out-file="$file" "$LUMIS" render "$SCENE" -q -o "$OUT/image.exr" \
    --threads 1 --width $W --height $H --spp "$spp" "$@" >/dev/null 2>&1 || { echo "callgrind run failed" >&2; exit 1; }
}
run "$SPP" "$OUT/a.out" "$@"
run $((2 * SPP)) "$OUT/b.out" "$@"
# Per function: instructions at 2 SPP spp minus at SPP spp, per extra sample.
table() { callgrind_annotate --threshold=100 "$1" 2>/dev/null | awk '/^ *[0-9,]+ +\( *[0-9.]+%\)/ {
    n = $1; gsub(",", "", n); sub(/^ *[0-9,]+ +\( *[0-9.]+%\) +/, ""); print n "\t" $0 }'; }
samples=$((SPP * W * H))
awk -F'\t' -v samples=$samples -v top="$TOP" '
  FNR == NR { a[$2] += $1; next }
  { b[$2] += $1 }
  END {
    for (k in b) {
      d = (b[k] - (k in a ? a[k] : 0)) / samples
      if (k ~ /PROGRAM TOTALS/) { total = d; continue }
      if (k ~ /embree/) embree += d; else if (k ~ /lumis::|\/lumis\]/) lumis += d; else other += d
      name = k; sub(/ \[.*\]$/, "", name); sub(/^\?\?\?:/, "", name); gsub(/\(anonymous namespace\)/, "anon", name)
      if (name !~ /lambda/) sub(/\(.*$/, "", name)
      line[name] += d
    }
    printf "instructions per sample: %.0f (lumis %.0f, Embree %.0f, other %.0f)\n", total, lumis, embree, other
    n = 0
    for (k in line) { keys[++n] = k }
    # selection sort of the top entries, largest first
    for (i = 1; i <= n && i <= top; ++i) {
      m = i
      for (j = i + 1; j <= n; ++j) if (line[keys[j]] > line[keys[m]]) m = j
      t = keys[i]; keys[i] = keys[m]; keys[m] = t
      printf "%8.0f  %s\n", line[keys[i]], substr(keys[i], 1, 110)
    }
  }' <(table "$OUT/a.out") <(table "$OUT/b.out")
rm -rf "$OUT"
