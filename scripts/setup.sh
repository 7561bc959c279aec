#!/usr/bin/env bash
# README command 1: install the dependencies, build hexlod in Release with warnings as
# errors, and run its main job on the embedded default scene (configs/default.json: a
# procedural city of 10,000 buildings and 20,000 trees): serve it over HTTP with
# `hexlod serve`, which prints the viewer's URL and runs until Ctrl-C (it blocks).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHEXLOD_WERROR=ON
cmake --build build
exec build/apps/hexlod serve --scene configs/default.json
