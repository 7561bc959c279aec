#!/usr/bin/env bash
# README command 2: every check CI runs, in order. The Release suite runs last so that
# the output ends in CTest's summary.
#   1. ASan+UBSan build, unit tests
#   2. libFuzzer smoke runs of the ten targets in tests/fuzz (FUZZ_SECONDS in all, default 60)
#   3. Release build, the whole suite (unit, extreme, command line, service, glTF validator,
#      web decoders, the browser test, clang-format check)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

scripts/install-deps.sh

echo "== sanitizers: ASan + UBSan unit tests"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DHEXLOD_SANITIZE=ON -DHEXLOD_BUILD_BENCH=OFF
cmake --build build-asan
ctest --test-dir build-asan -L unit --output-on-failure -j "$jobs"

echo "== fuzz: smoke runs"
CXX=clang++-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHEXLOD_FUZZ=ON
cmake --build build-fuzz
scripts/fuzz-smoke.sh build-fuzz "${FUZZ_SECONDS:-60}"

echo "== release: the whole suite"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHEXLOD_WERROR=ON
cmake --build build
ctest --test-dir build --output-on-failure -j "$jobs"
