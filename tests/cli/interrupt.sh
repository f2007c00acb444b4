#!/usr/bin/env bash
# Interruption and time budgets keep the work done so far: Ctrl-C (SIGINT) during a long render writes the image
# rendered so far (exit 130) with its true sample count in the EXR metadata and leaves no temporary file; SIGTERM
# does the same (exit 143); --time stops at the budget (exit 0) the same way; a render too large for the memory
# available fails before allocating; a compare stopped before its first write leaves no folders.
# Usage: interrupt.sh path/to/lumis
set -uo pipefail
LUMIS=${1:?usage: interrupt.sh path/to/lumis}
source "$(dirname "$0")/common.bash"
need iinfo openimageio-tools
fail() { echo "FAIL: $*"; [ -f "$T/err" ] && sed 's/^/    /' "$T/err"; exit 1; }  # with lumis's messages

# attr FILE NAME: the value of a string attribute in the image header.
attr() { iinfo -v "$1" | sed -n "s/^ *$2: \"\(.*\)\"$/\1/p"; }
# summary_spp: the sample count the render's summary line reports.
summary_spp() { sed -n 's/.*, \([0-9]*\) spp in .*/\1/p' "$T/err"; }

# stopped_render SIGNAL DIR: a render of far more samples than can finish, into DIR/out.exr, sent SIGNAL every half
# second until it exits; $code is its exit status. lumis starts with SIGNAL ignored, as a job started with & ignores
# SIGINT, so the signals sent while the scene loads (before lumis installs its handler) are lost: a stop signal
# then would end it at once, with nothing rendered. After 30 s of signals it is killed: a failure, not a wait of
# hours.
stopped_render() {
  local sig=$1 dir=$2
  mkdir "$dir"
  (trap '' "$sig" && exec "$LUMIS" render "$SCENE" --width 64 --height 64 --spp 1000000 --threads 2 \
    -o "$dir/out.exr") 2>"$T/err" &
  local pid=$!
  sleep 1
  for _ in $(seq 1 60); do
    kill -"$sig" "$pid" 2>/dev/null || break
    sleep 0.5
  done
  kill -KILL "$pid" 2>/dev/null
  wait "$pid"
  code=$?
}

# --- Ctrl-C (SIGINT).
stopped_render INT "$T/int"
[ "$code" = 130 ] || fail "interrupted render exited $code, expected 130"
[ -s "$T/int/out.exr" ] || fail "no image written after SIGINT"
[ "$(ls -A "$T/int")" = "out.exr" ] || fail "files left beside the image: $(ls -A "$T/int")"
spp=$(attr "$T/int/out.exr" lumis:spp)
[ -n "$spp" ] || fail "no lumis:spp in the EXR header: $(iinfo -v "$T/int/out.exr")"
[ "$spp" -ge 1 ] && [ "$spp" -lt 1000000 ] || fail "lumis:spp $spp after an interruption"
[ "$spp" = "$(summary_spp)" ] || fail "lumis:spp $spp, summary says $(summary_spp)"
[ "$(attr "$T/int/out.exr" lumis:stopped)" = interrupted ] || fail "lumis:stopped is not 'interrupted'"
[ "$(attr "$T/int/out.exr" lumis:integrator)" = nee_mis ] || fail "lumis:integrator"
[ "$(attr "$T/int/out.exr" lumis:seed)" = 0 ] || fail "lumis:seed"
[ "$(attr "$T/int/out.exr" lumis:scene)" = "$SCENE" ] || fail "lumis:scene"
grep -q "(interrupted)" "$T/err" || fail "summary does not say interrupted"

# --- SIGTERM (what batch schedulers and `kill` send) stops the render the same way: the image so far is written
# and the exit code is 143 (128 + 15), as a shell reports a terminated command.
stopped_render TERM "$T/term"
[ "$code" = 143 ] || fail "terminated render exited $code, expected 143"
[ "$(ls -A "$T/term")" = "out.exr" ] || fail "after SIGTERM the folder holds: $(ls -A "$T/term")"
[ "$(attr "$T/term/out.exr" lumis:stopped)" = interrupted ] || fail "lumis:stopped is not 'interrupted' after SIGTERM"
spp=$(attr "$T/term/out.exr" lumis:spp)
[ "$spp" = "$(summary_spp)" ] || fail "lumis:spp $spp, summary says $(summary_spp)"

# --- Time budget: stops near the budget with what it has, exit 0.
mkdir "$T/time"
start=$(date +%s.%N)
"$LUMIS" render "$SCENE" --width 32 --height 32 --time 1 --threads 2 -o "$T/time/out.exr" 2>"$T/err"
code=$?
elapsed=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
[ "$code" = 0 ] || fail "--time render exited $code"
[ "$(ls -A "$T/time")" = "out.exr" ] || fail "files beside the image: $(ls -A "$T/time")"
spp=$(attr "$T/time/out.exr" lumis:spp)
[ -n "$spp" ] && [ "$spp" -ge 1 ] || fail "lumis:spp '$spp' after a time budget"
[ "$spp" = "$(summary_spp)" ] || fail "lumis:spp $spp, summary says $(summary_spp)"
[ "$(attr "$T/time/out.exr" lumis:stopped)" = "time budget" ] || fail "lumis:stopped is not 'time budget'"
# The budget includes no scene loading; 20 s leaves room for slow sanitizer builds and busy machines.
awk -v e="$elapsed" 'BEGIN { exit !(e < 20) }' || fail "--time 1 took $elapsed s"

