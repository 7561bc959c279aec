#!/usr/bin/env bash
# Service benchmarks (docs/BENCHMARKS.md, "Service"): wrk on loopback against `hexlod serve`
# on a scene (default configs/default.json), then edit latency and bytes per cell with
# serve_bench. Writes OUT/serve_load.json and OUT/*.txt (wrk's own reports).
#   bench/serve_load.sh BUILD_DIR OUT_DIR [SCENE]
# Environment: DURATION (seconds per wrk run, 10), CONNECTIONS ("1 16 128"), REPEAT (edit runs, 30),
# SERVE_OPTIONS (more `hexlod serve` options, e.g. "--cache-mb 256 --payload-cache-mb 128").
set -euo pipefail
build=${1:?usage: serve_load.sh BUILD_DIR OUT_DIR [SCENE]}
out=${2:?usage: serve_load.sh BUILD_DIR OUT_DIR [SCENE]}
scene=${3:-configs/default.json}
duration=${DURATION:-10}
connections=${CONNECTIONS:-1 16 128}
repeat=${REPEAT:-30}
mkdir -p "$out"
source "$(dirname "$0")/server_process.sh"

# No rate limit: the load generator is one client address.
# shellcheck disable=SC2086 # SERVE_OPTIONS is a list of options
"$build/apps/hexlod" serve --scene "$scene" --port 0 --journal "$work/edits.jsonl" --rate-limit 0 \
    --web-root "$work/none" ${SERVE_OPTIONS:-} > "$work/stdout" 2> "$out/serve_stderr.txt" &
server_pid=$!
for _ in $(seq 600); do
    grep -q "viewer at" "$work/stdout" 2>/dev/null && break
    sleep 0.1
done
url=$(grep -o 'http://127.0.0.1:[0-9]*/' "$work/stdout")
port=$(echo "$url" | grep -o '[0-9]*/$' | tr -d /)
echo "serving $scene at $url (pid $server_pid)"

rss_mb() { awk '/VmRSS/ {printf "%.1f", $2 / 1024}' "/proc/$server_pid/status"; }
metric() { curl -s "${url}metrics" | awk -v name="$1" '$1 == name {print $2}'; }

# Every terminal-set URL of the scene, and one hot one (a residential batch).
curl -s "${url}api/v1/cells" | python3 -c '
import json, sys
index = json.load(sys.stdin)
for cell in index["cells"]:
    for batch in cell["batches"]:
        print(batch["terminal_set"])' > "$work/paths"
hot=$(grep -m1 '/1/' "$work/paths" || head -1 "$work/paths")
echo "$(wc -l < "$work/paths") terminal-set URLs; hot one: $hot"
rss_idle=$(rss_mb)

# Warm every batch (this is the whole city's expansion), so that the load runs measure cached requests.
start=$(date +%s.%N)
xargs -P 2 -I{} curl -s -o /dev/null "${url%/}{}" < "$work/paths"
warm_seconds=$(python3 -c "print(round($(date +%s.%N) - $start, 2))")
rss_warm=$(rss_mb)
echo "warmed in ${warm_seconds}s; RSS ${rss_idle} MB idle, ${rss_warm} MB warm"

results="[]"
for mode in hot all; do
    for c in $connections; do
        threads=$(( c < 2 ? 1 : 2 ))
        report="$out/wrk_${mode}_c${c}.txt"
        peak="$work/peak"
        echo 0 > "$peak"
        ( while kill -0 "$server_pid" 2>/dev/null; do r=$(rss_mb); awk -v r="$r" '{ if (r > $1) print r; else print $1 }' "$peak" > "$peak.n"; mv "$peak.n" "$peak"; sleep 0.5; done ) &
        sampler=$!
        if [ "$mode" = hot ]; then
            wrk -t"$threads" -c"$c" -d"${duration}s" --latency "${url%/}$hot" > "$report"
        else
            HEXLOD_PATHS="$work/paths" wrk -t"$threads" -c"$c" -d"${duration}s" --latency -s bench/wrk_paths.lua "$url" > "$report"
        fi
        kill "$sampler"; wait "$sampler" 2>/dev/null || true
        rps=$(awk '/Requests\/sec/ {print $2}' "$report")
        p50=$(awk '$1 == "50%" {print $2}' "$report")
        p99=$(awk '$1 == "99%" {print $2}' "$report")
        non2xx=$(awk '/Non-2xx/ {print $5}' "$report")
        echo "$mode c=$c: $rps req/s, p50 $p50, p99 $p99, peak RSS $(cat "$peak") MB ${non2xx:+, non-2xx $non2xx}"
        results=$(echo "$results" | python3 -c "
import json, sys
r = json.load(sys.stdin)
r.append({'urls': '$mode', 'connections': $c, 'requests_per_second': float('$rps'), 'p50': '$p50', 'p99': '$p99',
          'peak_rss_mb': float('$(cat "$peak")'), 'non_2xx': int('${non2xx:-0}')})
print(json.dumps(r))")
    done
done

budget=$(curl -s "${url}metrics" | awk '/^hexlod_cache_budget_bytes|^hexlod_bulk_pool_limit_bytes/ {s += $2} END {printf "%.1f", s / 1048576}')
decoded=$(metric 'hexlod_cache_bytes{tier="decoded"}')
terminal=$(metric 'hexlod_cache_bytes{tier="terminal_payload"}')
extruded=$(metric 'hexlod_cache_bytes{tier="extruded_payload"}')
"$build/bench/serve_bench" edits --port "$port" --repeat "$repeat" > "$work/edits.json"
"$build/bench/serve_bench" sizes --port "$port" > "$work/sizes.json"
python3 - "$out/serve_load.json" <<PY
import json, sys
out = {
    "scene": "$scene", "warm_seconds": float("$warm_seconds"), "rss_idle_mb": float("$rss_idle"),
    "rss_warm_mb": float("$rss_warm"), "memory_budget_mb": float("$budget"),
    "cache_bytes": {"decoded": float("$decoded"), "terminal_payload": float("$terminal"),
                    "extruded_payload": float("$extruded")},
    "wrk": json.loads('$results'),
    "edits": json.load(open("$work/edits.json")),
    "sizes": json.load(open("$work/sizes.json")),
}
json.dump(out, open(sys.argv[1], "w"), indent=2)
print(json.dumps({k: out[k] for k in ("memory_budget_mb", "cache_bytes", "edits", "sizes")}, indent=2))
PY
