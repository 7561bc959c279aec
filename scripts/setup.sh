#!/usr/bin/env bash
# README command 1: install the dependencies, build hexlod in Release with warnings as
# errors, and run its main job on the embedded default scene (configs/default.json: a
# procedural city of 10,000 buildings and 20,000 trees): expand every batch and print the
# statistics.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHEXLOD_WERROR=ON
cmake --build build
build/apps/hexlod expand --scene configs/default.json --stats
