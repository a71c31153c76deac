#!/usr/bin/env bash
# The standard benchmark matrix on the shared scenes: every registered structure and
# baseline x every backend x primary, secondary and shadow rays, validated against the
# dense grid while measuring. Writes docs/bench/results.jsonl, regenerates the plots
# (docs/bench/*.png) and the README's benchmark table from it.
#
# Sized for a small machine: 960 x 540 primary rays, 1 warm-up + 3 timed runs a row, meshes
# voxelized at 512; about 5 minutes on 2 shared cores (483 rows). Override with WIDTH, HEIGHT, RUNS,
# RESOLUTION, SCENES (space-separated).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
DATA="${VOXRAY_DATA_DIR:-$ROOT/../shared/data}"
WIDTH="${WIDTH:-960}" HEIGHT="${HEIGHT:-540}" RUNS="${RUNS:-3}" RESOLUTION="${RESOLUTION:-512}"
SCENES="${SCENES:-$DATA/vox/flyingapts.vox $DATA/vox/minecraft_nether.vox $DATA/vox/mmmm_scene_church1.vox
    $DATA/vox/minecraft_tree.vox $DATA/mesh/stanford_bunny.ply $DATA/mesh/dabrovic_sponza.obj builtin:terrain}"
relative_scenes
install_packages
cd "$ROOT"
TOOL="$(realpath -m --relative-to="$ROOT" "$BUILD_DIR")/voxray" OUT=docs/bench
echo "== configure and build the tool ($BUILD_DIR)"
cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DVOXRAY_REQUIRE_ALL_BACKENDS=ON ${CMAKE_EXTRA:-} >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)" --target voxray_tool
mkdir -p "$OUT"
echo "== matrix: $WIDTH x $HEIGHT, $RUNS runs"
# bench exits 1 when a row disagrees or fails; the table shows which, so go on.
"$TOOL" bench "${scenes[@]}" --resolution "$RESOLUTION" --width "$WIDTH" --height "$HEIGHT" --runs "$RUNS" \
    --out "$OUT/results.jsonl" || echo "== some rows disagree or failed: see the mismatches column"
/usr/bin/python3 scripts/plot_bench.py "$OUT/results.jsonl" --out "$OUT"
