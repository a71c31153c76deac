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
OUT="$ROOT/docs/bench"
for s in $SCENES; do
    [[ "$s" == builtin:* || -f "$s" ]] || { echo "scene $s not found (set VOXRAY_DATA_DIR)"; exit 1; }
done

install_packages
# From the repository's root with relative paths, so that the command the results file
# records names no directory of this machine (docs must not: tests/docs).
cd "$ROOT"
rel() { realpath -m --relative-to="$ROOT" "$1"; }
scenes=()
for s in $SCENES; do
    if [[ "$s" == builtin:* ]]; then scenes+=("$s"); else scenes+=("$(rel "$s")"); fi
done
TOOL="$(rel "$BUILD_DIR")/voxray" OUT="$(rel "$OUT")"
echo "== configure and build the tool ($BUILD_DIR)"
cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DVOXRAY_REQUIRE_ALL_BACKENDS=ON ${CMAKE_EXTRA:-} >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)" --target voxray_tool
mkdir -p "$OUT"
echo "== matrix: $WIDTH x $HEIGHT, $RUNS runs"
# bench exits 1 when a row disagrees or fails; the table shows which, so go on.
"$TOOL" bench "${scenes[@]}" --resolution "$RESOLUTION" --width "$WIDTH" --height "$HEIGHT" --runs "$RUNS" \
    --out "$OUT/results.jsonl" || echo "== some rows disagree or failed: see the mismatches column"
/usr/bin/python3 scripts/plot_bench.py "$OUT/results.jsonl" --out "$OUT"
