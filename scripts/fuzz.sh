#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan; the scene loaders and every library below them instrumented,
# the commands not built) in build-fuzz/ and runs each for SECONDS (default 60). Seeds: scenes/*.json and
# tests/malformed/ cases, plus the small self-contained glTF models of the shared assets folder (copied into
# build-fuzz/seeds/ at run time, never committed). New corpus entries accumulate in build-fuzz/corpus/<target>/,
# crashing inputs in build-fuzz/artifacts/. Exits non-zero when a target finds a crash, a leak, a timeout or a
# sanitizer report.
# Usage: scripts/fuzz.sh [SECONDS]     (environment: LUMIS_SHARED_ASSETS=folder with gltf/, FUZZ_JOBS=build jobs)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
root=$(pwd)
build="$root/build-fuzz"
assets=${LUMIS_SHARED_ASSETS:-$root/../shared/assets}

command -v clang++ >/dev/null || { echo "fuzz: clang++ not found (install clang and libclang-rt-14-dev)" >&2; exit 1; }
cmake -S . -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DLUMIS_TESTS=OFF -DLUMIS_FUZZ=ON >/dev/null
cmake --build "$build" -j "${FUZZ_JOBS:-$(nproc)}" --target fuzz_json_scene fuzz_gltf

# Seeds.
rm -rf "$build/seeds"
mkdir -p "$build/seeds/json" "$build/seeds/gltf" "$build/corpus/fuzz_json_scene" "$build/corpus/fuzz_gltf" \
  "$build/artifacts"
cp scenes/*.json tests/malformed/*.json "$build/seeds/json/"
cp tests/malformed/*.gltf tests/malformed/*.glb "$build/seeds/gltf/"
if [ -d "$assets/gltf" ]; then
  # Self-contained models only (binary or embedded buffers): external .bin files would not travel with the input.
  find "$assets/gltf" -type f \( -name '*.glb' -o -path '*glTF-Embedded*' -name '*.gltf' \) -size -256k |
    while read -r f; do cp "$f" "$build/seeds/gltf/$(basename "$(dirname "$(dirname "$f")")")-$(basename "$f")"; done
else
  echo "fuzz: $assets/gltf not found; glTF seeds are the malformed-input cases only" >&2
fi

# The fuzzers' scratch files (fuzz_json_scene writes its input to $TMPDIR/fuzz.json) go to a folder removed on exit.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
status=0
run() {
  local target=$1 seeds=$2
  echo "fuzz: $target for ${seconds}s ($(ls "$seeds" | wc -l) seeds)" >&2
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: the loader must refuse absurd allocations.
  if ! (cd "$build" && LSAN_OPTIONS=suppressions=$root/scripts/lsan.supp:print_suppressions=0 TMPDIR=$scratch \
        "$build/tests/fuzz/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2560 \
        -max_len=65536 -dict="$root/tests/fuzz/scene.dict" -print_final_stats=1 \
        -artifact_prefix="$build/artifacts/$target-" "corpus/$target" "$seeds" 2>"$build/$target.log"); then
    status=1
    echo "fuzz: $target FAILED; see $build/$target.log and $build/artifacts/" >&2
    grep -E "ERROR|SUMMARY|Test unit written" "$build/$target.log" >&2 || true
  fi
  grep -E "stat::number_of_executed_units|stat::average_exec_per_sec|stat::new_units_added" "$build/$target.log" |
    sed "s/^/fuzz: $target /" >&2 || true
}
run fuzz_json_scene "$build/seeds/json"
run fuzz_gltf "$build/seeds/gltf"
exit $status
