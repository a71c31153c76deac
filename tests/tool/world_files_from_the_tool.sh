#!/usr/bin/env bash
# Issue 22, defects 6, 7 and 11 and "--force": world-build writes voxray-world.json before
# the manifest and checks the write (a folder with a manifest has it; a failed write
# leaves no manifest); its --json and world-fly's are checked; world-fly reads
# voxray-world.json as untrusted input; a folder holding another world is replaced only
# with --force.
#   world_files_from_the_tool.sh TOOL WORK_DIR
set -euo pipefail
tool=$1 work=$2
source "$(dirname "$0")/expect.sh"
rm -rf "$work" && mkdir -p "$work"
build=(world-build builtin:menger:27 --chunk-bits 4)
fly=(world-fly --frames 1 --width 16 --height 16 --backend cpu)

# voxray-world.json cannot be put in place (a folder of that name): the build fails, naming
# it, and the folder holds no manifest.
mkdir -p "$work/blocked/voxray-world.json/inside"
expect_failure "voxray-world.json cannot be written" "voxray-world.json" "$tool" "${build[@]}" --out "$work/blocked"
[[ ! -e "$work/blocked/world.vxwm" ]] && echo "ok   no manifest after the failed write" || { echo "FAIL: a manifest was written"; failures=$((failures + 1)); }
expect_failure "world-build --json naming a folder" "--json $work: cannot be written" "$tool" "${build[@]}" --out "$work/w0" --json "$work"

"$tool" "${build[@]}" --out "$work/world" > /dev/null 2>&1
expect_failure "world-fly --json to a full disk" "--json /dev/full: writing failed" "$tool" "${fly[@]}" "$work/world" --json /dev/full
expect_failure "another world without --force" "holds another world" "$tool" world-build builtin:menger:81 --chunk-bits 4 --out "$work/world"
"$tool" world-build builtin:menger:81 --chunk-bits 4 --out "$work/world" --force > /dev/null 2>&1 \
    && echo "ok   --force replaces it" || { echo "FAIL: --force did not replace the world"; failures=$((failures + 1)); }

# voxray-world.json as untrusted input.
bad_meta() {  # NAME TEXT: world-fly on a copy of the world whose voxray-world.json is made by the caller first
    expect_failure "$1" "$2" "$tool" "${fly[@]}" "$work/bad"
}
fresh() { rm -rf "$work/bad" && cp -r "$work/world" "$work/bad" && rm -f "$work/bad/voxray-world.json"; }
fresh; echo '{"up_axis": 1.5}' > "$work/bad/voxray-world.json"; bad_meta "a fractional up axis" "voxray-world.json: up_axis 1.5 is not 0, 1 or 2"
fresh; echo '{"up_axis": 3}' > "$work/bad/voxray-world.json"; bad_meta "an up axis past z" "up_axis 3 is not 0, 1 or 2"
fresh; echo '{"palette": null}' > "$work/bad/voxray-world.json"; bad_meta "a null palette" "voxray-world.json: palette is not an array"
fresh; echo '{"palette": [-1]}' > "$work/bad/voxray-world.json"; bad_meta "a negative colour" "palette\[0\] -1 is not an RGBA word"
fresh; echo '{"up_axis": ' > "$work/bad/voxray-world.json"; bad_meta "truncated JSON" "voxray-world.json: not valid JSON"
fresh; mkfifo "$work/bad/voxray-world.json"; bad_meta "a FIFO" "voxray-world.json: not a regular file"
finish
