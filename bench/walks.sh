#!/usr/bin/env bash
# Headless walkthroughs (`hexlod walk`) of the shipped camera paths, the LOD system against
# everything at LOD4 in the same run, for docs/BENCHMARKS.md ("Walkthroughs"). Prints one
# Markdown row per (scene, path, mode) and keeps every summary in OUT_DIR.
#   bench/walks.sh BUILD_DIR [OUT_DIR]
# FRAMES (default 6) frames per path at 1280x720; REFERENCE_FRAMES (default 4) for the LOD4
# reference, which is run where REFERENCE lists the scene (default: default; the thesis city at
# LOD4 is over 1e9 triangles a frame, minutes per frame on llvmpipe). The default city has no
# disk tier; the thesis city reads and fills its own (configs/thesis-city.json's disk_path), so
# for rows from an empty disk remove out/cache/thesis-city first.
set -euo pipefail
build=${1:?usage: walks.sh BUILD_DIR [OUT_DIR]}
out=${2:-out/bench/walks}
frames=${FRAMES:-6}
reference_frames=${REFERENCE_FRAMES:-4}
reference=${REFERENCE:-default}
mkdir -p "$out"

row() {
    python3 - "$1" "$2" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
lod = d["terminals_per_lod"]
# No cache lookup at all (only extruded cells in view) leaves the hit rate undefined.
hits = "—" if d["cache_hit_rate"] is None else "{:.2f}".format(d["cache_hit_rate"])
print("| {} | {} | {:.0f} | {:.0f} | {:.1f} M | {:.0f} k / {:.0f} k / {:.0f} k | {:.0f} MB | {:.0f} MB | {} |".format(
    sys.argv[2], d["path"], d["median_frame_ms"], d["p95_frame_ms"], d["median_triangles"] / 1e6,
    lod.get("lod4", 0) / 1e3, lod.get("lod3", 0) / 1e3, lod.get("lod2", 0) / 1e3,
    d["peak_resident_bytes"] / 1e6, d["peak_rss_bytes"] / 1e6, hits))
PY
}

echo "| mode | path | median frame ms | p95 frame ms | median triangles | LOD4 / LOD3 / LOD2 terminals | peak resident | peak RSS | cache hit rate |"
echo "|---|---|---|---|---|---|---|---|---|"
for scene in default thesis; do
    config=configs/$scene.json
    [ "$scene" = thesis ] && config=configs/thesis-city.json
    for path in street rooftop overview; do
        name=$scene-$path
        "$build/apps/hexlod" walk --scene "$config" --path "configs/paths/$name.json" --frames "$frames" \
            --width 1280 --height 720 --impostor-cache out/impostors --json >"$out/$name.json" 2>"$out/$name.log"
        row "$out/$name.json" lod
        if [[ " $reference " == *" $scene "* ]]; then
            "$build/apps/hexlod" walk --scene "$config" --path "configs/paths/$name.json" \
                --frames "$reference_frames" --width 1280 --height 720 --impostor-cache out/impostors --reference \
                --json >"$out/$name-lod4.json" 2>"$out/$name-lod4.log"
            row "$out/$name-lod4.json" "all LOD4"
        fi
    done
done
