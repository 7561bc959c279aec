#!/usr/bin/env bash
# ctest gltf.validator: exports a small city (buildings of both city grammars and trees) as
# .glb with EXT_mesh_gpu_instancing, as flattened .glb and as .gltf + .bin, serves it with
# `hexlod serve` for its per-shape meshes, and requires the Khronos glTF validator to report no
# error and no warning on any of them.
#   tests/gltf/validate-export.sh HEXLOD_BINARY
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
configs=$(cd "$here/../../configs" && pwd)
hexlod=$1
if [ ! -f "$here/node_modules/gltf-validator/package.json" ]; then
    echo "gltf-validator is not installed in tests/gltf: run scripts/install-deps.sh (it runs npm ci there)"
    exit 1
fi
tmp=$(mktemp -d)
server_pid=
cleanup() {
    [ -n "$server_pid" ] && kill "$server_pid" 2>/dev/null && wait "$server_pid" 2>/dev/null
    rm -rf "$tmp"
}
trap cleanup EXIT
cat >"$tmp/small.json" <<JSON
{
  "name": "validator-city", "seed": 11, "cell_size": 120,
  "grammars": { "business": { "file": "$configs/grammars/business.grammar" },
                "residential": { "file": "$configs/grammars/residential.grammar" } },
  "buildings": [ { "source": "procedural", "count": 12, "block_size": 80,
    "districts": [ { "grammar": "business", "share": 0.6, "floors": [12, 16], "lot": [30, 30] },
                   { "grammar": "residential", "share": 0.4, "floors": [2, 4], "lot": [16, 20] } ] } ],
  "trees": { "count": 6, "species": "$configs/species.json" }
}
JSON
"$hexlod" export --scene "$tmp/small.json" -o "$tmp/city.glb"
"$hexlod" export --scene "$tmp/small.json" --flatten -o "$tmp/city-flat.glb"
"$hexlod" export --scene "$tmp/small.json" -o "$tmp/city.gltf"
"$hexlod" serve --scene "$tmp/small.json" --port 0 --journal "$tmp/edits.jsonl" --no-impostors \
    --web-root "$tmp/none" >"$tmp/serve.out" 2>"$tmp/serve.err" &
server_pid=$!
for _ in $(seq 300); do
    grep -q "viewer at" "$tmp/serve.out" 2>/dev/null && break
    sleep 0.1
done
url=$(grep -o 'http://127.0.0.1:[0-9]*/' "$tmp/serve.out") || { cat "$tmp/serve.err"; exit 1; }
node "$here/validate.mjs" --max-warnings 0 "$tmp/city.glb" "$tmp/city-flat.glb" "$tmp/city.gltf" \
    --served-meshes "$url"
