#!/usr/bin/env bash
# Frame time of the GPU-driven passes, pass by pass, on every backend: flies the camera
# path of `voxray world-fly` through a built world with --passes on cpu, opencl and
# vulkan, and again traced ray by ray (primary and shadow rays), then tabulates the median
# per pass (scripts/world_passes_table.py).
#
#   scripts/world_passes.sh WORLD_DIR [NAME]
# Writes docs/bench/world_passes_<NAME>.jsonl (anew) and world_passes_<NAME>.md; PNG
# frames go to $WORK (default /tmp/voxray-world-passes). FRAMES (8), WIDTH (640),
# HEIGHT (360), FACTOR (2.0) and BACKENDS ("cpu opencl vulkan") may be set.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WORLD="$1"
NAME="${2:-$(basename "$WORLD")}"
WORK="${WORK:-/tmp/voxray-world-passes}"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
out="$ROOT/docs/bench/world_passes_$NAME"
mkdir -p "$ROOT/docs/bench"
rm -f "$out.jsonl"
for backend in ${BACKENDS:-cpu opencl vulkan}; do
    for mode in --passes ""; do  # the passes, then the same path traced ray by ray for comparison
        echo "== world-fly $mode, $backend"
        # shellcheck disable=SC2086
        "$BUILD_DIR/voxray" world-fly "$WORLD" $mode --backend "$backend" --frames "${FRAMES:-8}" \
            --width "${WIDTH:-640}" --height "${HEIGHT:-360}" --factor "${FACTOR:-2.0}" \
            --png-dir "$WORK/$NAME/$backend${mode:+-passes}" --json "$out.jsonl"
    done
done
/usr/bin/python3 "$ROOT/scripts/world_passes_table.py" "$out.jsonl" --out "$out.md"
