#!/usr/bin/env bash
# The chunk mesher's benchmark: voxray mesh-bench on the one-chunk anchors (sphere r30 and
# the checkerboard of the blocky-meshing literature, a 4-material terrain, 50 % noise) and on
# shared scenes, 2 threads for the throughput column. Writes docs/bench/mesh_results.jsonl,
# then the table (docs/bench/mesh_table.md, also in docs/meshing.md), the plot of quads and
# overdraw per level, and a picture of each level of detail (docs/bench/mesh_*.png).
# About 2 minutes on 2 shared cores. Override SCENES (space-separated), SECONDS_PER_RUN.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
DATA="${VOXRAY_DATA_DIR:-$ROOT/../shared/data}"
SCENES="${SCENES:-builtin:sphere30 builtin:terrain64 builtin:checker builtin:noise50 $DATA/vox/minecraft_nether.vox
    $DATA/vox/flyingapts.vox $DATA/vox/mmmm_scene_church1.vox}"
relative_scenes
install_packages
cd "$ROOT"
TOOL="$(realpath -m --relative-to="$ROOT" "$BUILD_DIR")/voxray" OUT=docs/bench
echo "== configure and build the tool ($BUILD_DIR)"
cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release ${CMAKE_EXTRA:-} >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)" --target voxray_tool
echo "== mesh-bench"
"$TOOL" mesh-bench "${scenes[@]}" --threads 2 --seconds "${SECONDS_PER_RUN:-0.5}" --json "$OUT/mesh_results.jsonl"
echo "== pictures of each level of detail (builtin:terrain64)"
pictures=$(mktemp -d)
for level in 0 1 2 3 4 5 6; do
    "$TOOL" mesh builtin:terrain64 --level "$level" --ply "$pictures/terrain64_$level.ply" > /dev/null 2>&1
done
echo "== minecraft_nether drawn by the Vulkan raster path: level 0, and POP levels of detail at LOD bias 4"
for bias in 64 4; do
    "$TOOL" mesh "$DATA/vox/minecraft_nether.vox" --png "$OUT/mesh_raster_bias$bias.png" --lod-bias "$bias" \
        --width 640 --height 360 2>/dev/null | tail -n 1
done
/usr/bin/python3 scripts/mesh_table.py "$OUT/mesh_results.jsonl" --plies "$pictures" --out "$OUT" --doc docs/meshing.md
rm -rf "$pictures"
