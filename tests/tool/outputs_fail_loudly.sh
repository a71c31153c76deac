#!/usr/bin/env bash
# Issue 22, defects 7 and 13 and "--out x.jpg": an output that cannot be written is an
# error naming it, never exit 0 with an empty file; images are written in the format
# their name asks for; a ray file is checked (kind, size, memory) before it is read.
#   outputs_fail_loudly.sh TOOL WORK_DIR DATA_DIR_OF_THIS_FOLDER
set -euo pipefail
tool=$1 work=$2 data=$3
source "$(dirname "$0")/expect.sh"
rm -rf "$work" && mkdir -p "$work"
ln -s /dev/full "$work/full.png"
small=(--width 16 --height 16)
bench=(bench builtin:menger:27 --structures dense --backends cpu --rays primary --width 8 --height 8 --runs 1)

expect_failure "render to a full disk" "full.png: writing failed" "$tool" render builtin:menger:27 "${small[@]}" --out "$work/full.png"
expect_failure "bench --out to a full disk" "--out /dev/full: writing failed" "$tool" "${bench[@]}" --out /dev/full
expect_failure "check --json to a full disk" "--json /dev/full: writing failed" "$tool" check builtin:menger:27 --rays 100 --backends cpu --json /dev/full
expect_failure "info --json to a full disk" "--json /dev/full: writing failed" "$tool" info builtin:menger:27 --json /dev/full
expect_failure "bench --out naming a folder" "--out $work: cannot be written" "$tool" "${bench[@]}" --out "$work"
expect_failure "an image format nobody asked for" "unknown image format '.gif' \(known: .png, .jpg, .jpeg, .bmp, .tga\)" \
    "$tool" render builtin:menger:27 "${small[@]}" --out "$work/x.gif"
[[ ! -e "$work/x.gif" ]] || { echo "FAIL: x.gif was written"; failures=$((failures + 1)); }

# The format follows the name: JPEG starts FF D8, BMP "BM", PNG 89 "PNG".
for ext in jpg bmp png; do
    "$tool" render builtin:menger:27 "${small[@]}" --out "$work/x.$ext" > /dev/null 2>&1
done
magic() { head -c "$2" "$1" | od -An -tx1 | tr -d ' \n'; }
[[ $(magic "$work/x.jpg" 2) == ffd8 ]] && echo "ok   x.jpg is a JPEG" || { echo "FAIL: x.jpg starts $(magic "$work/x.jpg" 4)"; failures=$((failures + 1)); }
[[ $(magic "$work/x.bmp" 2) == 424d ]] && echo "ok   x.bmp is a BMP" || { echo "FAIL: x.bmp starts $(magic "$work/x.bmp" 4)"; failures=$((failures + 1)); }
[[ $(magic "$work/x.png" 4) == 89504e47 ]] && echo "ok   x.png is a PNG" || { echo "FAIL: x.png starts $(magic "$work/x.png" 4)"; failures=$((failures + 1)); }

# A ray file that claims 2^29 rays (16 GiB) in a sparse file: refused by its header and the
# memory it would take, before anything is allocated (ulimit -v makes the limit the same
# on every machine).
printf 'VXRAYS01\x20\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x20\x00\x00\x00\x00' > "$work/sparse.vxrays"
truncate -s $((24 + 32 * (1 << 29))) "$work/sparse.vxrays"
expect_failure "a sparse ray file claiming 16 GiB" "--ray-file $work/sparse.vxrays \(536870912 rays\) needs [0-9.]+ GiB but only" \
    sh -c "ulimit -v 4000000 && exec \"\$0\" \"\$@\"" "$tool" "${bench[@]}" --ray-file "$work/sparse.vxrays"
mkfifo "$work/fifo.vxrays"
expect_failure "a FIFO as the ray file" "fifo.vxrays: not a regular file" "$tool" "${bench[@]}" --ray-file "$work/fifo.vxrays"

# Two scenes of one file name would write the same ray files.
mkdir -p "$work/a" "$work/b"
cp "$data/empty.vox" "$work/a/scene.vox" && cp "$data/empty.vox" "$work/b/scene.vox"
expect_failure "two scenes, one ray file name" "would both write scene.vox.\*.vxrays" \
    "$tool" bench "$work/a/scene.vox" "$work/b/scene.vox" --write-rays "$work/rays" --runs 1
finish
