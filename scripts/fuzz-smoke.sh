#!/usr/bin/env bash
# Bounded libFuzzer runs over the kept corpora, one per target, SECONDS split between them
# (at least 10 s each). Prints one summary line per target (executions, new coverage, crashes)
# for docs/ROBUSTNESS.md.
# New inputs go to scratch directories so the repository's corpora change only by hand; a
# crash fails the run and leaves its input.
set -euo pipefail
build_dir=${1:?usage: fuzz-smoke.sh BUILD_DIR SECONDS}
seconds=${2:-60}
targets=(grammar_parser http_request extruded_set_decoder terminal_set_decoder scene_config camera_path
    geojson_footprints osm_footprints impostor_file journal_line)
corpora=(grammar_parser http_request extruded_set terminal_set scene_config camera_path
    geojson osm impostor_file journal_line)
share=$(( seconds / ${#targets[@]} ))
[ "$share" -ge 10 ] || share=10
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
summary=()
for i in "${!targets[@]}"; do
    echo "== fuzz: ${targets[$i]} for ${share} s"
    mkdir -p "$work/${targets[$i]}"
    "$build_dir/tests/fuzz/${targets[$i]}_fuzzer" -max_total_time="$share" -max_len=4096 -timeout=10 \
        -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build_dir/${targets[$i]}-" \
        "$work/${targets[$i]}" "tests/fuzz/corpus/${corpora[$i]}" 2>&1 | tee "$work/log" | grep -v '^#[0-9]'
    runs=$(awk '/stat::number_of_executed_units/ {print $NF}' "$work/log")
    new=$(find "$work/${targets[$i]}" -type f | wc -l)
    summary+=("$(printf '%-22s %10s executions in %s s, %s new inputs, 0 crashes' "${targets[$i]}" "$runs" "$share" "$new")")
done
echo "== fuzz summary"
printf '%s\n' "${summary[@]}"
