#!/usr/bin/env bash
# Start-up of `hexlod serve` (docs/ROBUSTNESS.md, "What a scene does not need"): seconds from
# launch until it serves, resident and peak memory at that moment, and what it says it
# started or left out, for the default city, a trees-only scene and a one-building scene:
# without impostors, with a cold impostor store (the bake) and with the store warm. Median of
# REPEAT (default 3) starts each.
#   bench/startup.sh BUILD_DIR [OUT_DIR]
set -euo pipefail
build=${1:?usage: startup.sh BUILD_DIR [OUT_DIR]}
out=${2:-out/bench}
repeat=${REPEAT:-3}
mkdir -p "$out"
source "$(dirname "$0")/server_process.sh"

# One start: prints "seconds rss_mb peak_mb" and leaves the notes in $work/notes.txt.
start_once() {
    local scene=$1 store=$2
    shift 2
    rm -f "$work/edits.jsonl" "$work/stdout"
    local began
    began=$(date +%s.%N)
    "$build/apps/hexlod" serve --scene "$scene" --port 0 --journal "$work/edits.jsonl" \
        --web-root "$work/none" --impostor-store "$store" "$@" >"$work/stdout" 2>"$work/stderr" &
    server_pid=$!
    until grep -q "viewer at" "$work/stdout" 2>/dev/null; do
        kill -0 "$server_pid" 2>/dev/null || { cat "$work/stderr"; exit 1; }
        sleep 0.02
    done
    local ended
    ended=$(date +%s.%N)
    local rss peak
    rss=$(awk '/VmRSS/ {printf "%.0f", $2 / 1024}' "/proc/$server_pid/status")
    peak=$(awk '/VmHWM/ {printf "%.0f", $2 / 1024}' "/proc/$server_pid/status")
    grep -o 'http://127.0.0.1:[0-9]*/' "$work/stdout" >"$work/url"
    curl -s "$(cat "$work/url")api/v1/scene" |
        python3 -c 'import json, sys; print("\n".join(json.load(sys.stdin)["notes"]))' >"$work/notes.txt"
    kill "$server_pid"
    wait "$server_pid" 2>/dev/null || true
    server_pid=
    echo "$(awk -v a="$began" -v b="$ended" 'BEGIN {print b - a}') $rss $peak"
}

median() { sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

echo "| scene | impostors | start s | RSS MB | peak MB | notes |" | tee "$out/startup.md"
echo "|---|---|---|---|---|---|" | tee -a "$out/startup.md"
for scene in configs/default.json bench/scenes/trees-only.json bench/scenes/one-building.json; do
    for mode in off cold warm; do
        : >"$work/runs"
        for _ in $(seq "$repeat"); do
            case $mode in
                off) start_once "$scene" "$work/store" --no-impostors ;;
                cold) rm -rf "$work/store"; start_once "$scene" "$work/store" ;;
                warm) start_once "$scene" "$work/store" ;;
            esac >>"$work/runs"
        done
        seconds=$(awk '{print $1}' "$work/runs" | median)
        rss=$(awk '{print $2}' "$work/runs" | median)
        peak=$(awk '{print $3}' "$work/runs" | median)
        notes=$(grep -E '^(vegetation|impostors|terminal meshes|cells)' "$work/notes.txt" | paste -sd ';' | sed 's/|/\//g')
        printf '| %s | %s | %.2f | %s | %s | %s |\n' "$(basename "$scene" .json)" "$mode" "$seconds" "$rss" "$peak" \
            "$notes" | tee -a "$out/startup.md"
    done
done
