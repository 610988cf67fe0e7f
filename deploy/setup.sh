#!/usr/bin/env bash
# Installs rovctl's build and test dependencies from Debian's packages and builds it in ./build.
# Usage: bash deploy/setup.sh [BUILD_DIR] [extra cmake args...]
#        bash deploy/setup.sh --arch arm64 [options]: the arm64 cross build in ./build-arm64, its
#        tests under qemu and its .deb (deploy/cross-arm64.sh says how and takes the options).
set -euo pipefail
cd "$(dirname "$0")/.."

if [ "${1:-}" == "--arch" ]; then
  [ "${2:-}" == "arm64" ] || { echo "setup: --arch takes arm64 (the native build needs no --arch)" >&2; exit 2; }
  shift 2
  exec bash deploy/cross-arm64.sh "$@"
fi

packages=(build-essential cmake ninja-build pkg-config git
  libeigen3-dev libopencv-dev libyaml-cpp-dev libmodbus-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-pymodbus python3-serial python3-serial-asyncio socat clang-format libclang-rt-14-dev
  povray python3-opencv python3-numpy
  libcpp-httplib-dev chromium nodejs universal-ctags)
# npm comes with some nodejs builds (NodeSource's) and is its own package in Debian's.
command -v npm >/dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  [[ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)" == "install ok installed" ]] || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The npm test peers (puppeteer-core for the browser test, node-mavlink for the MAVLink peer),
# pinned by tests/package-lock.json; a checkout that had only the first gets the second too.
if [ ! -d tests/node_modules/puppeteer-core ] || [ ! -d tests/node_modules/node-mavlink ]; then
  echo "setup: npm ci in tests/"
  npm ci --prefix tests --no-audit --no-fund --loglevel=error
fi

build_dir=${1:-build}
shift || true
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build_dir" -j"$(nproc)"
echo "setup: built $build_dir/rovctl"
