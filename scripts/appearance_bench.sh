#!/usr/bin/env bash
# Filtered voxel appearance against the triangles (issue 25): voxray appearance-bench on
# shared meshes at 128^3 and 256^3 (pictures of 128^2 and 256^2, as in the paper), 3 views,
# a light in front and one behind, 2 threads, with --lod (ours re-sampled from ours at twice the
# resolution). Writes docs/bench/appearance_results.jsonl and the strips
# (reference | averages | sggx | six | faithful | ours | ours_lod) into the build folder, then the table
# (docs/bench/appearance_table.md, also in docs/appearance.md) with every metric checked
# against scikit-image's on the strips, and keeps view 0's strips in docs/bench/appearance/.
# About 25 minutes on 2 shared cores.
# Override SCENES (space-separated), RESOLUTIONS, REFERENCE_SIDE (16: 256 samples a pixel).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
DATA="${VOXRAY_DATA_DIR:-$ROOT/../shared/data}"
SCENES="${SCENES:-$DATA/mesh/stanford_bunny.ply $DATA/mesh/small_tree/scene.gltf $DATA/mesh/flight_helmet/FlightHelmet.gltf
    $DATA/mesh/kitchen/scene.gltf}"
relative_scenes
install_packages
/usr/bin/python3 -c "import skimage" 2>/dev/null || {
    echo "== installing python3-skimage (the metrics' check)"
    sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
    $sudo apt-get install -y -qq --no-install-recommends python3-skimage >/dev/null
}
cd "$ROOT"
TOOL="$(realpath -m --relative-to="$ROOT" "$BUILD_DIR")/voxray" OUT=docs/bench
echo "== configure and build the tool ($BUILD_DIR)"
cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release ${CMAKE_EXTRA:-} >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)" --target voxray_tool
STRIPS="$(realpath -m --relative-to="$ROOT" "$BUILD_DIR")/appearance_strips"  # relative: recorded in the results
rm -rf "$OUT/appearance_results.jsonl" "$STRIPS" "$OUT/appearance"
mkdir -p "$STRIPS" "$OUT/appearance"
for resolution in ${RESOLUTIONS:-128 256}; do
    for scene in "${scenes[@]}"; do
        echo "== appearance-bench $scene at $resolution"
        part="$OUT/appearance_part.jsonl"  # relative: the header records the command line
        "$TOOL" appearance-bench "$scene" --resolution "$resolution" --views 3 --threads 2 \
            --reference-side "${REFERENCE_SIDE:-16}" --lod --json "$part" --images "$STRIPS"
        # One results file: the first header, then every run's rows.
        if [ -s "$OUT/appearance_results.jsonl" ]; then tail -n +2 "$part" >> "$OUT/appearance_results.jsonl"
        else cp "$part" "$OUT/appearance_results.jsonl"; fi
        rm -f "$part"
    done
done
echo "== table"
/usr/bin/python3 scripts/appearance_table.py "$OUT/appearance_results.jsonl" --strips "$STRIPS" \
    --out "$OUT/appearance_table.md" --doc docs/appearance.md
cp "$STRIPS"/*_view0_*.png "$OUT/appearance/"
