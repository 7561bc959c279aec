#!/usr/bin/env bash
# Installs every Debian 12 package hexlod needs to build, test and fuzz, and the npm packages
# of the test tools (the Khronos glTF validator in tests/gltf). Idempotent: apt-get skips what
# is already there, npm ci runs only when tests/gltf/package-lock.json is newer than the install.
set -euo pipefail

packages=(
    cmake ninja-build g++ pkg-config
    libglm-dev libtbb-dev libzstd-dev
    nlohmann-json3-dev libcli11-dev libspdlog-dev
    libosmium2-dev libprotozero-dev zlib1g-dev libbz2-dev libexpat1-dev
    libegl-dev libegl-mesa0 libgl-dev libgl1-mesa-dri libosmesa6-dev
    libopenexr-dev libstb-dev libflann-dev liblz4-dev libtinygltf-dev
    libboost-dev
    googletest libgtest-dev libbenchmark-dev
    clang-14 libclang-rt-14-dev clang-format
    wrk curl python3
)

run_as_root() {
    if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node and npm run the glTF validator; Debian's packages serve where none is installed.
command -v npm >/dev/null 2>&1 || missing+=(nodejs npm)
if [ ${#missing[@]} -eq 0 ]; then
    echo "install-deps: all ${#packages[@]} packages present"
else
    echo "install-deps: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    # A fresh machine may have stale package lists; update only when the install fails.
    if ! run_as_root apt-get install -y --no-install-recommends "${missing[@]}"; then
        run_as_root apt-get update
        run_as_root apt-get install -y --no-install-recommends "${missing[@]}"
    fi
fi

gltf="$(dirname "$0")/../tests/gltf"
if [ ! -f "$gltf/node_modules/.package-lock.json" ] || [ "$gltf/package-lock.json" -nt "$gltf/node_modules/.package-lock.json" ]; then
    echo "install-deps: npm ci in tests/gltf (gltf-validator)"
    (cd "$gltf" && npm ci --no-audit --no-fund)
else
    echo "install-deps: tests/gltf npm packages present"
fi
