#!/usr/bin/env bash
# Filtered voxel appearance against the triangles (issue 25): voxray appearance-bench on
# shared meshes at 128^3 and 256^3 (pictures of 128^2 and 256^2, as in the paper), 3 views,
# a light in front and one behind, 2 threads, with --lod (ours re-sampled from ours at twice the
# resolution). Writes docs/bench/appearance_results.jsonl and the strips
# (reference | averages | sggx | six | faithful | ours | ours_lod) into the build folder, then the table
# (docs/bench/appearance_table.md, also in docs/appearance.md) with every metric checked
# against scikit-image's on the strips, and keeps view 0's strips in docs/bench/appearance/.
# Then the same with cast shadows (--shadows) on two scenes at 128^3: appearance_shadows.*.
# Then appearance in a world's LOD chunks (appearance-world-bench): appearance_world.*.
# Then the walk's speed on each structure and CPU backend (appearance-walk-bench): appearance_walk.*.
# About 37 minutes on 2 shared cores.
# Override SCENES (space-separated), RESOLUTIONS, REFERENCE_SIDE (16: 256 samples a pixel),
# SHADOW_SCENES, PARTS ("plain shadows world walk": which of the four to run).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
DATA="${VOXRAY_DATA_DIR:-$ROOT/../shared/data}"
SCENES="${SCENES:-$DATA/mesh/stanford_bunny.ply $DATA/mesh/small_tree/scene.gltf $DATA/mesh/flight_helmet/FlightHelmet.gltf
    $DATA/mesh/kitchen/scene.gltf}"
relative_scenes
all_scenes=("${scenes[@]}")  # the shadows part narrows `scenes`; the walk part takes them all
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
# run_matrix NAME FLAGS RESOLUTIONS SCENE...: docs/bench/NAME_results.jsonl, its strips in the build
# folder, its table (docs/bench/NAME_table.md, also in docs/appearance.md between the
# NAME markers), view 0's strips in docs/bench/NAME/.
run_matrix() {
    local name=$1 flags=$2 resolutions=$3
    shift 3
    local strips results="$OUT/${name}_results.jsonl"
    strips="$(realpath -m --relative-to="$ROOT" "$BUILD_DIR")/${name}_strips"  # relative: recorded in the results
    rm -rf "$results" "$strips" "${OUT:?}/$name"
    mkdir -p "$strips" "$OUT/$name"
    for resolution in $resolutions; do
        for scene in "$@"; do
            echo "== appearance-bench $scene at $resolution $flags"
            part="$OUT/${name}_part.jsonl"  # relative: the header records the command line
            # shellcheck disable=SC2086  # flags: several words
            "$TOOL" appearance-bench "$scene" --resolution "$resolution" --views 3 --threads 2 \
                --reference-side "${REFERENCE_SIDE:-16}" $flags --json "$part" --images "$strips"
            # One results file: the first header, then every run's rows.
            if [ -s "$results" ]; then tail -n +2 "$part" >> "$results"; else cp "$part" "$results"; fi
            rm -f "$part"
        done
    done
    echo "== table ($name)"
    /usr/bin/python3 scripts/appearance_table.py "$results" --strips "$strips" \
        --out "$OUT/${name}_table.md" --doc docs/appearance.md --marker "$name"
    cp "$strips"/*_view0_*.png "$OUT/$name/"
}

# PARTS: which parts (all by default).
if [[ " ${PARTS:-plain shadows world walk} " == *" plain "* ]]; then
    run_matrix appearance "--lod" "${RESOLUTIONS:-128 256}" "${scenes[@]}"
fi
# Cast shadows (--shadows): two scenes at 128^3, the bunny (a solid, self-shadowing) and the
# small tree (foliage, partial shadows), about 4 minutes.
if [[ " ${PARTS:-plain shadows world walk} " == *" shadows "* ]]; then
    SCENES="${SHADOW_SCENES:-$DATA/mesh/stanford_bunny.ply $DATA/mesh/small_tree/scene.gltf}"
    relative_scenes
    run_matrix appearance_shadows "--shadows" "128" "${scenes[@]}"
fi
# A world's LOD chunks with filtered tables against average-colour ones, both against the
# frames of every chunk at LOD 0, at StreamingFactor 2.0: the kitchen at 512^3 in 64^3 chunks
# seen from inside it (a third of the orbit's distance: near chunks at LOD 0, far ones coarse),
# and the bunny at 256^3 in 32^3 chunks from the orbit (every chunk coarse). About 3 minutes.
if [[ " ${PARTS:-plain shadows world walk} " == *" world "* ]]; then
    name=appearance_world results="$OUT/appearance_world_results.jsonl"
    strips="$(realpath -m --relative-to="$ROOT" "$BUILD_DIR")/${name}_strips"
    rm -rf "$results" "$strips" "${OUT:?}/$name"
    mkdir -p "$strips" "$OUT/$name"
    for run in "kitchen/scene.gltf 512 6 0.3" "stanford_bunny.ply 256 5 1"; do
        read -r mesh resolution bits distance <<< "$run"
        scene="$(realpath -m --relative-to="$ROOT" "$DATA/mesh/$mesh")"
        echo "== appearance-world-bench $scene at $resolution, chunks of 2^$bits"
        part="$OUT/${name}_part.jsonl"
        "$TOOL" appearance-world-bench "$scene" --resolution "$resolution" --chunk-bits "$bits" --distance "$distance" \
            --factor 2 --views 3 --size 256 --threads 2 --json "$part" --images "$strips"
        if [ -s "$results" ]; then tail -n +2 "$part" >> "$results"; else cp "$part" "$results"; fi
        rm -f "$part"
    done
    echo "== table ($name)"
    /usr/bin/python3 scripts/appearance_world_table.py "$results" --strips "$strips" --out "$OUT/${name}_table.md" \
        --doc docs/appearance.md
    cp "$strips"/*_view0.png "$OUT/$name/"
fi
# The precompute's and the walk's speed (the targets: 20 us a voxel per thread, the bunny at
# 256^3 in 5 s; 256^2 pixels x 4 rays at 256^3 at 27 fps, 2 threads) on every scene at 256^3:
# the tables timed through the voxels' lists and through Embree's BVH, the walk on each
# structure and CPU backend.
if [[ " ${PARTS:-plain shadows world walk} " == *" walk "* ]]; then
    results="$OUT/appearance_walk_results.jsonl"
    rm -f "$results"
    for scene in "${all_scenes[@]}"; do
        echo "== appearance-walk-bench $scene at 256"
        part="$OUT/appearance_walk_part.jsonl"
        "$TOOL" appearance-walk-bench "$scene" --resolution 256 --threads 2 --runs 5 --json "$part"
        if [ -s "$results" ]; then tail -n +2 "$part" >> "$results"; else cp "$part" "$results"; fi
        rm -f "$part"
    done
    echo "== table (appearance_walk)"
    /usr/bin/python3 scripts/appearance_walk_table.py "$results" --out "$OUT/appearance_walk_table.md" \
        --doc docs/appearance.md
fi
