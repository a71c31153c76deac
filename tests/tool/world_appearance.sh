#!/usr/bin/env bash
# world-build --appearance: a coloured glTF mesh's world and its appearance tables in one
# step, one table file for every chunk at every LOD (the build's own table of chunks counts
# them), resumed when run again, and walked by world-fly --appearance; --appearance from a
# scene without triangles, with --shard, or naming no one folder is
# refused, before the world is built.
#   world_appearance.sh TOOL DATA_DIR WORK_DIR
set -euo pipefail
tool=$1 data=$2 work=$3
source "$(dirname "$0")/expect.sh"
rm -rf "$work" && mkdir -p "$work"
build=(world-build "$data/mesh/small_tree/scene.gltf" --resolution 48 --chunk-bits 4)

"$tool" "${build[@]}" --appearance ours --out "$work/world" > "$work/build.txt" 2>&1 || { cat "$work/build.txt"; exit 1; }
# The build's table: "  LOD  chunks  voxels ..." rows; the tables: appearance/ours/lodN/X_Y_Z.vxap.
lods=0
while read -r lod chunks _; do
    tables=$(find "$work/world/appearance/ours/lod$lod" -name '*.vxap' 2>/dev/null | wc -l || true)
    if [[ $tables -eq $chunks ]]; then echo "ok   LOD $lod: $tables tables for $chunks chunks"
    else echo "FAIL LOD $lod: $tables tables for $chunks chunks"; failures=$((failures + 1)); fi
    lods=$((lods + 1))
done < <(grep -E '^ +[0-9]+ +[0-9]+ +[0-9]+ ' "$work/build.txt")
[[ $lods -ge 2 ]] && echo "ok   $lods LODs" || { echo "FAIL: $lods LODs in the build's table"; failures=$((failures + 1)); }
grep -E "appearance tables ours: $lods LODs" "$work/build.txt" || { echo "FAIL: no tables line"; failures=$((failures + 1)); }

# The same build again resumes: every chunk's table kept. With one LOD 0 table gone, that one
# is made again, the same bytes.
all=$(find "$work/world/appearance/ours" -name '*.vxap' | wc -l)
one=$(find "$work/world/appearance/ours/lod0" -name '*.vxap' | sort | head -n 1)
sum=$(md5sum "$one" | cut -d' ' -f1)
"$tool" "${build[@]}" --appearance ours --out "$work/world" > "$work/again.txt" 2>&1 \
    || { cat "$work/again.txt"; exit 1; }
grep -E "appearance tables ours: $lods LODs, 0 voxels .* $all chunks' tables kept" "$work/again.txt" \
    && echo "ok   run again: all $all tables kept" || { echo "FAIL: run again"; failures=$((failures + 1)); }
rm "$one"
"$tool" "${build[@]}" --appearance ours --out "$work/world" > "$work/resumed.txt" 2>&1 \
    || { cat "$work/resumed.txt"; exit 1; }
kept=$(sed -nE "s/.* ([0-9]+) chunks' tables kept.*/\1/p" "$work/resumed.txt")
[[ -f "$one" && "$(md5sum "$one" | cut -d' ' -f1)" == "$sum" && $kept -lt $all && $kept -ge $((all - lods)) ]] \
    && echo "ok   one table gone: made again, the same bytes ($kept of $all kept)" \
    || { echo "FAIL: one table gone ($kept of $all kept)"; failures=$((failures + 1)); }

# world-fly --appearance: each frame's LOD cut walked through the tables, beside the traced
# frame: a picture and a JSON record a frame, voxels blended where the flight sees the tree.
fly=(world-fly "$work/world" --frames 2 --width 64 --height 40)
"$tool" "${fly[@]}" --appearance ours --png-dir "$work/fly" --json "$work/fly.jsonl" > "$work/fly.txt" 2>&1 \
    || { cat "$work/fly.txt"; exit 1; }
pictures=$(find "$work/fly" -name 'appearance_*.png' | wc -l)
blended=$(grep -cE '"appearance":\{[^}]*"visits_per_ray":[0-9.e-]*[1-9]' "$work/fly.jsonl" || true)
[[ $pictures -eq 2 && $blended -ge 1 ]] && grep -qE "appearance ours: [0-9]+ chunks in the cut" "$work/fly.txt" \
    && echo "ok   world-fly --appearance: $pictures pictures, $blended frames with voxels blended" \
    || { echo "FAIL world-fly --appearance: $pictures pictures, $blended frames blended"; failures=$((failures + 1)); }
expect_failure "world-fly --appearance of a set the world lacks" "appearance/none does not exist" \
    "$tool" "${fly[@]}" --appearance none
expect_failure "world-fly --appearance with --passes" "--appearance walks the traced frame's rays" \
    "$tool" "${fly[@]}" --appearance ours --passes

expect_failure "--appearance without triangles" "--appearance: tables are made from a mesh" \
    "$tool" world-build builtin:menger:27 --chunk-bits 4 --appearance ours --out "$work/menger"
expect_failure "--appearance with --shard" "--appearance: .* not from --shard" \
    "$tool" "${build[@]}" --appearance ours --shard 0/2 --out "$work/shard"
expect_failure "--appearance naming no one folder" "the set's name \"a/b\" must be one folder name" \
    "$tool" "${build[@]}" --appearance a/b --out "$work/slash"
[[ ! -e "$work/slash/world.vxwm" ]] && echo "ok   refused before the world was built" \
    || { echo "FAIL: a world was built before the set's name was refused"; failures=$((failures + 1)); }
finish
