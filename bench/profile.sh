#!/usr/bin/env bash
# Profile a representative render with `perf record` (linux-perf) and print the shared-object split and the top
# symbols: the figures docs/performance.md quotes. Writes the generated 1M-triangle room with
# `lumis bench --write-large-scene` first.
# Usage: bench/profile.sh path/to/lumis [OUT_DIR]   (OUT_DIR default: a temporary folder, kept)
set -euo pipefail
LUMIS=${1:?usage: bench/profile.sh path/to/lumis [OUT_DIR]}
SRC=$(cd "$(dirname "$0")/.." && pwd)
OUT=${2:-$(mktemp -d /tmp/lumis-profile.XXXXXX)}
mkdir -p "$OUT"
command -v perf >/dev/null || { echo "perf (linux-perf) is needed" >&2; exit 1; }

"$LUMIS" bench --write-large-scene "$OUT/large.glb"

# name scene render-options...
profile() {
  local name=$1 scene=$2; shift 2
  perf record -q -o "$OUT/$name.data" "$LUMIS" render "$scene" -q -o "$OUT/$name.png" "$@" 2>/dev/null
  echo "== $name: by shared object"
  # `|| true`: head closing the pipe early (SIGPIPE upstream) is not a failure.
  perf report -i "$OUT/$name.data" --no-children --sort dso --stdio 2>/dev/null | grep '%' | head -6 || true
  echo "== $name: top symbols (Embree's are unnamed: Debian strips libembree3)"
  perf report -i "$OUT/$name.data" --no-children --sort dso,symbol --stdio 2>/dev/null | grep '%' | head -25 |
    cut -c1-110 || true
}
profile cornell-sphere "$SRC/scenes/cornell-sphere.json" --width 256 --height 256 --spp 64
profile large "$OUT/large.glb" --width 128 --height 128 --spp 64
echo "perf data and images in $OUT"
