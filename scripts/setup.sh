#!/usr/bin/env bash
# Installs lumis's build dependencies from Debian 12 packages (idempotent), builds lumis (Release, in build/) and
# renders the built-in default scene to cornell-sphere.png.
# Usage: scripts/setup.sh [--deps-only]
set -euo pipefail
cd "$(dirname "$0")/.."

# The tests also need: openimageio-tools (iinfo, oiiotool), python3 (cli_bench checks the bench JSON with it), clang
# (the fuzz stage) and chromium (cli_compare runs the HTML viewer's script). A slim Debian 12 image lacks python3.
PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libopenimageio-dev openimageio-tools
  libtinygltf-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev python3
  clang libclang-rt-14-dev
  chromium
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: need root or sudo to install packages" >&2; exit 1; }
    SUDO="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all packages present" >&2
fi

[ "${1:-}" = "--deps-only" ] && exit 0

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
build/lumis render -o cornell-sphere.png
echo "setup: rendered $(pwd)/cornell-sphere.png" >&2
