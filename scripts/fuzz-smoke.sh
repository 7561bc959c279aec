#!/usr/bin/env bash
# Bounded libFuzzer run over the kept corpus. New inputs go to a scratch directory so the
# repository's corpus changes only by hand; a crash fails the run and leaves its input.
set -euo pipefail
build_dir=${1:?usage: fuzz-smoke.sh BUILD_DIR SECONDS}
seconds=${2:-60}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build_dir/tests/fuzz/grammar_parser_fuzzer" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build_dir/" \
    "$work" tests/fuzz/corpus/grammar_parser
