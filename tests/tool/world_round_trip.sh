#!/usr/bin/env bash
# voxray world-build then world-fly end to end: a tiled built-in scene built chunk by chunk,
# built again (every chunk resumed), flown on every backend (exit 0 only when no chunk
# failed to load), traced and drawn by the GPU-driven passes (the same PNGs on every
# backend), a world's shown chunks meshed and drawn by the raster path beside the traced
# frames (SSIM against them), and a clear error for a folder that holds no world.
set -euo pipefail
tool="$1"; work="$2"
rm -rf "$work"
"$tool" world-build builtin:terrain:96 --tile 2 2 1 --chunk-bits 5 --colours --out "$work/world" | tee "$work.build.txt"
grep -q "LODs 0\.\." "$work.build.txt"
"$tool" world-build builtin:terrain:96 --tile 2 2 1 --chunk-bits 5 --colours --out "$work/world" > "$work.again.txt"
# Every chunk of the second build was kept from the first (the resumed column equals the chunks column).
awk '$1 ~ /^[0-9]+$/ && NF == 6 && $2 != $6 { bad = 1 } END { exit bad }' "$work.again.txt"
for backend in cpu cpu-scalar opencl vulkan; do
    "$tool" world-fly "$work/world" --backend "$backend" --frames 3 --width 64 --height 36 --factor 2.0 \
        --png-dir "$work/frames_$backend" | tee "$work.fly.txt"
    grep -q "peak resident share" "$work.fly.txt"
    [ -f "$work/frames_$backend/frame_002.png" ]
    "$tool" world-fly "$work/world" --backend "$backend" --frames 3 --width 64 --height 36 --factor 2.0 \
        --passes --png-dir "$work/passes_$backend" | tee "$work.passes.txt"
    grep -q "march ms" "$work.passes.txt"
    # The passes draw the same frames on every backend, to the byte.
    for f in 0 1 2; do cmp "$work/passes_cpu/frame_00$f.png" "$work/passes_$backend/frame_00$f.png"; done
done
# The raster path beside the traced frames, on a world whose camera path stays in open air
# (a Menger sponge): at level 0 everywhere the two agree but for voxel edges and shadows.
"$tool" world-build builtin:menger:81 --tile 2 1 1 --chunk-bits 5 --colours --out "$work/sponge" > /dev/null
for bias in 64 2; do
    "$tool" world-fly "$work/sponge" --backend cpu --frames 2 --width 96 --height 54 --raster --lod-bias $bias \
        --png-dir "$work/raster_$bias" --json "$work/raster_$bias.jsonl" | tee "$work.raster.txt"
    grep -q "SSIM" "$work.raster.txt"
    [ -f "$work/raster_$bias/raster_and_traced_001.png" ]
done
python3 - "$work/raster_64.jsonl" "$work/raster_2.jsonl" <<'PY'
import json, sys
fine, coarse = ([json.loads(l)["raster"] for l in open(p)] for p in sys.argv[1:])
for f, c in zip(fine, coarse):
    assert f["rays_starting_in_a_voxel"] == 0 and f["ssim"] >= 0.98, f
    assert 0 < c["quads"] < f["quads"], (f, c)
print("raster frames beside the traced ones: SSIM %s at level 0, %s at LOD bias 2"
      % ([round(f["ssim"], 4) for f in fine], [round(c["ssim"], 4) for c in coarse]))
PY
if "$tool" world-fly "$work/world" --raster --passes 2> "$work.err.txt"; then echo "--raster with --passes ran"; exit 1; fi
grep -q -- "--raster compares with the traced frame" "$work.err.txt"
mkdir -p "$work/empty"
if "$tool" world-fly "$work/empty" 2> "$work.err.txt"; then echo "no error for a folder without a world"; exit 1; fi
grep -q "world.vxwm" "$work.err.txt"
echo "world round trip: ok"
