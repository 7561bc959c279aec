#!/usr/bin/env bash
# Bounded libFuzzer runs over the kept corpora, one per target, SECONDS split between them.
# New inputs go to scratch directories so the repository's corpora change only by hand; a
# crash fails the run and leaves its input.
set -euo pipefail
build_dir=${1:?usage: fuzz-smoke.sh BUILD_DIR SECONDS}
seconds=${2:-60}
targets=(grammar_parser http_request extruded_set_decoder)
corpora=(grammar_parser http_request extruded_set)
share=$(( seconds / ${#targets[@]} ))
[ "$share" -ge 10 ] || share=10
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for i in "${!targets[@]}"; do
    echo "== fuzz: ${targets[$i]} for ${share} s"
    mkdir -p "$work/${targets[$i]}"
    "$build_dir/tests/fuzz/${targets[$i]}_fuzzer" -max_total_time="$share" -max_len=4096 -timeout=10 \
        -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build_dir/${targets[$i]}-" \
        "$work/${targets[$i]}" "tests/fuzz/corpus/${corpora[$i]}"
done
