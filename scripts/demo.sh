#!/usr/bin/env bash
# The main job: install what is missing, build, render the built-in scene on every
# backend to PNG, run the benchmark matrix (every structure and baseline: Embree, NanoVDB)
# into a results file and print its table, the editing figures of brickmap and NAADF, and
# an open world built chunk by chunk and streamed along a camera path, traced ray by ray
# and drawn by the GPU-driven passes; then chunk meshes with POP levels of detail, coloured
# meshes, filtered appearance against the triangles and moving entities.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
install_packages
configure_and_build voxray_tool  # only what the demo runs: the tests are scripts/test.sh's

SCENE="${SCENE:-builtin:terrain}"
OUT="$BUILD_DIR/demo"
mkdir -p "$OUT"
VOXRAY="$BUILD_DIR/voxray"
status=0

echo "== render $SCENE on every backend"
for backend in cpu cpu-scalar opencl vulkan; do
    for structure in dense brickmap naadf svdag; do
        "$VOXRAY" render "$SCENE" --structure "$structure" --backend "$backend" --width 960 --height 540 \
            --out "$OUT/terrain_${structure}_$backend.png"
    done
done
"$VOXRAY" render "$SCENE" --structure embree-boxes --backend cpu --width 960 --height 540 \
    --out "$OUT/terrain_embree-boxes_cpu.png"

echo "== benchmark matrix: $SCENE, every structure and baseline x backend x ray set, 960x540, median of 3 runs"
# One results file (JSON lines); the table below is printed from it, not scraped from text.
"$VOXRAY" bench "$SCENE" --width 960 --height 540 --runs 3 --out "$OUT/results.jsonl" >/dev/null 2>"$OUT/bench.log" ||
    { echo "bench: some rows disagree or failed (see below and $OUT/bench.log)"; status=1; }
/usr/bin/python3 "$ROOT/scripts/plot_bench.py" "$OUT/results.jsonl" --out "$OUT" >/dev/null
cat "$OUT/table.md"
for structure in brickmap naadf; do
    echo "== $structure editing: 50 balls of radius 25 per frame, 2 threads, then a one-voxel edit (vulkan)"
    "$VOXRAY" bench "$SCENE" --structure "$structure" --backend vulkan --edits spheres --threads 2 2>/dev/null | tail -n1
    "$VOXRAY" bench "$SCENE" --structure "$structure" --backend vulkan --edits voxel 2>/dev/null | tail -n1
done
echo "== open world: $SCENE tiled 4 x 4 x 1, built chunk by chunk (128^3 chunks), then streamed along a camera path (vulkan)"
"$VOXRAY" world-build "$SCENE" --tile 4 4 1 --chunk-bits 7 --colours --out "$OUT/world" | tail -n1
"$VOXRAY" world-fly "$OUT/world" --backend vulkan --frames 8 --factor 2.0 --png-dir "$OUT/world_frames"
echo "== the same path drawn by the GPU-driven passes (chunk and tile selection, visibility buffer, Hi-Z, colour resolve), ms per pass (vulkan)"
"$VOXRAY" world-fly "$OUT/world" --backend vulkan --frames 8 --factor 2.0 --passes --png-dir "$OUT/world_pass_frames"
echo "== the same world's shown chunks meshed at their LOD and drawn by the Vulkan raster path (POP inside chunks), beside the traced frames"
"$VOXRAY" world-fly "$OUT/world" --backend vulkan --frames 2 --factor 2.0 --raster --width 640 --height 360 \
    --png-dir "$OUT/world_raster_frames" | grep "raster:"
echo "== chunk meshes with POP levels of detail: the one-chunk anchors and $SCENE, then face sets and crack tests"
"$VOXRAY" mesh-bench builtin:sphere30 builtin:terrain64 builtin:checker "$SCENE" --seconds 0.2 --kernel-runs 1 \
    --json "$OUT/mesh.jsonl" 2>/dev/null
"$VOXRAY" mesh builtin:terrain64 --level 2 --gltf "$OUT/terrain64_level2.glb" --ply "$OUT/terrain64_level2.ply" 2>/dev/null | tail -n 8
echo "== $SCENE's chunk meshes drawn by the Vulkan raster path: level 0, then POP levels of detail (LOD bias 5)"
"$VOXRAY" mesh "$SCENE" --png "$OUT/mesh_raster_level0.png" --width 960 --height 540 2>/dev/null | tail -n 1
"$VOXRAY" mesh "$SCENE" --png "$OUT/mesh_raster_bias5.png" --lod-bias 5 --width 960 --height 540 2>/dev/null | tail -n 1
"$VOXRAY" check "$SCENE" --mesh --mesh-views 1000 2>/dev/null | tail -n 2 || status=1
echo "== coloured meshes (glTF with textures and cut-out leaves) voxelized with the colours they cover"
DATA="${VOXRAY_DATA_DIR:-$ROOT/../shared/data}"
"$VOXRAY" render "$DATA/mesh/flight_helmet/FlightHelmet.gltf" --resolution 384 --view 1 --width 960 --height 540 \
    --out "$OUT/coloured_helmet.png" 2>/dev/null
"$VOXRAY" render "$DATA/mesh/realistic_trees/scene.gltf" --resolution 512 --width 960 --height 540 \
    --out "$OUT/coloured_trees.png" 2>/dev/null
echo "== filtered appearance: the small tree at 128^3 against its triangles (Embree, 256 samples a pixel), averages and ours"
"$VOXRAY" appearance-bench "$DATA/mesh/small_tree/scene.gltf" --resolution 128 --views 1 --threads 2 \
    --images "$OUT/appearance" 2>/dev/null || status=1
echo "== filtered appearance in a world's LOD chunks: the bunny at 128^3 in 16^3 chunks, ours against average-colour chunks, both against all LOD 0"
"$VOXRAY" appearance-world-bench "$DATA/mesh/stanford_bunny.ply" --resolution 128 --chunk-bits 4 --views 1 --size 128 \
    --threads 2 --images "$OUT/appearance" 2>/dev/null || status=1
echo "== moving entities: 3,000 deer and trees (shared models) over builtin:terrain:512, 6 frames of their motion (naadf, vulkan), then checked"
/usr/bin/python3 "$ROOT/scripts/make_entity_scene.py" "$OUT/herd.json" --world builtin:terrain:512 --count 3000 \
    --extent 512 512 131 --data "$DATA"
mkdir -p "$OUT/entities"
"$VOXRAY" render "$OUT/herd.json" --frames 6 --structure naadf --backend vulkan --width 960 --height 540 \
    --out "$OUT/entities/frame.png" 2>/dev/null
"$VOXRAY" check "$OUT/herd.json" --frames 2 --rays 20000 --backends cpu,vulkan 2>/dev/null | tail -n 5 || status=1
echo "== images (entities/frame_*.png, coloured_*.png, appearance/*.png (world strips too)), results.jsonl, mesh.jsonl, terrain64_level2.glb, mesh_raster_*.png, world_raster_frames/raster_and_traced_*.png, plots (mrays.png, speed_vs_memory.png, steps.png) and table.md in $OUT"
exit ${status}
