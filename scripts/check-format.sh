#!/usr/bin/env bash
# Fails listing every C++ file that clang-format would change.
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h' 2>/dev/null || find . -path ./build\* -prune -o \( -name '*.cpp' -o -name '*.h' \) -print)
bad=()
for f in "${files[@]}"; do
    clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if [ ${#bad[@]} -gt 0 ]; then
    echo "clang-format would change: ${bad[*]}"
    echo "fix with: clang-format -i ${bad[*]}"
    exit 1
fi
echo "clang-format: ${#files[@]} files clean"
