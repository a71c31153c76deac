#!/usr/bin/env bash
# The main job: install what is missing, build, render the built-in scene on every
# backend to PNG and print a benchmark table (dense grid and brickmap vs the Embree
# baselines) and the brickmap's editing figures.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
install_packages
configure_and_build

SCENE="${SCENE:-builtin:terrain}"
OUT="$BUILD_DIR/demo"
mkdir -p "$OUT"
VOXRAY="$BUILD_DIR/voxray"

echo "== render $SCENE on every backend"
for backend in cpu cpu-scalar opencl vulkan; do
    for structure in dense brickmap; do
        "$VOXRAY" render "$SCENE" --structure "$structure" --backend "$backend" --width 960 --height 540 \
            --out "$OUT/terrain_${structure}_$backend.png"
    done
done
"$VOXRAY" render "$SCENE" --structure embree-boxes --backend cpu --width 960 --height 540 \
    --out "$OUT/terrain_embree-boxes_cpu.png"

echo "== benchmark: $SCENE, primary and shadow rays, 1280x720, median of 3 runs"
printf '%-14s %-11s %-8s %10s %10s %10s %10s\n' structure backend rays "median" "min" "max" "steps/ray"
for rays in primary shadow; do
    for pair in dense:cpu dense:cpu-scalar dense:opencl dense:vulkan brickmap:cpu brickmap:cpu-scalar \
                brickmap:opencl brickmap:vulkan embree-boxes:cpu embree-quads:cpu; do
        s="${pair%%:*}"; b="${pair##*:}"
        out=$("$VOXRAY" bench "$SCENE" --structure "$s" --backend "$b" --rays "$rays" --width 1280 --height 720 \
            --runs 3 --json "$OUT/bench_${s}_${b}_${rays}.json" 2>/dev/null) || { echo "bench $s/$b/$rays failed:"; echo "$out"; exit 1; }
        # Last line: "median X Mrays/s (min Y, max Z)"; second line holds "steps/ray S".
        read -r median lo hi <<<"$(tail -n1 <<<"$out" | sed -E 's/median ([0-9.]+) Mrays\/s \(min ([0-9.]+), max ([0-9.]+)\)/\1 \2 \3/')"
        steps=$(grep -o 'steps/ray [0-9.]*' <<<"$out" | cut -d' ' -f2)
        printf '%-14s %-11s %-8s %10s %10s %10s %10s\n' "$s" "$b" "$rays" "$median" "$lo" "$hi" "$steps"
    done
done
echo "== brickmap editing: 50 balls of radius 25 per frame, 2 threads, then a one-voxel edit (vulkan)"
"$VOXRAY" bench "$SCENE" --structure brickmap --backend vulkan --edits spheres --threads 2 2>/dev/null | tail -n1
"$VOXRAY" bench "$SCENE" --structure brickmap --backend vulkan --edits voxel 2>/dev/null | tail -n1
echo "== images in $OUT (Mrays/s above; JSON beside them)"
