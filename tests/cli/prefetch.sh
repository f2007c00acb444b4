#!/usr/bin/env bash
# The hit-record prefetches exist in the built binary (docs/performance-history.md, thirteenth round). GCC counts
# __builtin_prefetch as free of side effects: its IPA pure-const pass found a void helper that only prefetched
# "const" and deleted every call to it, so for twelve rounds the binary had no prefetch while the code had several.
# Passes when a prefetcht0 sits in a function that is not a prefetch helper (prefetch_line, prefetch_hit_*: they
# were inlined), or when such a helper holds one and is called (not prefetches_hit_records, a query of the flag).
# Deterministic (no false failures). x86-64 only; otherwise skipped (exit 77).
# Usage: prefetch.sh path/to/lumis
set -uo pipefail
LUMIS=${1:?usage: prefetch.sh path/to/lumis}
source "$(dirname "$0")/common.bash"
[ "$(uname -m)" = x86_64 ] || { echo "skip: not x86-64"; exit 77; }
need objdump binutils

objdump -d --no-show-raw-insn -C "$LUMIS" >"$T/asm" || fail "objdump -d $LUMIS failed"
awk '
  /^[0-9a-f]+ <.*>:$/ { fn = $0; helper = fn ~ /prefetch_(line|hit_)/ }
  /\tprefetcht0 / { if (helper) in_helper++; else inlined++ }
  /\tcall .*prefetch_(line|hit_)/ { calls++ }
  END {
    printf "prefetcht0: %d inlined, %d in helpers; calls to helpers: %d\n", inlined, in_helper, calls
    exit !(inlined > 0 || (in_helper > 0 && calls > 0))
  }' "$T/asm" >"$T/out" || fail "no prefetch that runs in $LUMIS: $(cat "$T/out")"
cat "$T/out"
