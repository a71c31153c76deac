#!/usr/bin/env bash
# The open-world study behind the README's tables: builds a world from a real mesh chunk
# by chunk (voxray world-build), flies the same camera path through it with every chunk at
# LOD 0 (the reference) and with LOD selection at StreamingFactor 1.2, 1.6, 2.0 and 2.4,
# and tabulates resident memory against the world on disk and SSIM against the reference
# (scripts/world_table.py, scikit-image).
#
#   scripts/world_study.sh [MESH] [RESOLUTION] [BACKEND]
#     defaults: ../shared/data/mesh/dabrovic_sponza.obj 4096 cpu
# Writes docs/bench/world_build.jsonl and world_fly_<scene>_<res>.jsonl (appending), the
# table to docs/bench/world_table_<scene>_<res>.md; the world and frames go to $WORK
# (default /tmp/voxray-world-study).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DATA="${VOXRAY_DATA_DIR:-$ROOT/../shared/data}"
MESH="${1:-$DATA/mesh/dabrovic_sponza.obj}"
RES="${2:-4096}"
BACKEND="${3:-cpu}"
WORK="${WORK:-/tmp/voxray-world-study}"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
VOXRAY="$BUILD_DIR/voxray"
FRAMES="${FRAMES:-24}"
SIZE=(--width "${WIDTH:-480}" --height "${HEIGHT:-270}")
/usr/bin/python3 -c "import skimage" 2>/dev/null || {
    echo "== installing python3-skimage (SSIM)"
    sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
    $sudo apt-get install -y -qq --no-install-recommends python3-skimage >/dev/null
}
name="$(basename "${MESH%.*}")_$RES"
world="$WORK/$name"
mkdir -p "$WORK" "$ROOT/docs/bench"
echo "== world-build $MESH at $RES -> $world"
"$VOXRAY" world-build "$MESH" --resolution "$RES" --max-cell-tests 68719476736 --colours --out "$world" --json "$ROOT/docs/bench/world_build.jsonl"
fly="$ROOT/docs/bench/world_fly_$name.jsonl"
rm -f "$fly"
rm -rf "$WORK/frames_$name"
echo "== world-fly, every chunk at LOD 0 (the reference)"
"$VOXRAY" world-fly "$world" --lod0 --frames "$FRAMES" "${SIZE[@]}" --backend "$BACKEND" \
    --png-dir "$WORK/frames_$name/lod0" --json "$fly"
for factor in 1.2 1.6 2.0 2.4; do
    echo "== world-fly, StreamingFactor $factor"
    "$VOXRAY" world-fly "$world" --factor "$factor" --frames "$FRAMES" "${SIZE[@]}" --backend "$BACKEND" \
        --png-dir "$WORK/frames_$name/factor_$factor" --json "$fly"
done
/usr/bin/python3 "$ROOT/scripts/world_table.py" "$fly" --frames "$WORK/frames_$name" --out "$ROOT/docs/bench/world_table_$name.md"
