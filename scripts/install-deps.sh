#!/usr/bin/env bash
# Installs every Debian 12 package hexlod needs to build, test and fuzz, and the npm packages
# of the web viewer (web/: three.js, fzstd, esbuild, playwright-core) and of the test tools (the
# Khronos glTF validator in tests/gltf). Idempotent: apt-get skips what is already there, npm ci
# runs only where a package-lock.json is newer than its install. The browser tests drive
# Debian's chromium; playwright-core never downloads a browser of its own.
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
    chromium
)

run_as_root() {
    if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node and npm build the viewer and run the glTF validator; Debian's packages serve where none is installed.
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

npm_ci() {
    local folder="$1" what="$2"
    if [ ! -f "$folder/node_modules/.package-lock.json" ] || [ "$folder/package-lock.json" -nt "$folder/node_modules/.package-lock.json" ]; then
        echo "install-deps: npm ci in $what"
        (cd "$folder" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund)
    else
        echo "install-deps: $what npm packages present"
    fi
}
root="$(dirname "$0")/.."
npm_ci "$root/tests/gltf" "tests/gltf (gltf-validator)"
npm_ci "$root/web" "web (three, fzstd, esbuild, playwright-core)"
