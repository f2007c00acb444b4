#!/usr/bin/env bash
# Malformed input that needs a process of its own: a missing scene, a folder, a pipe and an unreadable file are
# rendered tiny and must exit 1 with the expected message on stderr and create no output file; `-o NAME.PNG` (upper
# case) must write a PNG. Exit codes >= 128 (signals, sanitizer aborts) always fail. The committed cases in
# tests/malformed/ run in one process: tests/app/test_malformed.cpp.
# Usage: malformed.sh path/to/lumis
set -uo pipefail
LUMIS=${1:?usage: malformed.sh path/to/lumis}
SRC=${LUMIS_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
DIR="$SRC/tests/malformed"
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

failures=0
count=0
bad() { echo "FAIL $1: $2"; sed 's/^/    /' "$T/err" | head -20; failures=$((failures + 1)); }

# run_case NAME INPUT WANT_SUBSTRING: exit 1, the substring on stderr, no output file.
run_case() {
  local name=$1 input=$2 substring=$3
  count=$((count + 1))
  rm -rf "$T/out"
  mkdir -p "$T/out"
  "$LUMIS" render "$input" -o "$T/out/out.png" --spp 1 --width 8 --height 8 -q >"$T/stdout" 2>"$T/err"
  local got=$?
  if [ "$got" -ge 128 ]; then bad "$name" "crashed (exit $got)"; return; fi
  if [ "$got" != 1 ]; then bad "$name" "exit $got, expected 1"; return; fi
  if ! grep -qF -- "$substring" "$T/err"; then bad "$name" "stderr lacks '$substring'"; return; fi
  if [ -n "$(ls -A "$T/out")" ]; then bad "$name" "left files: $(ls -A "$T/out")"; fi
}

# Cases that cannot be committed as files: a missing scene, a directory, a pipe, an unreadable file.
run_case missing_scene "$T/no-such-scene.json" "no-such-scene.json"
mkdir -p "$T/folder.json"
run_case directory_scene "$T/folder.json" "folder.json: is a folder, expected a scene file"
mkfifo "$T/pipe.json"
run_case pipe_scene "$T/pipe.json" "pipe.json: is not a regular file (a pipe, device or socket)"
cp "$DIR/json_empty_object.json" "$T/unreadable.json"
chmod 000 "$T/unreadable.json"
if ! cat "$T/unreadable.json" >/dev/null 2>&1; then   # root reads anything: skip there
  run_case unreadable_scene "$T/unreadable.json" "cannot open"
fi

# Output extensions are matched without regard to case (.PNG is a PNG).
count=$((count + 1))
"$LUMIS" render "$DIR/json_version_float.json" -o "$T/upper.PNG" --spp 1 --width 8 --height 8 -q 2>"$T/err" &&
  [ -s "$T/upper.PNG" ] || bad upper_case_extension "-o upper.PNG was not written"

echo "$count malformed-input cases, $failures failed (the committed cases: test_malformed)"
[ "$failures" = 0 ]
