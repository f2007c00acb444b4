#!/usr/bin/env bash
# Runs the whole lumis test suite: installs missing packages (idempotent), then the stages
#   release  build Release in build/ ($BUILD_DIR) and run every ctest
#   asan     build with ASan + UBSan (-DLUMIS_SANITIZE=ON, -O1) in build-asan/ and run the unit and regression tests
#            (the heaviest statistical image tests are left to the Release stage: LUMIS_ASAN_EXCLUDE)
#   tsan     build the renderer with ThreadSanitizer (-DLUMIS_TSAN=ON) in build-tsan/ and render the default scene
#            small on 2 threads; any report fails (suppressions: scripts/tsan.supp)
#   fuzz     build the libFuzzer targets (scripts/fuzz.sh) and run each for FUZZ_SECONDS (default 20)
# ctest and the fuzzers run with TMPDIR set to a fresh folder, and a stage fails when anything is left there.
# Every stage runs even when an earlier one failed; the script fails when any stage fails. A stage is skipped, with
# a message, only when its tool is missing (no clang for fuzz). Stage times are printed at the end. The last line
# is the Release ctest summary when everything passed, else "N passed, M failed" over all tests and stages.
# Usage: scripts/test.sh [release|asan|tsan|fuzz ...]   (default: all stages)
# Environment: BUILD_DIR (default build), FUZZ_SECONDS (20), LUMIS_ASAN_EXCLUDE (ctest regex).
set -uo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --deps-only || exit 1
jobs=$(nproc)
build=${BUILD_DIR:-build}
stages=("$@")
[ ${#stages[@]} -eq 0 ] && stages=(release asan tsan fuzz)
# Heavy image-statistics tests (seconds in Release, minutes under ASan); Release runs them.
asan_exclude=${LUMIS_ASAN_EXCLUDE:-test_variant_agreement|test_end_to_end|cli_compare}
log=$(mktemp -d)
trap 'rm -rf "$log"' EXIT

declare -A seconds result
passed=0
failed=0
skipped=""
release_summary=""

# ctest_counts FILE: add ctest's "N tests failed out of M" to the totals.
ctest_counts() {
  local line total bad
  line=$(grep -E "tests passed, [0-9]+ tests? failed out of [0-9]+" "$1" | tail -1)
  [ -n "$line" ] || return 0
  bad=$(echo "$line" | sed -E 's/.* ([0-9]+) tests? failed out of ([0-9]+).*/\1/')
  total=$(echo "$line" | sed -E 's/.* failed out of ([0-9]+).*/\1/')
  passed=$((passed + total - bad))
  failed=$((failed + bad))
}

# fresh_temp STAGE: make and print a folder for the stage's TMPDIR. left_in_temp STAGE FOLDER: fail (status 1,
# with a message) when the stage left anything there: tests and tools clean up after themselves.
fresh_temp() { mkdir -p "$log/temp-$1" && echo "$log/temp-$1"; }
left_in_temp() {
  [ -z "$(ls -A "$2")" ] && return 0
  echo "test: the $1 stage left $(ls -A "$2" | wc -l) entries in TMPDIR, such as:" \
    "$(ls -A "$2" | head -3 | tr '\n' ' ')" >&2
  return 1
}

# run_ctest STAGE ARGS...: ctest ARGS with TMPDIR set to a fresh folder; anything left there fails the stage.
run_ctest() {
  local stage=$1; shift
  local tmp
  tmp=$(fresh_temp "$stage")
  TMPDIR=$tmp ctest "$@" 2>&1 | tee "$log/$stage.txt"
  local code=${PIPESTATUS[0]}
  ctest_counts "$log/$stage.txt"
  # Skipped tests (exit 77: not x86-64, a missing reference) are named in the summary, not only in ctest's output.
  skipped+=$(grep -E "^\s*[0-9]+ - .* \(Skipped\)" "$log/$stage.txt" | sed -E "s/^\s*[0-9]+ - (.*) \(Skipped\)/ $stage:\1/" | tr -d '\n')
  if ! left_in_temp "$stage" "$tmp"; then
    failed=$((failed + 1))
    code=1
  fi
  return "$code"
}

stage_release() {
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null &&
    cmake --build "$build" -j "$jobs" || return 1
  run_ctest release --test-dir "$build" --output-on-failure -j "$jobs"
  local code=$?
  release_summary=$(grep -E "tests passed, [0-9]+ tests? failed out of" "$log/release.txt" | tail -1)
  return "$code"
}

stage_asan() {
  # -O1 with line tables: sanitizer reports get file:line at a fraction of a full debug build's cost.
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
    -DLUMIS_SANITIZE=ON >/dev/null &&
    cmake --build build-asan -j "$jobs" || return 1
  # Leak checking stays on (two leaks inside TBB and OpenImageIO suppressed: scripts/lsan.supp); UBSan findings
  # abort (-fno-sanitize-recover) and print a stack.
  ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1} \
    LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$(pwd)/scripts/lsan.supp:print_suppressions=0} \
    UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
    LUMIS_REGRESSION_SPP_SCALE=${LUMIS_REGRESSION_SPP_SCALE:-0.25} \
    run_ctest asan --test-dir build-asan --output-on-failure -j "$jobs" -E "$asan_exclude"
}

