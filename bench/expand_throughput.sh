#!/usr/bin/env bash
# Terminal-set generation throughput: residential and business over 10,000 procedural
# buildings, on 1 thread and on all threads, median of REPEAT runs each (one process per
# configuration, so both thread counts see the same input). Writes JSON and CSV.
#   bench/expand_throughput.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
out=${2:-out/bench}
repeat=${REPEAT:-7}
buildings=${BUILDINGS:-10000}
mkdir -p "$out"
all=$(nproc)
csv="$out/expand_throughput.csv"
json="$out/expand_throughput.json"
echo "grammar,threads,buildings,terminals,seconds_median,cold_seconds,terminals_per_second,bytes_per_terminal,geometry_to_terminal_ratio" >"$csv"
echo "[" >"$json"
first=1
for grammar in residential business; do
    for threads in 1 "$all"; do
        result=$("$build/apps/hexlod" expand --grammar "configs/grammars/$grammar.grammar" --demo "$buildings" \
            --threads "$threads" --repeat "$repeat" --json)
        [ $first -eq 1 ] || echo "," >>"$json"
        first=0
        echo "$result" >>"$json"
        # Pull the figures out of the JSON without extra tools: one "key": value per line.
        get() { echo "$result" | sed -n "s/^  \"$1\": \\([^,]*\\),\\{0,1\\}$/\\1/p"; }
        echo "$grammar,$threads,$buildings,$(get terminals),$(get seconds),$(get cold_seconds),$(get terminals_per_second),$(get bytes_per_terminal),$(get geometry_to_terminal_ratio)" >>"$csv"
    done
done
echo "]" >>"$json"
cat "$csv"
echo "wrote $csv and $json"
