#!/usr/bin/env bash
# Installs every Debian 12 package hexlod needs to build, test and fuzz. Idempotent:
# apt-get skips what is already there.
set -euo pipefail

packages=(
    cmake ninja-build g++ pkg-config
    libglm-dev libtbb-dev libzstd-dev
    nlohmann-json3-dev libcli11-dev libspdlog-dev
    libosmium2-dev libprotozero-dev zlib1g-dev libbz2-dev libexpat1-dev
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
if [ ${#missing[@]} -eq 0 ]; then
    echo "install-deps: all ${#packages[@]} packages present"
    exit 0
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
# A fresh machine may have stale package lists; update only when the install fails.
if ! run_as_root apt-get install -y --no-install-recommends "${missing[@]}"; then
    run_as_root apt-get update
    run_as_root apt-get install -y --no-install-recommends "${missing[@]}"
fi
