#!/usr/bin/env bash
# Scene files (docs/entities.md) through the tool: `check SCENE.json --frames` on every world
# kind x backend x way of finding candidates ends in "0 mismatches"; `render --frames`
# writes one image a frame; bad scene files fail naming the file and the key.
# Usage: entity_scenes.sh TOOL DATA_DIR WORK_DIR
set -euo pipefail
tool=$1 data=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
source "$here/expect.sh"

python3 "$here/../../scripts/make_entity_scene.py" "$work/herd.json" --world builtin:terrain:128 --count 400 \
    --extent 128 128 40 --data "$data" > /dev/null
out=$("$tool" check "$work/herd.json" --frames 4 --rays 4000 2>/dev/null) || { echo "FAIL check: exit $?"; echo "$out"; failures=$((failures + 1)); }
echo "$out" | tail -n 10
last=$(tail -n 1 <<< "$out")
if [[ $last == "0 mismatches" ]] && grep -qE "^naadf +vulkan +bvh +[1-9][0-9]* +0$" <<< "$out" &&
   grep -qE "^naadf +vulkan +chunk-lists +[1-9][0-9]* +0$" <<< "$out"; then echo "ok   check: $last"
else echo "FAIL check: last line '$last'"; failures=$((failures + 1)); fi

# Models cut from a region of a file, one without distance fields: every combination exact.
cat > "$work/cut.json" <<'JSON'
{"world": "builtin:terrain:64",
 "models": {"hill": {"file": "builtin:terrain:128", "region": [20, 20, 0, 60, 60, 40]},
            "plain": {"file": "builtin:terrain:128", "region": [0, 0, 0, 30, 30, 20], "fields": "none"}},
 "instances": [{"model": "hill", "position": [20, 30, 30], "rotation": [0.9, 0.1, 0.3, 0.2], "motion": {"spin": [0, 0, 1, 0.3]}},
               {"model": "plain", "position": [40, 20, 25], "motion": {"linear": [1, 0.5, 0]}},
               {"model": "hill", "position": [50, 50, 20], "scale": 0.5}]}
JSON
out=$("$tool" check "$work/cut.json" --frames 3 --rays 2000 2>/dev/null) || { echo "FAIL check cut: exit $?"; echo "$out"; failures=$((failures + 1)); }
last=$(tail -n 1 <<< "$out")
if [[ $last == "0 mismatches" ]] && grep -qE "^dense +opencl +bvh +[1-9][0-9]* +0$" <<< "$out"; then echo "ok   check cut regions: $last"
else echo "FAIL check cut regions: last line '$last'"; echo "$out" | tail -n 5; failures=$((failures + 1)); fi

"$tool" render "$work/herd.json" --frames 2 --structure naadf --backend cpu --width 160 --height 90 \
    --out "$work/frame.png" > /dev/null 2>&1 || { echo "FAIL render: exit $?"; failures=$((failures + 1)); }
for f in frame_000.png frame_001.png; do
    [[ -s $work/$f ]] && echo "ok   render wrote $f" || { echo "FAIL render: no $f"; failures=$((failures + 1)); }
done

bad() {  # bad NAME JSON: a scene file holding JSON
    printf '%s\n' "$2" > "$work/$1.json"
    echo "$work/$1.json"
}
model='"models": {"m": {"file": "builtin:sphere30"}}'
expect_failure zero_rotation 'bad_rotation.json: instances\[0\]: entity pose: rotation \(w 0.*cannot be normalised' \
    "$tool" check "$(bad bad_rotation "{\"world\": \"builtin:sphere30\", $model, \"instances\": [{\"model\": \"m\", \"position\": [0, 0, 0], \"rotation\": [0, 0, 0, 0]}]}")"
expect_failure unknown_model 'instances\[0\].model: no model named "deer"' \
    "$tool" check "$(bad bad_model "{\"world\": \"builtin:sphere30\", $model, \"instances\": [{\"model\": \"deer\", \"position\": [0, 0, 0]}]}")"
expect_failure short_position 'instances\[0\].position: expected 3 numbers' \
    "$tool" render "$(bad bad_position "{\"world\": \"builtin:sphere30\", $model, \"instances\": [{\"model\": \"m\", \"position\": [0, 0]}]}")" --out "$work/x.png"
expect_failure huge_position 'instances\[0\].position: a number is not a finite float \(1e\+300\)' \
    "$tool" check "$(bad huge_position "{\"world\": \"builtin:sphere30\", $model, \"instances\": [{\"model\": \"m\", \"position\": [1e300, 0, 0]}]}")"
expect_failure unknown_motion 'instances\[0\].motion.wobble: unknown motion' \
    "$tool" check "$(bad bad_motion "{\"world\": \"builtin:sphere30\", $model, \"instances\": [{\"model\": \"m\", \"position\": [0, 0, 0], \"motion\": {\"wobble\": 1}}]}")"
expect_failure no_world 'no_world.json: world: missing, or not a string' \
    "$tool" check "$(bad no_world "{$model, \"instances\": []}")"
expect_failure not_json 'not_json.json: not JSON' "$tool" check "$(bad not_json "{\"world\": ")"
expect_failure missing_model_file 'error: .*nonexistent.vox' \
    "$tool" check "$(bad missing_file "{\"world\": \"builtin:sphere30\", \"models\": {\"m\": {\"file\": \"nonexistent.vox\"}}, \"instances\": []}")"
expect_failure unknown_fields 'bad_fields.json: models.m.fields: "maybe" is neither "bricks" nor "none"' \
    "$tool" check "$(bad bad_fields "{\"world\": \"builtin:sphere30\", \"models\": {\"m\": {\"file\": \"builtin:sphere30\", \"fields\": \"maybe\"}}, \"instances\": []}")"
expect_failure bad_region 'bad_region.json: models.m.region: expected whole voxel coordinates within \+-2\^30 \(0.5\)' \
    "$tool" check "$(bad bad_region "{\"world\": \"builtin:sphere30\", \"models\": {\"m\": {\"file\": \"builtin:sphere30\", \"region\": [0.5, 0, 0, 8, 8, 8]}}, \"instances\": []}")"
expect_failure empty_region 'models.m.region: region model: the region is 0 x 8 x 8 voxels' \
    "$tool" check "$(bad empty_region "{\"world\": \"builtin:sphere30\", \"models\": {\"m\": {\"file\": \"builtin:sphere30\", \"region\": [4, 0, 0, 4, 8, 8]}}, \"instances\": []}")"
expect_failure frames_need_a_scene_file '--frames 3: only a scene file' "$tool" check builtin:sphere30 --frames 3
finish
