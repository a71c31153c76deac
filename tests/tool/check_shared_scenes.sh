#!/usr/bin/env bash
# voxray check on every shared .vox scene, a voxelized mesh and a coloured glTF, all structures x backends,
# and once more after random edits.
# Skips (exit 0 with a note) only when the data folder is absent.
set -euo pipefail
tool="$1"; data="${VOXRAY_DATA_DIR:-$2}"
if [ ! -d "$data/vox" ]; then echo "no data folder at $data: skipped"; exit 0; fi
status=0
for scene in "$data"/vox/*.vox "$data/mesh/stanford_bunny.ply" "$data/mesh/kitchen/scene.gltf"; do
    line=$("$tool" check "$scene" --resolution 256 --rays 100000 --structures dense,brickmap,naadf,svdag,svdag-colours,world,world-16,embree-boxes,nanovdb-hdda \
        --backends cpu,cpu-scalar,opencl,vulkan 2>/dev/null | tail -n1) || status=1
    echo "$(basename "$scene"): $line"
done
line=$("$tool" check "$data/vox/minecraft_tree.vox" --rays 100000 --edits 200 --structures dense,brickmap \
    --backends cpu,cpu-scalar,opencl,vulkan 2>/dev/null | tail -n1) || status=1
echo "minecraft_tree.vox after 200 edits: $line"
exit $status
