#!/usr/bin/env bash
# Installs the Debian 12 packages interiornet needs to build, test and run. Idempotent: does
# nothing when everything is present. Runs apt-get as root, through sudo otherwise.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libembree-dev libtbb-dev libeigen3-dev libassimp-dev libopenexr-dev libpng-dev libjpeg-dev
  nlohmann-json3-dev libpugixml-dev libcli11-dev libfmt-dev libspdlog-dev librandom123-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcairo2-dev
  libtorch-dev
  libhdf5-dev
  libyaml-cpp-dev
  libopencv-dev libopencv-contrib-dev
  libbullet-dev
  libtinygltf-dev
  libzip-dev sweethome3d-furniture libgeos-dev
  libsqlite3-dev libopenmpi-dev openmpi-bin
  libarchive-dev
  libcpp-httplib-dev
  chromium
)
# The studio's page (studio/web): three.js, esbuild and playwright-core from the npm registry,
# as pinned in its package-lock.json, with the machine's Node.js and npm (Node.js >= 20);
# Debian's chromium runs its browser tests. Done when node_modules is older than the lock.
studio_npm() {
  local web; web="$(cd "$(dirname "$0")/.." && pwd)/studio/web"
  if ! command -v npm >/dev/null; then echo "setup: no npm: the studio's page is not built"; return 0; fi
  if [ "$web/node_modules/.package-lock.json" -nt "$web/package-lock.json" ]; then return 0; fi
  echo "setup: npm ci in studio/web"
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
}

# `setup.sh fuzz` also installs clang and its sanitizer/libFuzzer runtimes (for `make fuzz`).
if [ "${1:-}" = "fuzz" ]; then
  PACKAGES+=(clang libclang-rt-14-dev)
fi
# `setup.sh peers` also installs the peer renderer the benchmarks and the glTF export's test
# compare against (Blender with Cycles; bench/cycles_gltf.py), and NumPy, which the bench
# scripts run inside Blender read images with (a Recommends of blender, so not pulled in by
# --no-install-recommends).
if [ "${1:-}" = "peers" ]; then
  PACKAGES+=(blender python3-numpy)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  studio_npm
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null; then SUDO="sudo"; else
    echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1
  fi
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
studio_npm