stage_tsan() {
  cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
    -DLUMIS_TSAN=ON -DLUMIS_TESTS=OFF >/dev/null &&
    cmake --build build-tsan -j "$jobs" --target lumis || return 1
  local out
  out=$(mktemp -d)
  # halt_on_error: the first report ends the render with exit code 66, so any data race fails the stage.
  TSAN_OPTIONS="halt_on_error=1 exitcode=66 second_deadlock_stack=1 suppressions=$(pwd)/scripts/tsan.supp" \
    build-tsan/lumis render --width 64 --height 64 --spp 4 --threads 2 -o "$out/tsan.exr" 2>&1 | tee "$log/tsan.txt"
  local code=${PIPESTATUS[0]}
  [ "$code" = 0 ] && [ -s "$out/tsan.exr" ] || code=1
  grep -q "WARNING: ThreadSanitizer" "$log/tsan.txt" && code=1
  rm -rf "$out"
  if [ "$code" = 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)); fi
  return "$code"
}

stage_fuzz() {
  if ! command -v clang++ >/dev/null; then
    echo "test: SKIPPED fuzz stage: clang++ is not installed (apt-get install clang libclang-rt-14-dev)" >&2
    result[fuzz]=skipped
    return 0
  fi
  local tmp
  tmp=$(fresh_temp fuzz)
  TMPDIR=$tmp scripts/fuzz.sh "${FUZZ_SECONDS:-20}" 2>&1 | tee "$log/fuzz.txt"
  local code=${PIPESTATUS[0]}
  left_in_temp fuzz "$tmp" || code=1
  if [ "$code" = 0 ]; then passed=$((passed + 2)); else failed=$((failed + 1)); fi
  return "$code"
}

for s in "${stages[@]}"; do
  case "$s" in release|asan|tsan|fuzz) ;; *) echo "test: unknown stage '$s' (release, asan, tsan, fuzz)" >&2; exit 2;; esac
  echo "==== test: stage $s" >&2
  start=$(date +%s)
  if "stage_$s"; then
    [ -n "${result[$s]:-}" ] || result[$s]=passed
  else
    result[$s]=FAILED
  fi
  seconds[$s]=$(($(date +%s) - start))
done

echo "==== test: stage times"
any_failed=0
for s in "${stages[@]}"; do
  printf '  %-8s %-8s %4d s\n' "$s" "${result[$s]}" "${seconds[$s]}"
  [ "${result[$s]}" = FAILED ] && any_failed=1
done
[ -z "$skipped" ] || echo "  skipped:$skipped"
if [ "$any_failed" = 0 ] && [ -n "$release_summary" ]; then
  echo "$release_summary"
else
  [ "$any_failed" = 1 ] && [ "$failed" = 0 ] && failed=1   # a build failure counts too
  echo "$passed passed, $failed failed"
fi
exit "$any_failed"
