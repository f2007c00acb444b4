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

# run_case NAME INPUT WANT_CODE WANT_SUBSTRING [EXTRA ARGS...]
run_case() {
  local name=$1 input=$2 want=$3 substring=$4
  shift 4
  count=$((count + 1))
  rm -rf "$T/out"
  mkdir -p "$T/out"
  "$LUMIS" render "$input" -o "$T/out/out.png" --spp 1 --width 8 --height 8 -q "$@" >"$T/stdout" 2>"$T/err"
  local got=$?
  if [ "$got" -ge 128 ]; then bad "$name" "crashed (exit $got)"; return; fi
  if [ "$got" != "$want" ]; then bad "$name" "exit $got, expected $want"; return; fi
  if [ -n "$substring" ] && ! grep -qF -- "$substring" "$T/err"; then
    bad "$name" "stderr lacks '$substring'"; return
  fi
  if [ "$want" = 0 ]; then
    [ -s "$T/out/out.png" ] || { bad "$name" "no image written"; return; }
  else
    if [ -n "$(ls -A "$T/out")" ]; then bad "$name" "left files: $(ls -A "$T/out")"; return; fi
    [ -s "$T/err" ] || { bad "$name" "no message on stderr"; return; }
  fi
}

# Cases that cannot be committed as files: a missing scene, a directory, a pipe, an unreadable file.
run_case missing_scene "$T/no-such-scene.json" 1 "no-such-scene.json"
mkdir -p "$T/folder.json"
run_case directory_scene "$T/folder.json" 1 "folder.json: is a folder, expected a scene file"
mkfifo "$T/pipe.json"
run_case pipe_scene "$T/pipe.json" 1 "pipe.json: is not a regular file (a pipe, device or socket)"
cp "$DIR/json_empty_object.json" "$T/unreadable.json"
chmod 000 "$T/unreadable.json"
if ! cat "$T/unreadable.json" >/dev/null 2>&1; then   # root reads anything: skip there
  run_case unreadable_scene "$T/unreadable.json" 1 "cannot open"
fi

# Output extensions are matched without regard to case (.PNG is a PNG).
count=$((count + 1))
"$LUMIS" render "$DIR/json_version_float.json" -o "$T/upper.PNG" --spp 1 --width 8 --height 8 -q 2>"$T/err" &&
  [ -s "$T/upper.PNG" ] || bad upper_case_extension "-o upper.PNG was not written"

echo "$count malformed-input cases, $failures failed (the committed cases: test_malformed)"
[ "$failures" = 0 ]