# A timed render that reaches the most samples a timed render takes (2^20) before its budget says that the cap, not
# the budget or the end of the work, stopped it. One pixel whose camera ray misses everything: about 2 s.
cat > "$T/miss.json" <<'EOF2'
{"version": 1, "camera": {"type": "perspective", "from": [0, 0, 0], "to": [0, 0, -1], "fov": 1},
 "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
 "shapes": [{"type": "quad", "origin": [-1, -1, 5], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0], "material": "grey"}]}
EOF2
"$LUMIS" render "$T/miss.json" --width 1 --height 1 --time 1000 -q -o "$T/cap.exr" 2>"$T/err" ||
  fail "capped render failed: $(cat "$T/err")"
[ "$(attr "$T/cap.exr" lumis:spp)" = 1048576 ] && [ "$(attr "$T/cap.exr" lumis:stopped)" = "sample cap" ] ||
  fail "metadata of a render stopped by the sample cap: $(iinfo -v "$T/cap.exr")"

# A complete render says so, with the spp asked for.
"$LUMIS" render "$SCENE" --width 8 --height 8 --spp 3 -q -o "$T/full.exr" 2>"$T/err" || fail "small render failed"
[ "$(attr "$T/full.exr" lumis:spp)" = 3 ] && [ "$(attr "$T/full.exr" lumis:stopped)" = complete ] ||
  fail "metadata of a complete render: $(iinfo -v "$T/full.exr")"

# --- Memory: 16384 x 16384 needs about 40 GiB; under a 4 GiB address-space limit lumis must refuse up front
# (exit 1, saying how much) instead of dying in an allocation. Sanitizer runtimes cannot start under such a limit:
# skip this part there.
mkdir "$T/mem"
(ulimit -v 4194304 && exec "$LUMIS" render "$SCENE" --width 16384 --height 16384 --spp 1 -q -o "$T/mem/out.png") \
  2>"$T/err"
code=$?
if grep -q -i "sanitizer" "$T/err"; then
  echo "note: memory-limit check skipped (sanitizer runtime)"
else
  [ "$code" = 1 ] || fail "oversized render exited $code, expected 1"
  grep -q "needs about .* GiB of memory" "$T/err" || fail "message does not say how much memory"
  [ -z "$(ls -A "$T/mem")" ] || fail "oversized render left files"
fi
# The same for compare (once "std::bad_alloc" after loading): refused before its folder is made.
(ulimit -v 4194304 && exec "$LUMIS" compare "$SCENE" --width 16384 --height 16384 --spp 1 -q -o "$T/mem/cmp") \
  2>"$T/err"
code=$?
if ! grep -q -i "sanitizer" "$T/err"; then
  [ "$code" = 1 ] || fail "oversized compare exited $code, expected 1: $(cat "$T/err")"
  grep -q "compare of 5 variants needs about .* GiB of memory" "$T/err" ||
    fail "compare's message does not say how much memory: $(cat "$T/err")"
  [ ! -e "$T/mem/cmp" ] || fail "oversized compare left its folder"
fi
# And bench (once a bare std::bad_alloc minutes in, or the kernel's OOM killer): refused before any scene is loaded,
# --json not written.
(ulimit -v 4194304 && exec "$LUMIS" bench "$SCENE" --quick --width 16384 --json "$T/mem/bench.json") 2>"$T/err"
code=$?
if ! grep -q -i "sanitizer" "$T/err"; then
  [ "$code" = 1 ] || fail "oversized bench exited $code, expected 1: $(cat "$T/err")"
  grep -q "16384 x 16384 benchmark needs about .* GiB of memory" "$T/err" ||
    fail "bench's message does not say how much memory: $(cat "$T/err")"
  grep -q "repetition" "$T/err" && fail "oversized bench measured a scene: $(cat "$T/err")"
  [ ! -e "$T/mem/bench.json" ] || fail "oversized bench wrote --json"
fi
# compare stopped while its reference renders (SIGTERM: a job started with & ignores SIGINT, and compare leaves the
# signal at its default) has written nothing yet: it leaves none of the folders -o made, where it once left them
# empty. Signalled every half second, as above, killed after 30 s.
"$LUMIS" compare "$SCENE" --width 32 --height 32 --spp 1 --reference-spp 1000000 -q -o "$T/cmpint/a/b" 2>"$T/err" &
pid=$!
sleep 1
for _ in $(seq 1 60); do
  kill -TERM "$pid" 2>/dev/null || break
  sleep 0.5
done
kill -KILL "$pid" 2>/dev/null
wait "$pid"
code=$?
[ "$code" = 143 ] || fail "compare stopped by SIGTERM exited $code, expected 143"
[ ! -e "$T/cmpint" ] || fail "a stopped compare left folders: $(find "$T/cmpint")"
echo "interrupt, time budget and memory checks passed"
