#!/usr/bin/env bash
# README command 1: install the dependencies, build hexlod in Release with warnings as
# errors, and run its main job on the embedded default: the expansion of the default demo
# city (10,000 procedural buildings, residential grammar) with its statistics.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHEXLOD_WERROR=ON
cmake --build build
build/apps/hexlod expand --grammar configs/grammars/residential.grammar --demo 10000 --stats
