# Sourced by the CLI test scripts after LUMIS is set: the source tree ($SRC), the built-in scene ($SCENE; the
# script is skipped, exit 77, when it is missing), a temporary folder $T removed on exit, fail, need and expect.
SRC=${LUMIS_SOURCE_DIR:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
SCENE="$SRC/scenes/cornell-sphere.json"
[ -f "$SCENE" ] || { echo "skip: $SCENE missing"; exit 77; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# need TOOL PACKAGE: fail unless TOOL is on the PATH. scripts/setup.sh installs PACKAGE, so a missing tool is a broken
# set-up, not a reason to skip checks silently.
need() { command -v "$1" >/dev/null || fail "$1 not found: install the Debian package $2 (scripts/setup.sh --deps-only)"; }

# expect CODE CMD...: run CMD (stdout to $T/out, stderr to $T/err) and check its exit status.
expect() {
  local want=$1; shift
  "$@" >"$T/out" 2>"$T/err"
  local got=$?
  [ "$got" = "$want" ] || { cat "$T/out" "$T/err"; fail "exit $got, expected $want: $*"; }
}
